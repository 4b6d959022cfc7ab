"""The unsteady lattice's gust responses from its transfer functions
(`solver.gusts.lattice_model`), as Nastran's SOL 146 computes them (MSC Nastran Aeroelastic
Analysis User's Guide, ch. 7; Hoblit, Gust Loads on Aircraft, 1988, ch. 2 and 3):

- a discrete gust (the 1-cos gusts of `solver.gusts.profiles`, or a profile of your own): the
  outputs' Fourier transform is the transfer function times the gust's, y = IFFT(H(omega_n)
  FFT(u)) on a period T, u the gust velocity sampled where it meets the foremost leading edge
  (each strip's delay is in H). The discrete transform is periodic: T must outlast the
  response, else its tail folds onto its start. T starts at twice the histories' span
  (`solver.gusts.discrete.time_grid`'s end: the gusts, the delays and two periods of the
  slowest mode) plus, free, eight time constants of the rigid plunge's decay (q a S / (V W /
  2g), its quasi-steady lift damping); it doubles while the last tenth of the period holds more
  than `_TAIL` of any output's peak. The samples are `time_grid`'s (a 100th of the shortest
  gust, an 8th of the fastest mode it excites); H is evaluated up to `_HARMONICS` times the
  shortest gust's frequency and twice the highest mode's (zero beyond: the 1-cos gust's
  spectrum falls as omega^-3);
- continuous turbulence: A-bar^2 = integral_0^inf |H(omega)|^2 Phi(omega) d omega, as
  `solver.gusts.turbulence` (its grid and trapezoidal rule), with the lattice's H.

Peaks are read as `solver.gusts.discrete.peaks` reads them (the parabola through the largest
sample and its neighbours).
"""

from __future__ import annotations

import math
from collections.abc import Callable

import numpy as np
import scipy.fft

from solver.gusts.discrete import DiscreteResponse
from solver.gusts.lattice_model import LatticeGustModel
from solver.gusts.profiles import TURBULENCE_SCALE, one_minus_cosine, von_karman
from solver.inputs.atmosphere import STANDARD_GRAVITY
from solver.inputs.flight import dynamic_pressure

__all__ = [
    "HARMONICS",
    "lattice_a_bar",
    "lattice_discrete_responses",
    "lattice_profile_response",
    "resolved_frequency",
    "top_frequency",
]

# H is evaluated up to this many times the shortest 1-cos gust's frequency 2 pi V / (2 H).
HARMONICS = 20.0
_PER_GUST = 100
_PER_PERIOD = 8
_QUASI_STATIC = 10.0
# The period doubles while the response's last tenth exceeds this share of its peak.
_TAIL = 5e-3
_DOUBLINGS = 4
_MOST_SAMPLES = 1 << 20  # the period stops doubling at this many samples
_BAND = 16.0  # gradients sharing one period lie within this factor
_DECAYS = 8.0  # plunge time constants in the period
_CHUNK = 256  # frequencies evaluated at once (the strips' gust tables are interpolated)
_POINTS = 1500  # A-bar's frequencies, as solver.gusts.turbulence


def top_frequency(velocity: float, shortest_gradient: float) -> float:
    """[rad/s] the highest frequency the 1-cos gusts of gradients from `shortest_gradient` [m]
    need at `velocity` [m/s] (`HARMONICS` times the shortest's)."""
    return HARMONICS * math.pi * velocity / shortest_gradient


def transfer(model: LatticeGustModel, omega: np.ndarray) -> np.ndarray:
    """(n_out, F) complex `model.response` at `omega` (F,) [rad/s], in chunks."""
    parts = [model.response(omega[i : i + _CHUNK]) for i in range(0, max(omega.size, 1), _CHUNK)]
    return np.concatenate(parts, axis=1)


def _plunge_rate(model: LatticeGustModel) -> float:
    """[1/s] the free aircraft's plunge decay rate with quasi-steady lift (0 clamped)."""
    if model.clamped:
        return 0.0
    q = dynamic_pressure(model.density, model.velocity)
    return (
        q * model.lift_slope * model.area / model.velocity / (model.weight / (2 * STANDARD_GRAVITY))
    )


