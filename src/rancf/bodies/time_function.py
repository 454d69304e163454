"""Time functions of prescribed motions, driven joints and time-dependent loads.

A :class:`TimeFunction` gives a value, its rate and its acceleration at a time ``t`` [s], exact
for every kind (the closed forms below and their derivatives); scalar (a load factor, a joint
angle) or vector valued (a support's displacement), every component sharing the kind:

* ``constant(value)``: ``f(t) = c``                                                      (T.1)
* ``table(rows, interpolation)``: rows ``[t, v...]`` with strictly increasing ``t``; piecewise
  linear, or the not-a-knot cubic spline of :class:`scipy.interpolate.CubicSpline` (C², exact
  for cubic polynomials; "natural" end conditions would not be); held at the first row's value
  before the table and at the last row's after it (rate and acceleration zero there)      (T.2)
* ``ramp(duration, value)``: ``f(t) = value · min(max(t, 0) / T, 1)``                     (T.3)
* ``harmonic(frequency_hz, amplitude, phase_deg)``: ``f(t) = A sin(2π f t + φ)``          (T.4)
* ``spin_up(duration, rate)``: the angle whose rate rises smoothly from 0 to ``Ω = rate`` in
  ``T = duration`` (Kane, Ryan & Banerjee 1987)                                             (T.5)

      θ(t) = (Ω/T) [t²/2 + (T/2π)² (cos(2πt/T) − 1)]   for 0 ≤ t ≤ T,
      θ(t) = Ω (t − T/2)                                for t > T,

  so ``θ̇ = (Ω/T)(t − (T/2π) sin(2πt/T))`` and ``θ̈ = (Ω/T)(1 − cos(2πt/T))`` rise from 0 and
  join ``Ω`` and ``0`` with continuous rate and acceleration at ``t = T`` (zero before ``t = 0``);
* ``from_callable(fn)``: any Python function of ``t`` (the Python API).  The function is kept and
  called for the value; the rate and the acceleration are central differences
  ``(f(t+h) − f(t−h)) / 2h`` with ``h = 6e-6 s`` (about ``ε^(1/3)``: truncation ``h² f‴ / 6``,
  round-off ``ε (|f| + |t f′|) / h``: ~1e-10 relative for smooth functions on a time scale of
  a second) and ``(f(t+h) − 2 f(t) + f(t−h)) / h²`` with ``h = 1.2e-4 s`` (about ``ε^(1/4)``:
  ~1e-7 relative).  :meth:`sampled` turns it into a cubic table for code that cannot call
  Python (the compiled time loop).

Any kind may be built up (:meth:`TimeFunction.with_build_up`, ``build_up = B`` in a scenario
file): it is multiplied by the quintic smooth step from 0 to 1 over ``[0, B]``           (T.6)

    g(t) = r(t) f(t),  r = 10 s³ − 15 s⁴ + 6 s⁵,  s = min(max(t / B, 0), 1),
    g′ = r′ f + r f′,  g″ = r″ f + 2 r′ f′ + r f″,

so that ``g``, ``g′`` and ``g″`` start from 0 (``r′ = r″ = 0`` at both ends: no jump of rate or
acceleration at ``t = 0`` or ``t = B``) and ``g = f`` after ``B``.

At a kink (a table's breakpoint, the end of a ramp) the rate is the one of the interval that
starts there (the right derivative).  The compiled core evaluates the same functions
(``src/cpp/system/time_function.hpp``) from the records of
:func:`rancf.bodies.time_record.core_record`.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from typing import Any

import numpy as np
from numpy.typing import ArrayLike, NDArray

from rancf.errors import InputError

__all__ = [
    "TimeFunction",
    "KINDS",
    "spin_up_angle",
    "build_up_factor",
]

#: The kinds of time functions.
KINDS = ("constant", "table", "ramp", "harmonic", "spin_up", "callable")
_H1, _H2 = 6e-6, 1.2e-4  # central-difference steps of callables [s]


def build_up_factor(t: float, duration: float) -> tuple[float, float, float]:
    """The smooth step ``r`` of (T.6) and its first two time derivatives at ``t``."""
    s = min(max(t / duration, 0.0), 1.0)
    if s <= 0.0 or s >= 1.0:
        return (0.0 if s <= 0.0 else 1.0), 0.0, 0.0
    r = s * s * s * (10.0 + s * (-15.0 + 6.0 * s))
    dr = 30.0 * s * s * (1.0 - s) * (1.0 - s) / duration
    ddr = 60.0 * s * (1.0 - s) * (1.0 - 2.0 * s) / (duration * duration)
    return r, dr, ddr


def _values(key: str, v: ArrayLike) -> tuple[tuple[float, ...], bool]:
    """``v`` as a tuple of finite floats, and whether it was given as a vector."""
    a = np.asarray(v, dtype=float)
    if a.ndim > 1 or a.size == 0 or not np.all(np.isfinite(a)):
        raise InputError(key, v, "a finite number or a vector of finite numbers")
    return tuple(float(x) for x in a.ravel()), a.ndim == 1


def _positive(key: str, v: float) -> float:
    if isinstance(v, bool) or not (isinstance(v, int | float) and math.isfinite(v) and v > 0):
        raise InputError(key, v, "a finite number > 0")
    return float(v)


def spin_up_angle(t: ArrayLike, duration: float, rate: float, order: int = 0) -> NDArray:
    """The spin-up law (T.5) (``order`` 0), its rate (1) or its acceleration (2) at ``t``."""
    t = np.asarray(t, dtype=float)
    tt, k = duration, 2.0 * math.pi / duration
    a = 1.0 / k
    before, after = t <= 0.0, t >= tt
    if order == 0:
        inside = rate / tt * (0.5 * t * t + a * a * (np.cos(k * t) - 1.0))
        out = np.where(after, rate * (t - 0.5 * tt), inside)
    elif order == 1:
        out = np.where(after, rate, rate / tt * (t - a * np.sin(k * t)))
    else:
        out = np.where(after, 0.0, rate / tt * (1.0 - np.cos(k * t)))
    return np.where(before, 0.0, out)


class TimeFunction:
    """A scalar or vector function of time (module docstring); build it with the class methods.

    Attributes
    ----------
    kind : str
        One of :data:`KINDS`.
    values : tuple of float
        The constant, the ramp's end value, the amplitude or the spin-up rate (one per
        component); a table's first row.
    vector : bool
        Whether the values are vectors (then :meth:`value` returns arrays of ``size``).
    duration, frequency, phase : float
        ``T`` of a ramp or spin-up [s], the harmonic's frequency [Hz] and phase [rad].
    rows : ndarray or None
        A table's rows ``(k, 1 + size)``.
    interpolation : str
        ``"linear"`` or ``"cubic"`` (tables).
    fn : callable or None
        The Python function of :meth:`from_callable`.
    build_up : float
        ``B`` of the build-up (T.6) [s]; 0: none.
    """

    def __init__(
        self,
        kind: str,
        values: tuple[float, ...],
        vector: bool = False,
        *,
        duration: float = 0.0,
        frequency: float = 0.0,
        phase: float = 0.0,
        rows: NDArray[np.float64] | None = None,
        interpolation: str = "linear",
        fn: Callable[[float], Any] | None = None,
        build_up: float = 0.0,
    ) -> None:
        self.kind, self.values, self.vector = kind, values, vector
        self.build_up = build_up
        self.duration, self.frequency, self.phase = duration, frequency, phase
        self.rows, self.interpolation, self.fn = rows, interpolation, fn
        #: A cubic table's spline (:class:`scipy.interpolate.CubicSpline`), else None.
        self.spline: Any = None
        if kind == "table" and interpolation == "cubic" and rows is not None and len(rows) > 2:
            from scipy.interpolate import CubicSpline

            self.spline = CubicSpline(rows[:, 0], rows[:, 1:], axis=0, bc_type="not-a-knot")

    # ------------------------------------------------------------------ construction
    @classmethod
    def constant(cls, value: ArrayLike) -> TimeFunction:
        """``f(t) = value`` (T.1)."""
        return cls("constant", *_values("value", value))

    @classmethod
    def ramp(cls, duration: float, value: ArrayLike = 1.0) -> TimeFunction:
        """``value · min(t / duration, 1)`` (T.3)."""
        return cls("ramp", *_values("value", value), duration=_positive("ramp", duration))

    @classmethod
    def harmonic(
        cls, frequency_hz: float, amplitude: ArrayLike = 1.0, phase_deg: float = 0.0
    ) -> TimeFunction:
        """``amplitude · sin(2π f t + phase)`` (T.4)."""
        f = _positive("harmonic", frequency_hz)
        if isinstance(phase_deg, bool) or not math.isfinite(phase_deg):
            raise InputError("phase_deg", phase_deg, "a finite angle [deg]")
        return cls(
            "harmonic", *_values("amplitude", amplitude), frequency=f, phase=math.radians(phase_deg)
        )

    @classmethod
    def spin_up(cls, duration: float, rate: float) -> TimeFunction:
        """The spin-up angle law (T.5) reaching the rate ``rate`` [rad/s] at ``duration``."""
        values, vector = _values("rate", rate)
        if vector:
            raise InputError("rate", rate, "a number (the final angular rate [rad/s])")
        return cls("spin_up", values, duration=_positive("spin_up", duration))

    @classmethod
    def table(cls, rows: ArrayLike, interpolation: str = "linear") -> TimeFunction:
        """Rows ``[t, v...]`` interpolated linearly or by the not-a-knot cubic spline (T.2).

        One value per row gives a scalar function, several a vector function.
        """
        a = np.asarray(rows, dtype=float)
        if a.ndim != 2 or a.shape[0] < 2 or a.shape[1] < 2 or not np.all(np.isfinite(a)):
            raise InputError("table", rows, "at least two rows [t, v...] of finite numbers")
        if np.any(np.diff(a[:, 0]) <= 0):
            raise InputError("table", a[:, 0], "rows with strictly increasing times")
        if interpolation not in ("linear", "cubic"):
            raise InputError("interpolation", interpolation, 'one of "linear", "cubic"')
        vector = a.shape[1] > 2
        return cls("table", tuple(a[0, 1:].tolist()), vector, rows=a, interpolation=interpolation)

    @classmethod
    def from_callable(cls, fn: Callable[[float], Any]) -> TimeFunction:
        """A Python function ``fn(t)`` (a number or a vector); derivatives by central
        differences (module docstring)."""
        if not callable(fn):
            raise InputError("time function", fn, "a callable f(t)")
        values, vector = _values("f(0)", fn(0.0))
        return cls("callable", values, vector, fn=fn)

    def with_build_up(self, seconds: float) -> TimeFunction:
        """This function times the smooth step from 0 to 1 over ``seconds`` (T.6); 0: none."""
        if isinstance(seconds, bool) or not (
            isinstance(seconds, int | float) and math.isfinite(seconds) and seconds >= 0
        ):
            raise InputError("build_up", seconds, "a finite duration >= 0 [s]")
        out = TimeFunction(
            self.kind,
            self.values,
            self.vector,
            duration=self.duration,
            frequency=self.frequency,
            phase=self.phase,
            rows=self.rows,
            interpolation=self.interpolation,
            fn=self.fn,
            build_up=float(seconds),
        )
        return out

    # ------------------------------------------------------------------ evaluation
    @property
    def size(self) -> int:
        """Number of components."""
        return len(self.values)

    def value(self, t: float) -> float | NDArray[np.float64]:
        """``f(t)``: a float, or an array of ``size`` for vector functions."""
        return self._eval(t, 0)

    def rate(self, t: float) -> float | NDArray[np.float64]:
        """``f'(t)``."""
        return self._eval(t, 1)

    def acceleration(self, t: float) -> float | NDArray[np.float64]:
        """``f''(t)``."""
        return self._eval(t, 2)

    def __call__(self, t: float) -> float | NDArray[np.float64]:
        return self._eval(t, 0)

    def _eval(self, t: float, order: int) -> float | NDArray[np.float64]:
        t = float(t)
        v = self._plain(t, order)
        if self.build_up > 0.0 and t < self.build_up:  # (T.6)
            r, dr, ddr = build_up_factor(t, self.build_up)
            if order == 0:
                v = r * v
            elif order == 1:
                v = dr * self._plain(t, 0) + r * v
            else:
                v = ddr * self._plain(t, 0) + 2.0 * dr * self._plain(t, 1) + r * v
        return v if self.vector else float(v[0])

    def _plain(self, t: float, order: int) -> NDArray[np.float64]:
        """The function without its build-up."""
        return self._callable(t, order) if self.kind == "callable" else self._exact(t, order)

    def _exact(self, t: float, order: int) -> NDArray[np.float64]:
        c = np.array(self.values)
        if self.kind == "constant":
            return c if order == 0 else 0.0 * c
        if self.kind == "ramp":
            inside = 0.0 <= t < self.duration
            if order == 0:
                return c * min(max(t, 0.0) / self.duration, 1.0)
            return c / self.duration if order == 1 and inside else 0.0 * c
        if self.kind == "harmonic":
            w = 2.0 * math.pi * self.frequency
            arg = w * t + self.phase
            return c * (math.sin(arg), w * math.cos(arg), -w * w * math.sin(arg))[order]
        if self.kind == "spin_up":
            return c * 0.0 + float(spin_up_angle(t, self.duration, c[0], order))
        return self._table(t, order)

    def _table(self, t: float, order: int) -> NDArray[np.float64]:
        rows = self.rows
        assert rows is not None
        ts, vs = rows[:, 0], rows[:, 1:]
        if t < ts[0] or t >= ts[-1]:
            held = vs[0] if t < ts[0] else vs[-1]
            return held.copy() if order == 0 else 0.0 * held
        if self.spline is not None:
            return np.asarray(self.spline(t, order), dtype=float)
        i = int(np.searchsorted(ts, t, side="right")) - 1
        slope = (vs[i + 1] - vs[i]) / (ts[i + 1] - ts[i])
        return (vs[i] + slope * (t - ts[i]), slope, 0.0 * slope)[order]

    def _callable(self, t: float, order: int) -> NDArray[np.float64]:
        fn = self.fn
        assert fn is not None

        def f(x: float) -> NDArray[np.float64]:
            return np.atleast_1d(np.asarray(fn(x), dtype=np.float64))

        if order == 0:
            return f(t)
        if order == 1:
            h = _H1
            return (f(t + h) - f(t - h)) / (2.0 * h)
        h = _H2
        return (f(t + h) - 2.0 * f(t) + f(t - h)) / (h * h)

    # ------------------------------------------------------------------ other forms
    def sampled(self, t_end: float, samples: int = 2001) -> TimeFunction:
        """This function sampled on ``samples`` uniform times in ``[0, t_end]`` as a cubic table
        (for code that cannot call Python; the error falls as the fourth power of the step)."""
        t = np.linspace(0.0, float(t_end), int(samples))
        vals = np.array([np.atleast_1d(self._eval(x, 0)) for x in t])
        out = TimeFunction.table(np.column_stack([t, vals]), "cubic")
        out.vector = self.vector
        return out

    def to_toml(self) -> float | list[float] | dict[str, Any]:
        """The scenario file's form of this function (a callable has none)."""

        def val(v: tuple[float, ...]) -> float | list[float]:
            return list(v) if self.vector else v[0]

        out = self._toml_plain(val)
        if self.build_up > 0.0:
            if not isinstance(out, dict):  # a constant: as a table of two equal rows
                out = {"table": [[0.0, *self.values], [1.0, *self.values]]}
            out["build_up"] = self.build_up
        return out

    def _toml_plain(self, val: Callable) -> float | list[float] | dict[str, Any]:
        if self.kind == "constant":
            return val(self.values)
        if self.kind == "ramp":
            return {"ramp": self.duration, "value": val(self.values)}
        if self.kind == "harmonic":
            return {
                "harmonic": self.frequency,
                "amplitude": val(self.values),
                "phase_deg": math.degrees(self.phase),
            }
        if self.kind == "spin_up":
            return {"spin_up": self.duration, "rate": self.values[0]}
        if self.kind == "table":
            assert self.rows is not None
            return {"table": self.rows.tolist(), "interpolation": self.interpolation}
        raise InputError("time function", self.fn, "a function given by its kind (not a callable)")

    def __eq__(self, other: object) -> bool:
        if not isinstance(other, TimeFunction):
            return NotImplemented
        if self.kind == "callable" or other.kind == "callable":
            return self.fn is other.fn
        rows_equal = (self.rows is None and other.rows is None) or (
            self.rows is not None
            and other.rows is not None
            and np.array_equal(self.rows, other.rows)
        )
        same = (
            self.kind,
            self.values,
            self.vector,
            self.duration,
            self.frequency,
            self.phase,
            self.build_up,
        )
        return rows_equal and same == (
            other.kind,
            other.values,
            other.vector,
            other.duration,
            other.frequency,
            other.phase,
            other.build_up,
        )

    # unhashable: a class that defines __eq__ and not __hash__ has __hash__ = None

    def __repr__(self) -> str:
        if self.kind == "callable":
            return f"TimeFunction.from_callable({self.fn!r})"
        return f"TimeFunction({self.to_toml()!r})"
