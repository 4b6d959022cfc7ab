"""The response to discrete 1-cos gusts in time, several gradients at once.

Each strip meets the gust when it reaches the strip's leading edge (`GustModel.delay`), and
lags it by Kuessner's function: the input g_j(t) = K_j * (w_g(t - tau_j) / V), Sears and Sparks'
two exponentials applied to the 1-cos in closed form (for y' = -gamma y + (1 - cos Omega t):
y = (1 - e^{-gamma t}) / gamma - (gamma cos Omega t + Omega sin Omega t - gamma e^{-gamma t}) /
(gamma^2 + Omega^2) while the gust lasts, then decaying as e^{-gamma t}).

The state x' = A x + B g is integrated exactly for g linear between samples (first-order hold)
on A's eigenvectors, x = V xi (each a causal convolution, by FFT):

    xi_{k+1} = e^{lambda h} xi_k + P0 beta_k + P1 (beta_{k+1} - beta_k),
    P0 = (e^{lambda h} - 1) / lambda,  P1 = (e^{lambda h} - 1 - lambda h) / (lambda^2 h),

beta = V^{-1} B g, exact for any step. Sampling sets what a peak between samples loses: the
step is a 100th of the gust and an 8th of the period of the fastest mode the gust excites
dynamically (modes ten times faster than the gust's own frequency follow it quasi-statically),
and each peak is the vertex of the parabola through its sample and its neighbours (an error of
order (pi / 8)^4 of that mode's share, against 1 - cos(pi / 8) = 7.6 % read off the samples);
`tests/solver/gusts/test_discrete.py` checks the peaks against four times more samples.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from solver.gusts.indicial import KUESSNER
from solver.gusts.model import GustModel

__all__ = [
    "DiscreteResponse",
    "discrete_response",
    "kuessner_lagged_gust",
    "peaks",
    "profile_response",
    "time_grid",
]

_PER_PERIOD = 8
_PER_GUST = 100
_QUASI_STATIC = 10.0
_SMALL = 1e-6  # |lambda h| below which P0 and P1 are their series


@dataclass(frozen=True)
class DiscreteResponse:
    """The outputs (`GustModel.output_slices`) to the 1-cos gust of one gradient: time (T,)
    [s]; outputs (n_out, T); gradient [m]; amplitude [m/s TAS] the gust's peak velocity."""

    time: np.ndarray
    outputs: np.ndarray
    gradient: float
    amplitude: float


def kuessner_lagged_gust(
    model: GustModel, time: np.ndarray, gradient: np.ndarray, amplitude: np.ndarray
) -> np.ndarray:
    """(m, T, G) [rad] each strip's Kuessner-lagged gust angle at `time` (T,) [s] for 1-cos
    gusts of gradients H (G,) [m] and peak velocities (G,) [m/s TAS]."""
    v = model.velocity
    omega = (math.pi * v / gradient)[None, None, :]  # [rad/s]
    duration = (2 * gradient / v)[None, None, :]
    local = time[None, :, None] - model.delay[:, None, None]  # (m, T, 1)
    inside = np.clip(local, 0.0, duration)
    after = np.maximum(local - duration, 0.0)
    scale = (amplitude / (2 * v))[None, None, :]
    poles = KUESSNER.poles(v, model.semichord)  # (m, terms)
    weights = KUESSNER.output_weights(v, model.semichord)
    lagged = KUESSNER.direct * scale * (1 - np.cos(omega * inside)) * (local <= duration)
    for i in range(poles.shape[1]):
        gamma = poles[:, i][:, None, None]
        decay = np.exp(-gamma * inside)
        state = (1 - decay) / gamma - (
            gamma * np.cos(omega * inside) + omega * np.sin(omega * inside) - gamma * decay
        ) / (gamma**2 + omega**2)
        lagged = lagged + weights[:, i][:, None, None] * scale * state * np.exp(-gamma * after)
    return lagged


def time_grid(model: GustModel, gradient: float, refine: float = 1.0) -> np.ndarray:
    """(T,) [s] the samples of the gust of gradient H [m]: from the first strip's meeting it
    to past its last strip's leaving it by a quarter of the gust and two periods of the
    slowest mode; `refine` times more than the module docstring's (a check of the sampling)."""
    v = model.velocity
    duration = 2 * gradient / v
    step = duration / _PER_GUST
    # Modes ten times faster than the gust follow it quasi-statically (a 1-cos excites their
    # transient by (2 pi / omega T)^2 < 1 %): the samples resolve the others.
    dynamic = model.frequencies[model.frequencies < _QUASI_STATIC * 2 * math.pi / duration]
    if dynamic.size:
        step = min(step, 2 * math.pi / float(dynamic.max()) / _PER_PERIOD)
    slowest = 2 * math.pi / float(model.frequencies.min())
    end = float(model.delay.max()) + duration * 1.25 + 2 * slowest
    count = math.ceil(refine * end / step) + 1
    return np.linspace(0.0, end, count)


def discrete_response(
    model: GustModel, gradient: float, amplitude: float, refine: float = 1.0
) -> DiscreteResponse:
    """The outputs' time histories for the 1-cos gust of gradient H [m] and peak velocity
    [m/s TAS] (`DiscreteResponse`). The model must be stable (`check_stable`)."""
    time = time_grid(model, gradient, refine)
    lagged = kuessner_lagged_gust(model, time, np.array([gradient]), np.array([amplitude]))
    return DiscreteResponse(time, _respond(model, time, lagged[:, :, 0]), gradient, amplitude)


