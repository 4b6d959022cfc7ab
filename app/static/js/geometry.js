// The deformed wing's sections, placed exactly as the solver does (solver/geometry.py, the study's
// make_wing): the leading edge is R_y(twist) [-x_ea c, y, 0] + [0, 0, heave], and the chord is
// rotated by the twist about the section's local span axis. Points are [x, y, z] in metres, x aft,
// y right, z up.

/** Leading and trailing edges of the right half-wing's N sections. */
export function sections({ y, chord, elasticAxis, heave, twist, scale = 1 }) {
  const n = y.length;
  const ea = Array.isArray(elasticAxis) ? elasticAxis : y.map(() => elasticAxis);
  const theta = twist.map((t) => (scale * t * Math.PI) / 180);
  const le = y.map((yi, i) => {
    const offset = chord[i] * ea[i];
    return [-offset * Math.cos(theta[i]), yi, offset * Math.sin(theta[i]) + scale * heave[i]];
  });
  // Local span axis: the normalised y-z projection of the LE-to-LE segments, averaged at interior
  // stations, one-sided at the root and tip.
  const segments = [];
  for (let i = 0; i < n - 1; i++) {
    const dy = le[i + 1][1] - le[i][1];
    const dz = le[i + 1][2] - le[i][2];
    const length = Math.hypot(dy, dz);
    segments.push([dy / length, dz / length]);
  }
  const axis = y.map((_, i) => {
    if (i === 0) return segments[0];
    if (i === n - 1) return segments[n - 2];
    const my = (segments[i - 1][0] + segments[i][0]) / 2;
    const mz = (segments[i - 1][1] + segments[i][1]) / 2;
    const length = Math.hypot(my, mz);
    return [my / length, mz / length];
  });
  const te = le.map((p, i) => {
    const [ay, az] = axis[i];
    const s = Math.sin(theta[i]);
    const direction = [Math.cos(theta[i]), az * s, -ay * s];
    return p.map((value, k) => value + chord[i] * direction[k]);
  });
  return { le, te };
}

const VIEWS = {
  top: ([x, y]) => ({ x: y, y: x }), // span across, chord down the page (reversed axis)
  front: ([, y, z]) => ({ x: y, y: z }), // seen from ahead
  side: ([x, , z]) => ({ x, y: z }), // seen from the right tip
};

const GAP = { x: null, y: null };

/** Wireframe of both halves in one view ("top", "front", "side"): the leading edge, the trailing
 * edge and every section's chord line, as one point list with null gaps between strokes. */
export function wireframe({ le, te }, view) {
  const project = VIEWS[view];
  const mirror = ([x, y, z]) => [x, -y, z];
  const edge = (points) => [...points.slice(1).reverse().map(mirror), ...points].map(project);
  const out = [...edge(le), GAP, ...edge(te), GAP];
  for (let i = 0; i < le.length; i++) {
    out.push(project(le[i]), project(te[i]), GAP);
    if (i > 0) out.push(project(mirror(le[i])), project(mirror(te[i])), GAP);
  }
  return out;
}
