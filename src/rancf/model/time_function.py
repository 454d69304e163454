"""Time functions of prescribed motions, driven joints and time-dependent loads.

A :class:`TimeFunction` is scalar or vector valued; the compiled core evaluates it (value, rate,
acceleration: ``src/cpp/time_function.hpp``), this module only describes and packs it:

* ``constant(value)``;
* ``table(rows, interpolation)``: rows ``[t, v...]``, piecewise ``"linear"`` or ``"cubic"`` (the
  not-a-knot cubic spline of :class:`scipy.interpolate.CubicSpline`: C², exact for cubics), held
  at the last row's value after the table (and at the first row's before it);
* ``ramp(duration, value)``: ``value · min(t / duration, 1)``;
* ``harmonic(frequency_hz, amplitude, phase_deg)``: ``amplitude · sin(2π f t + phase)``;
* ``spin_up(duration, rate)``: the angle whose rate rises smoothly from 0 to ``rate`` in
  ``duration`` T (Kane, Ryan & Banerjee 1987):
  ``(rate/T)[t²/2 + (T/2π)² (cos(2πt/T) − 1)]`` for ``t ≤ T``, ``rate (t − T/2)`` after;
* ``from_callable(fn, t_end, samples)``: a Python function sampled on a uniform grid and
  interpolated by the cubic spline (the compiled time loop cannot call Python; the sampling error
  falls as the fourth power of the grid spacing).
"""

from __future__ import annotations

from collections.abc import Callable, Sequence
from dataclasses import dataclass, field

import numpy as np
from numpy.typing import ArrayLike, NDArray

from rancf.errors import InputError

__all__ = ["TimeFunction", "KINDS"]

#: Kind names and their code in the compiled core.
KINDS = {"constant": 0, "table": 1, "ramp": 2, "harmonic": 3, "spin_up": 4}


def _vec(key: str, v: ArrayLike) -> tuple[float, ...]:
    a = np.atleast_1d(np.asarray(v, dtype=float))
    if a.ndim != 1 or a.size == 0 or not np.all(np.isfinite(a)):
        raise InputError(key, v, "a finite number or vector")
    return tuple(float(x) for x in a)


@dataclass(frozen=True)
class TimeFunction:
    """A time function (module docstring); build it with the class methods."""

    kind: str
    value: tuple[float, ...]
    duration: float = 0.0
    frequency: float = 0.0
    phase: float = 0.0
    rows: NDArray[np.float64] | None = field(default=None, compare=False)
    interpolation: str = "linear"

    @property
    def size(self) -> int:
        """Number of components."""
        return len(self.value)

    @classmethod
    def constant(cls, value: ArrayLike) -> TimeFunction:
        return cls("constant", _vec("value", value))

    @classmethod
    def ramp(cls, duration: float, value: ArrayLike) -> TimeFunction:
        if not (np.isfinite(duration) and duration > 0):
            raise InputError("ramp", duration, "a duration > 0 [s]")
        return cls("ramp", _vec("value", value), duration=float(duration))

    @classmethod
    def harmonic(
        cls, frequency_hz: float, amplitude: ArrayLike, phase_deg: float = 0.0
    ) -> TimeFunction:
        if not (np.isfinite(frequency_hz) and frequency_hz >= 0):
            raise InputError("harmonic", frequency_hz, "a frequency >= 0 [Hz]")
        if not np.isfinite(phase_deg):
            raise InputError("phase_deg", phase_deg, "a finite angle [deg]")
        return cls("harmonic", _vec("amplitude", amplitude), frequency=float(frequency_hz),
                   phase=float(np.radians(phase_deg)))  # fmt: skip

    @classmethod
    def spin_up(cls, duration: float, rate: float) -> TimeFunction:
        if not (np.isfinite(duration) and duration > 0):
            raise InputError("spin_up", duration, "a duration > 0 [s]")
        return cls("spin_up", _vec("rate", rate), duration=float(duration))

    @classmethod
    def table(cls, rows: ArrayLike, interpolation: str = "linear") -> TimeFunction:
        a = np.asarray(rows, dtype=float)
        if a.ndim != 2 or a.shape[0] < 2 or a.shape[1] < 2 or not np.all(np.isfinite(a)):
            raise InputError("table", rows, "at least two rows [t, v...] of finite numbers")
        if np.any(np.diff(a[:, 0]) <= 0):
            raise InputError("table", a[:, 0].tolist(), "strictly increasing times")
        if interpolation not in ("linear", "cubic"):
            raise InputError("interpolation", interpolation, 'one of "linear", "cubic"')
        if interpolation == "cubic" and a.shape[0] < 3:
            interpolation = "linear"  # two points: the cubic spline is the line
        return cls("table", tuple(a[0, 1:]), rows=a, interpolation=interpolation)

    @classmethod
    def from_callable(
        cls, fn: Callable[[float], ArrayLike], t_end: float, samples: int = 2001
    ) -> TimeFunction:
        t = np.linspace(0.0, float(t_end), int(samples))
        vals = np.array([np.atleast_1d(np.asarray(fn(float(x)), dtype=float)) for x in t])
        return cls.table(np.column_stack([t, vals]), "cubic")

    # ---------------------------------------------------------------- packing for the core
    def coefficients(self) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
        """Piecewise-cubic breakpoints ``(k + 1,)`` and coefficients ``(k, 4, n)`` (``c0 + c1 s
        + c2 s² + c3 s³``, ``s = t − t_i``) of a table; empty for the other kinds."""
        if self.kind != "table" or self.rows is None:
            return np.zeros(0), np.zeros(0)
        t, v = self.rows[:, 0], self.rows[:, 1:]
        k, n = t.size - 1, v.shape[1]
        coef = np.zeros((k, 4, n))
        if self.interpolation == "linear":
            coef[:, 0] = v[:-1]
            coef[:, 1] = np.diff(v, axis=0) / np.diff(t)[:, None]
        else:
            from scipy.interpolate import CubicSpline

            c = CubicSpline(t, v, axis=0, bc_type="not-a-knot").c  # (4, k, n), highest first
            coef = np.transpose(c[::-1], (1, 0, 2))
        return t.copy(), np.ascontiguousarray(coef)


def pack(functions: Sequence[TimeFunction]) -> dict[str, NDArray]:
    """The core's arrays of a list of time functions (``tf_*`` of ``rancf._core.System``)."""
    kinds, sizes, values, vstart, params, breaks, bstart, coef, cstart = ([] for _ in range(9))
    nv = nb = nc = 0
    for f in functions:
        kinds.append(KINDS[f.kind])
        sizes.append(f.size)
        vstart.append(nv)
        values += list(f.value)
        nv += f.size
        params += [f.duration, f.frequency, f.phase]
        b, c = f.coefficients()
        bstart.append(nb)
        cstart.append(nc)
        breaks += b.tolist()
        coef += c.ravel().tolist()
        nb += b.size
        nc += c.size
    bstart.append(nb)
    cstart.append(nc)
    i64 = np.int64
    return {
        "tf_kind": np.array(kinds, dtype=i64),
        "tf_n": np.array(sizes, dtype=i64),
        "tf_value": np.array(values, dtype=float),
        "tf_value_start": np.array(vstart, dtype=i64),
        "tf_params": np.array(params, dtype=float),
        "tf_breaks": np.array(breaks, dtype=float),
        "tf_breaks_start": np.array(bstart, dtype=i64),
        "tf_coef": np.array(coef, dtype=float),
        "tf_coef_start": np.array(cstart, dtype=i64),
    }
