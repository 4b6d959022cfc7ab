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

/** The point of `points` (one per station, at the stations' `y`) at span position `yq`, linearly
 * interpolated, and the unit span direction of the interval it lies in. */
function alongSpan(points, yq) {
  const y = points.map((p) => p[1]);
  let i = 0;
  while (i < y.length - 2 && yq > y[i + 1]) i++;
  const t = Math.min(1, Math.max(0, (yq - y[i]) / (y[i + 1] - y[i])));
  const point = points[i].map((v, k) => v + t * (points[i + 1][k] - v));
  const step = points[i + 1].map((v, k) => v - points[i][k]);
  const length = Math.hypot(...step);
  return { point, span: step.map((v) => v / length) };
}

const cross = ([a, b, c], [d, e, f]) => [b * f - c * e, c * d - a * f, a * e - b * d];
const unit = (v) => {
  const length = Math.hypot(...v);
  return v.map((x) => x / length);
};

/**
 * Outlines of the control surfaces, deflected, on the sections `{le, te}` of the right half-wing
 * (sections()), mirrored to the left (an aileron's the other way there), in one view: each
 * surface's hinge line and its deflected trailing edge (the part aft of the hinge rotated about
 * the hinge line by its deflection, trailing edge down positive), closed, as one point list with
 * null gaps between strokes. Surfaces with a missing number are left out.
 */
export function surfaceOutlines({ le, te }, surfaces, view) {
  const project = VIEWS[view];
  const y = le.map((p) => p[1]);
  const semispan = y.at(-1);
  const out = [];
  for (const surface of surfaces ?? []) {
    const { start, end, hinge, deflection = 0, kind, extent_unit: extentUnit } = surface;
    if (![start, end, hinge, deflection].every(Number.isFinite) || !(end > start) || y.length < 2) continue;
    const [y0, y1] = extentUnit === "m" ? [start, end] : [start * semispan, end * semispan];
    const ys = [y0, ...y.filter((v) => v > y0 && v < y1), y1];
    for (const side of [1, -1]) {
      const delta = ((side < 0 && kind === "aileron" ? -1 : 1) * deflection * Math.PI) / 180;
      const hingeLine = [];
      const trailing = [];
      for (const yq of ys) {
        const { point: l, span } = alongSpan(le, yq);
        const { point: t } = alongSpan(te, yq);
        const chordVector = t.map((v, k) => v - l[k]);
        const chord = Math.hypot(...chordVector);
        const d = chordVector.map((v) => v / chord);
        const up = unit(cross(d, span)); // the section's normal, upward
        const h = l.map((v, k) => v + hinge * chord * d[k]);
        const e = h.map((v, k) => v + (1 - hinge) * chord * (Math.cos(delta) * d[k] - Math.sin(delta) * up[k]));
        const mirror = ([px, py, pz]) => (side > 0 ? [px, py, pz] : [px, -py, pz]);
        hingeLine.push(project(mirror(h)));
        trailing.push(project(mirror(e)));
      }
      out.push(...hingeLine, ...trailing.reverse(), hingeLine[0], GAP);
    }
  }
  return out;
}
