"""Irregular seas as sums of linear (Airy) components: a JONSWAP spectrum's components or a
measured elevation record's (docs/derivations/fluid.md, "Irregular seas").

The free-surface elevation at the horizontal position ``x`` and time ``t`` is::

    η(x, t) = Σ_i a_i cos(ω_i t - k_i e·x + φ_i)                                          (1)

with ``e`` the direction of travel and ``k_i`` the root of ``ω_i² = g k tanh(k h)``
(:func:`wave_number`).

* :func:`jonswap_components`: ``n`` components over ``[0.5 ω_p, 4 ω_p]`` in bins of equal
  width ``Δω``, each at a frequency drawn uniformly inside its bin (a sum of commensurate
  frequencies would repeat every ``2π / Δω``), amplitude ``a_i = sqrt(2 S(ω_i) Δω)`` of the
  JONSWAP spectrum ``S`` (:func:`jonswap`), phase drawn uniformly in ``[0, 2π)``; both draws
  from ``numpy.random.default_rng(seed)``: the same seed gives the same sea.
* :func:`record_components`: the discrete Fourier series of a record ``η(t_j)`` sampled at
  equal steps at the origin: eq. (1) reproduces it at ``t_j`` to round-off (the mean as a
  component of ``ω = 0``; the Nyquist term with half its weight).

The fluid kernel takes eq. (1)'s arrays ``(a_i, ω_i, k_i, φ_i)`` (``FluidRecord``), each
component's Airy kinematics added (:class:`JonswapWaves`, :class:`RecordedWaves`; a regular
wave, :class:`Waves`, is one component).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike, NDArray

from rancf.errors import InputError

__all__ = [
    "WaveComponents",
    "Waves",
    "JonswapWaves",
    "RecordedWaves",
    "wave_number",
    "jonswap",
    "jonswap_components",
    "record_components",
]

#: The band of :func:`jonswap_components`, in multiples of the peak frequency.
BAND = (0.5, 4.0)


def wave_number(period: float, depth: float, g: float) -> float:
    """The root ``k`` of the dispersion relation ``ω² = g k tanh(k h)`` (Newton from the deep-water
    value; fluid.md section 2)."""
    om2 = (2.0 * math.pi / period) ** 2
    k = max(om2 / g, math.sqrt(om2 / (g * depth)))
    for _ in range(100):
        th = math.tanh(k * depth)
        f = g * k * th - om2
        df = g * th + g * k * depth * (1.0 - th * th)
        step = f / df
        k -= step
        if abs(step) <= 1e-15 * k:
            break
    return k


@dataclass(frozen=True)
class WaveComponents:
    """Components of eq. (1): amplitudes [m], angular frequencies [rad/s], wave numbers
    [1/m], phases [rad]; the direction of travel (from the x axis, degrees) and the depth."""

    amplitude: NDArray[np.float64]
    omega: NDArray[np.float64]
    k: NDArray[np.float64]
    phase: NDArray[np.float64]
    direction_deg: float
    depth: float

    def elevation(self, t: ArrayLike, x: ArrayLike = (0.0, 0.0)) -> NDArray[np.float64]:
        """``η`` (eq. (1)) at the times ``t`` and the horizontal position ``x``."""
        b = math.radians(self.direction_deg)
        ex = float(np.asarray(x, dtype=float) @ np.array([math.cos(b), math.sin(b)]))
        tt = np.atleast_1d(np.asarray(t, dtype=float))
        out = np.zeros(tt.shape)
        for a, w, k, p in zip(self.amplitude, self.omega, self.k, self.phase, strict=True):
            out += a * np.cos(w * tt - k * ex + p)
        return out


def jonswap(omega: ArrayLike, hs: float, tp: float, gamma: float = 3.3) -> NDArray[np.float64]:
    """The JONSWAP spectrum ``S(ω)`` [m² s] (DNV-RP-C205, 2010, eqs. 3.5.5-3.5.6)::

        S = A_γ (5/16) Hs² ω_p⁴ ω⁻⁵ exp(-5/4 (ω/ω_p)⁻⁴) γ^exp(-(ω - ω_p)² / (2 σ² ω_p²))

    ``A_γ = 1 - 0.287 ln γ``, ``σ = 0.07`` below the peak ``ω_p = 2π / T_p``, 0.09 above."""
    w = np.asarray(omega, dtype=float)
    wp = 2.0 * math.pi / tp
    sigma = np.where(w <= wp, 0.07, 0.09)
    pm = 5.0 / 16.0 * hs**2 * wp**4 * w**-5.0 * np.exp(-1.25 * (w / wp) ** -4.0)
    peak = gamma ** np.exp(-0.5 * ((w - wp) / (sigma * wp)) ** 2)
    return (1.0 - 0.287 * math.log(gamma)) * pm * peak


def jonswap_components(
    hs: float,
    tp: float,
    gamma: float = 3.3,
    depth: float = 1000.0,
    components: int = 200,
    seed: int = 0,
    direction_deg: float = 0.0,
    g: float = 9.80665,
) -> WaveComponents:
    """The components of a JONSWAP sea (module docstring).

    Raises
    ------
    InputError
        ``hs``, ``tp`` or ``depth`` not > 0, ``gamma`` not in [1, 7] (DNV's range),
        ``components`` not an integer >= 1.
    """
    for key, v in (("hs", hs), ("tp", tp), ("depth", depth)):
        if not (math.isfinite(v) and v > 0.0):
            raise InputError(f"fluid.waves.{key}", v, "a finite number > 0")
    if not 1.0 <= gamma <= 7.0:
        raise InputError("fluid.waves.gamma", gamma, "a peak enhancement in [1, 7]")
    if isinstance(components, bool) or int(components) != components or components < 1:
        raise InputError("fluid.waves.components", components, "an integer >= 1")
    rng = np.random.default_rng(seed)
    wp = 2.0 * math.pi / tp
    edges = np.linspace(BAND[0] * wp, BAND[1] * wp, int(components) + 1)
    dw = edges[1] - edges[0]
    omega = edges[:-1] + dw * rng.uniform(size=int(components))
    phase = rng.uniform(0.0, 2.0 * math.pi, size=int(components))
    amp = np.sqrt(2.0 * jonswap(omega, hs, tp, gamma) * dw)
    k = np.array([wave_number(2.0 * math.pi / w, depth, g) for w in omega])
    return WaveComponents(amp, omega, k, phase, float(direction_deg), float(depth))


def record_components(
    t: ArrayLike, eta: ArrayLike, depth: float, direction_deg: float = 0.0, g: float = 9.80665
) -> WaveComponents:
    """The components of a measured elevation record at the origin (module docstring).

    Raises
    ------
    InputError
        Fewer than 4 samples, times not increasing at equal steps (to 1e-6 of a step), or
        values that are not finite.
    """
    tt, ee = np.asarray(t, dtype=float), np.asarray(eta, dtype=float)
    if tt.ndim != 1 or tt.shape != ee.shape or tt.size < 4:
        raise InputError("fluid.waves.elevation", tt.size, "rows [t, eta], at least 4")
    dt = np.diff(tt)
    step = float(np.mean(dt))
    if not (step > 0.0 and np.all(np.abs(dt - step) <= 1e-6 * step)):
        raise InputError("fluid.waves.elevation", "t", "times at equal steps, increasing")
    if not np.all(np.isfinite(ee)):
        raise InputError("fluid.waves.elevation", "eta", "finite elevations")
    n = tt.size
    c = np.fft.rfft(ee) / n
    weight = np.full(c.size, 2.0)
    weight[0] = 1.0
    if n % 2 == 0:
        weight[-1] = 1.0
    omega = np.asarray(2.0 * math.pi * np.fft.rfftfreq(n, step), dtype=np.float64)
    amp = np.asarray(weight * np.abs(c), dtype=np.float64)
    phase = np.asarray(np.angle(c) - omega * tt[0], dtype=np.float64)  # the record starts at t[0]
    k = np.array([0.0 if w == 0.0 else wave_number(2.0 * math.pi / w, depth, g) for w in omega])
    return WaveComponents(amp, omega, k, phase, float(direction_deg), float(depth))


@dataclass(frozen=True)
class Waves:
    """Linear (Airy) waves: ``height`` H [m], ``period`` T [s], ``direction_deg`` of travel in
    the horizontal plane from the x axis, water ``depth`` h [m] below the still surface."""

    height: float
    period: float
    direction_deg: float = 0.0
    depth: float = 1000.0

    def wave_components(self, g: float) -> WaveComponents:
        """The wave as one component of amplitude ``H/2`` and phase 0."""

        def one(x: float) -> np.ndarray:
            return np.array([x], dtype=float)

        om = 2.0 * math.pi / self.period
        k = wave_number(self.period, self.depth, g)
        amp = one(0.5 * float(self.height))
        return WaveComponents(amp, one(om), one(k), one(0.0), self.direction_deg, self.depth)


@dataclass(frozen=True)
class JonswapWaves:
    """An irregular sea of ``components`` Airy components of a JONSWAP spectrum (significant
    height ``hs`` [m], peak period ``tp`` [s], peak enhancement ``gamma``), phases drawn from
    ``seed`` (:func:`rancf.system.irregular_waves.jonswap_components`)."""

    hs: float
    tp: float
    gamma: float = 3.3
    depth: float = 1000.0
    components: int = 200
    seed: int = 0
    direction_deg: float = 0.0

    def wave_components(self, g: float) -> WaveComponents:
        """The sea's components under gravity ``g``."""
        return jonswap_components(
            self.hs,
            self.tp,
            self.gamma,
            self.depth,
            self.components,
            self.seed,
            self.direction_deg,
            g,
        )


@dataclass(frozen=True)
class RecordedWaves:
    """A measured elevation record ``eta`` [m] at the times ``t`` [s] (equal steps) at the
    origin, as the components of its discrete Fourier series
    (:func:`rancf.system.irregular_waves.record_components`)."""

    t: tuple[float, ...]
    eta: tuple[float, ...]
    depth: float = 1000.0
    direction_deg: float = 0.0

    def wave_components(self, g: float) -> WaveComponents:
        """The record's components under gravity ``g``."""
        return record_components(self.t, self.eta, self.depth, self.direction_deg, g)