def _respond(
    model: LatticeGustModel,
    shape: Callable[[np.ndarray], np.ndarray],
    span: float,
    step: float,
    cut: float,
    stretch: float = 1.0,
) -> tuple[np.ndarray, list[np.ndarray]]:
    """The time (T,) [s] and each input's outputs (n_out, T) on the period found (module
    docstring), `stretch` times longer; `shape(time)` gives the inputs' samples (G, T) [m/s]
    at the time samples."""
    rate = _plunge_rate(model)
    period = stretch * (2 * span + (_DECAYS / rate if rate > 0 else 0.0))
    outputs: list[np.ndarray] = []
    time = np.zeros(0)
    for _ in range(_DOUBLINGS + 1):
        count = scipy.fft.next_fast_len(math.ceil(period / step), real=True)
        h = period / count
        time = np.arange(count) * h
        omega = 2 * math.pi * np.arange(count // 2 + 1) / period
        kept = omega <= cut
        response = np.zeros((3 * model.wing.n_stations + 3, omega.size), dtype=complex)
        response[:, kept] = transfer(model, omega[kept])
        samples = shape(time)
        spectra = scipy.fft.rfft(samples, axis=-1)  # (G, F)
        outputs = [
            scipy.fft.irfft(response * spectrum[None, :], n=count, axis=-1) for spectrum in spectra
        ]
        # The response's tail, short of the period's end (where the band limit's precursor of
        # t < 0 folds), against each quantity's peak along the span.
        tail = (time >= 0.8 * period) & (time <= 0.95 * period)
        settled = all(_settled(model, y, tail) for y in outputs)
        if settled or 2 * count > _MOST_SAMPLES:
            break
        period *= 2
    return time, outputs


def _settled(model: LatticeGustModel, outputs: np.ndarray, tail: np.ndarray) -> bool:
    """Whether every quantity's largest value in `tail` is below `_TAIL` of its peak (the
    stations' shears together, bending moments together, torques together)."""
    n = model.wing.n_stations
    groups = [
        slice(0, n),
        slice(n, 2 * n),
        slice(2 * n, 3 * n),
        *(slice(i, i + 1) for i in range(3 * n, 3 * n + 3)),
    ]
    size = np.abs(outputs)
    return all(float(size[g][:, tail].max()) <= _TAIL * float(size[g].max()) for g in groups)


def _span(model: LatticeGustModel, duration: float) -> float:
    """[s] the histories' span for a gust lasting `duration` [s] (`time_grid`'s end)."""
    slowest = 2 * math.pi / float(model.frequencies.min())
    return float(model.delay.max()) + duration * 1.25 + 2 * slowest


def _step(model: LatticeGustModel, duration: float) -> float:
    step = duration / _PER_GUST
    dynamic = model.frequencies[model.frequencies < _QUASI_STATIC * 2 * math.pi / duration]
    if dynamic.size:
        step = min(step, 2 * math.pi / float(dynamic.max()) / _PER_PERIOD)
    return step


def lattice_discrete_responses(
    model: LatticeGustModel,
    gradients: np.ndarray,
    amplitudes: np.ndarray,
    stretch: float = 1.0,
    harmonics: float = HARMONICS,
) -> list[DiscreteResponse]:
    """Each 1-cos gust's outputs (`DiscreteResponse`, the histories over `time_grid`'s span)
    for gradients H (G,) [m] and peak velocities (G,) [m/s TAS]; the period `stretch` times the
    module docstring's and H up to `harmonics` times the shortest gust's frequency (checks of
    the transform's convergence). The model must be stable (`check_stable`)."""
    gradients = np.asarray(gradients, dtype=float)
    amplitudes = np.asarray(amplitudes, dtype=float)
    if gradients.max() > _BAND * gradients.min():
        # One period for gusts of very different lengths would sample the longest as finely
        # as the shortest: bands of gradients within a factor _BAND share one.
        short = gradients <= _BAND * gradients.min()
        first = lattice_discrete_responses(
            model, gradients[short], amplitudes[short], stretch, harmonics
        )
        rest = lattice_discrete_responses(
            model, gradients[~short], amplitudes[~short], stretch, harmonics
        )
        found = {int(i): r for i, r in zip(np.flatnonzero(short), first, strict=True)}
        found |= {int(i): r for i, r in zip(np.flatnonzero(~short), rest, strict=True)}
        return [found[i] for i in range(gradients.size)]
    v = model.velocity
    durations = 2 * gradients / v
    span = _span(model, float(durations.max()))
    step = _step(model, float(durations.min()))
    shortest = float(np.min(gradients))
    cut = max(harmonics * math.pi * v / shortest, 2 * float(model.frequencies.max()))

    def shape(time: np.ndarray) -> np.ndarray:
        return np.array(
            [
                one_minus_cosine(v * time, float(g), float(a))
                for g, a in zip(gradients, amplitudes, strict=True)
            ]
        )

    time, outputs = _respond(model, shape, span, step, cut, stretch)
    shown = time <= span
    return [
        DiscreteResponse(time[shown], y[:, shown], float(g), float(a))
        for g, a, y in zip(gradients, amplitudes, outputs, strict=True)
    ]


def lattice_profile_response(
    model: LatticeGustModel, times: np.ndarray, velocity: np.ndarray
) -> DiscreteResponse:
    """The outputs for a gust of your own (`solver.gusts.discrete.profile_response`'s
    meaning: vertical velocity [m/s TAS] at `times` [s] from its reaching the foremost leading
    edge, linear between them, zero after the last); samples a tenth of its shortest interval
    and an 8th of the fastest mode's period, at most 20,000 over the span."""
    times, velocity = np.asarray(times, dtype=float), np.asarray(velocity, dtype=float)
    fastest = 2 * math.pi / float(model.frequencies.max())
    span = _span(model, float(times[-1]))
    step = max(min(float(np.diff(times).min()) / 10, fastest / _PER_PERIOD), span / 20_000)

    def shape(time: np.ndarray) -> np.ndarray:
        return np.interp(time, times, velocity, left=0.0, right=0.0)[None, :]

    time, outputs = _respond(model, shape, span, step, math.pi / step)
    shown = time <= span
    return DiscreteResponse(time[shown], outputs[0][:, shown], 0.0, float(np.abs(velocity).max()))


def resolved_frequency(model: LatticeGustModel) -> float:
    """[rad/s] the frequency whose gust wavelength 2 pi V / omega spans four of the lattice's
    longest chordwise panels (the wing's longest chord over its chordwise panels)."""
    panel = float(model.wing.chord.max()) / model.chordwise
    return 2 * math.pi * model.velocity / (4 * panel)


def lattice_a_bar(model: LatticeGustModel, limit: float | None = None) -> np.ndarray:
    """(n_out,) A-bar: each output's rms per unit rms gust velocity [per m/s] (the spectrum
    cut at `limit` [rad/s] if given)."""
    rate = _plunge_rate(model)
    # Below the slowest of the modes, the plunge's decay, the wake's slowest lag (Wagner's
    # 0.0455 V / b) and the turbulence's scale V / L lies only the flat start of |H|^2 Phi.
    lag = 0.0455 * model.velocity / float(model.semichord.max())
    slowest = min(float(model.frequencies.min()), lag, model.velocity / TURBULENCE_SCALE)
    if rate > 0:
        slowest = min(slowest, rate)
    fastest = float(model.frequencies.max())
    omega = np.geomspace(1e-3 * slowest, 50 * fastest, _POINTS)
    if limit is not None:
        omega = omega[omega <= limit]
    response = transfer(model, omega)
    spectrum = von_karman(omega, model.velocity)
    return np.sqrt(np.trapezoid(np.abs(response) ** 2 * spectrum, omega, axis=1))