def profile_response(model: GustModel, times: np.ndarray, velocity: np.ndarray) -> DiscreteResponse:
    """The outputs' time histories for a gust of your own: vertical velocity [m/s TAS] at
    `times` [s] (from its reaching the foremost leading edge), linear between them and zero
    after the last. Kuessner's states filter each strip's delayed gust exactly for its
    piecewise-linear samples (first-order hold on the grid); the grid's step is a tenth of the
    profile's shortest interval and an 8th of the fastest mode's period, at most 20,000."""
    times, velocity = np.asarray(times, dtype=float), np.asarray(velocity, dtype=float)
    slowest = 2 * math.pi / float(model.frequencies.min())
    fastest = 2 * math.pi / float(model.frequencies.max())
    end = float(model.delay.max()) + float(times[-1]) + 2 * slowest
    step = max(min(float(np.diff(times).min()) / 10, fastest / _PER_PERIOD), end / 20_000)
    time = np.linspace(0.0, end, math.ceil(end / step) + 1)
    h = float(time[1] - time[0])
    local = time[None, :] - model.delay[:, None]  # (m, T)
    angle = np.interp(local, times, velocity, left=0.0, right=0.0) / model.velocity
    angle[local > times[-1]] = 0.0
    poles = KUESSNER.poles(model.velocity, model.semichord)
    weights = KUESSNER.output_weights(model.velocity, model.semichord)
    lagged = KUESSNER.direct * angle
    decay = np.exp(-poles * h)  # (m, 2)
    p0 = (1 - decay) / poles
    p1 = (decay - 1 + poles * h) / (poles**2 * h)
    # y_{k+1} = e y_k + (p0 - p1) u_k + p1 u_{k+1}, from rest: its impulse response is p1, then
    # (e p1 + p0 - p1) e^(k - 1), a causal convolution.
    k = np.arange(time.size)
    impulse = (decay * p1 + p0 - p1)[:, :, None] * decay[:, :, None] ** (k - 1).clip(0)
    impulse[:, :, 0] = p1
    states = _causal_convolution(impulse, angle[:, None, :]).real  # (m, 2, T)
    lagged += np.einsum("ji,jit->jt", weights, states)
    return DiscreteResponse(time, _respond(model, time, lagged), 0.0, float(np.abs(velocity).max()))


def _causal_convolution(kernel: np.ndarray, forcing: np.ndarray) -> np.ndarray:
    """(..., T) sum over j <= t of kernel[..., t - j] forcing[..., j]: the first T terms of
    their linear convolution along the last axis (broadcast over the others), by FFT, zero
    padded to the first length of factors 2, 3 and 5 from 2 T - 1 (at most a fifth longer)."""
    size = kernel.shape[-1]
    n = _fast_length(2 * size - 1)
    spectrum = np.fft.fft(kernel, n, axis=-1) * np.fft.fft(forcing, n, axis=-1)
    return np.fft.ifft(spectrum, axis=-1)[..., :size]


def _fast_length(target: int) -> int:
    """The least n >= `target` whose prime factors are 2, 3 and 5 (FFTs of it are fast)."""
    best, five = 2 * target, 1
    while five < best:
        three = five
        while three < best:
            n = three << max(0, math.ceil(math.log2(target / three)))
            best = min(best, n)
            three *= 3
        five *= 5
    return best


def _respond(model: GustModel, time: np.ndarray, lagged: np.ndarray) -> np.ndarray:
    """(n_out, T) the outputs of the strips' lagged gust angles `lagged` (m, T) sampled at
    `time` (T,) [s], evenly spaced from 0, the system at rest at 0 (module docstring)."""
    h = float(time[1] - time[0])
    roots, vectors, inverse = model.eigen
    drive = (inverse @ model.b) @ lagged  # (S, T)
    step = roots * h
    growth = np.exp(step)
    small = np.abs(step) < _SMALL
    safe = np.where(small, 1.0, roots)
    p0 = np.where(small, h * (1 + step / 2), (growth - 1) / safe)[:, None]
    p1 = np.where(small, h * (0.5 + step / 6), (growth - 1 - step) / (safe * safe * h))[:, None]
    # xi_{k+1} = e xi_k + u_{k+1}: a causal convolution with e^{lambda h k}, by FFT.
    forcing = np.zeros_like(drive)
    forcing[:, 1:] = (p0 - p1) * drive[:, :-1] + p1 * drive[:, 1:]
    kernel = np.exp(np.outer(step, np.arange(time.size)))
    xi = _causal_convolution(kernel, forcing)
    return np.asarray((model.c @ vectors @ xi).real + model.d @ lagged)


def peaks(values: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """(max, min) over the last axis of sampled `values` (..., T), each refined by the
    parabola through its sample and the two beside it (the peak between samples)."""
    return _refined(values), -_refined(-values)


def _refined(values: np.ndarray) -> np.ndarray:
    index = np.clip(np.argmax(values, axis=-1), 1, values.shape[-1] - 2)
    take = np.take_along_axis
    y0 = take(values, (index - 1)[..., None], -1)[..., 0]
    y1 = take(values, index[..., None], -1)[..., 0]
    y2 = take(values, (index + 1)[..., None], -1)[..., 0]
    curvature = y0 - 2 * y1 + y2
    vertex = np.where(
        curvature < 0, y1 - (y0 - y2) ** 2 / (8 * np.where(curvature < 0, curvature, -1.0)), y1
    )
    return np.maximum(np.maximum(vertex, values.max(axis=-1)), y1)
