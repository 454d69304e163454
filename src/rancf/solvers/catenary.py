"""The elastic catenary between two points (Irvine, *Cable Structures*, 1981, §2.2): the start
estimate of form-finding (:mod:`rancf.solvers.form`; docs/derivations/form-finding.md).

A cable of unstretched length ``L``, weight ``w`` per unstretched length and axial stiffness
``EA`` (Hooke's law in the engineering strain) hangs from ``A = (0, 0)`` to ``B = (l, h)``
(``l > 0`` the horizontal span, ``h`` the rise of ``B`` above ``A``).  With the horizontal
tension ``H`` and the vertical tension ``V`` at ``A`` (positive when the cable rises from ``A``),
the tension at the unstretched arc length ``s`` from ``A`` is ``(H, V + w s)`` and the cable
passes through (docs/derivations/form-finding.md, eq. (1))::

    x(s) = H s / EA + (H / w) [asinh((V + w s) / H) - asinh(V / H)]
    z(s) = (V s + w s² / 2) / EA + (1 / w) [sqrt(H² + (V + w s)²) - sqrt(H² + V²)]

``(H, V)`` are the root of ``x(L) = l``, ``z(L) = h``.  The sag is the largest vertical distance
below the chord, ``max_s (h x(s) / l - z(s))``; the end tension is ``|T(L)|`` at ``B``.
"""

from __future__ import annotations

import math
from typing import Literal

import numpy as np

from rancf.errors import ConvergenceError, InputError

__all__ = ["Catenary", "catenary", "catenary_length", "Target"]

#: What form-finding meets: ``[form]``'s keys.
Target = Literal["sag", "horizontal_tension", "end_tension"]


class Catenary:
    """One elastic catenary (module docstring): its ends, properties and ``(H, V)``."""

    def __init__(
        self, span: float, rise: float, length: float, w: float, ea: float, h: float, v: float
    ) -> None:
        self.span, self.rise, self.length, self.w, self.ea = span, rise, length, w, ea
        self.h, self.v = h, v

    def points(self, s: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """``x(s)``, ``z(s)`` (eq. (1))."""
        h, v, w, ea = self.h, self.v, self.w, self.ea
        x = h * s / ea + (h / w) * (np.arcsinh((v + w * s) / h) - math.asinh(v / h))
        z = (v * s + 0.5 * w * s * s) / ea + (np.hypot(h, v + w * s) - math.hypot(h, v)) / w
        return x, z

    def sag(self) -> float:
        """The largest vertical distance below the chord."""
        from scipy.optimize import minimize_scalar  # SciPy only where a catenary is solved

        def below(s: float) -> float:
            x, z = self.points(np.array([s]))
            return float(self.rise * x[0] / self.span - z[0])

        s = np.linspace(0.0, self.length, 401)
        x, z = self.points(s)
        k = int(np.argmax(self.rise * x / self.span - z))
        lo, hi = s[max(k - 1, 0)], s[min(k + 1, s.size - 1)]
        best = minimize_scalar(lambda t: -below(t), bounds=(lo, hi), method="bounded")
        return max(below(float(best.x)), below(float(s[k])))

    def end_tension(self) -> float:
        """``|T|`` at ``B``."""
        return math.hypot(self.h, self.v + self.w * self.length)

    def measure(self, kind: Target) -> float:
        """The sag, the horizontal tension or the end tension."""
        if kind == "sag":
            return self.sag()
        return self.h if kind == "horizontal_tension" else self.end_tension()


def _start(span: float, rise: float, length: float, w: float, ea: float) -> tuple[float, float]:
    """``(H, V)`` of the inextensible catenary of ``length`` (slack), or of the straight line
    stretched onto the chord (taut): Newton's start."""
    from scipy.optimize import brentq

    chord = math.hypot(span, rise)
    if length > chord * (1.0 + 1e-9):
        c = math.sqrt(length**2 - rise**2)
        a = brentq(lambda a: 2.0 * a * math.sinh(min(span / (2.0 * a), 700.0)) - c, 1e-6, 1e9)
        a *= span  # the root in units of the span
        h = w * a
        u1 = -(span / 2.0 - a * math.atanh(rise / length)) / a
        return h, h * math.sinh(u1)
    h = max(ea * (chord / length - 1.0), 1e-3 * w * length) * span / chord + w * length
    return h, h * rise / span - 0.5 * w * length


def catenary(span: float, rise: float, length: float, w: float, ea: float) -> Catenary:
    """The elastic catenary of unstretched ``length`` from ``(0, 0)`` to ``(span, rise)``
    (module docstring; ``span > 0``, ``w > 0``, ``EA > 0``).

    Raises
    ------
    ConvergenceError
        Newton's method (``scipy.optimize.fsolve`` in ``log H``) finds no ``(H, V)``.
    """
    from scipy.optimize import fsolve

    h0, v0 = _start(span / span, rise / span, length / span, 1.0, ea / (w * span))
    scale = w * span  # the unknowns in units of w l

    def residual(u: np.ndarray) -> np.ndarray:
        cat = Catenary(1.0, rise / span, length / span, 1.0, ea / scale, math.exp(u[0]), u[1])
        x, z = cat.points(np.array([cat.length]))
        return np.array([x[0] - 1.0, z[0] - cat.rise])

    sol, _, _, msg = fsolve(residual, [math.log(h0), v0], full_output=True, xtol=1e-13)
    if not np.max(np.abs(residual(sol))) <= 1e-10:  # (fsolve may stall at round-off)
        raise ConvergenceError(f"the elastic catenary of length {length:g} m: {msg}")
    return Catenary(span, rise, length, w, ea, math.exp(sol[0]) * scale, sol[1] * scale)


def catenary_length(
    kind: Target, target: float, span: float, rise: float, w: float, ea: float, key: str
) -> float:
    """The unstretched length whose elastic catenary meets ``target`` (``kind``: the sag, the
    horizontal tension or the end tension; the end tension's taut root, the shorter of two);
    ``key`` names the target in errors.

    Raises
    ------
    InputError
        No length gives ``target`` (an end tension below the least one any length gives).
    """
    from scipy.optimize import brentq, minimize_scalar

    chord = math.hypot(span, rise)

    def f(length: float) -> float:
        return catenary(span, rise, length, w, ea).measure(kind) - target

    lo, hi = chord * 0.5, chord * 2.0
    if kind == "end_tension":  # the least end tension, at the length hi
        best = minimize_scalar(
            lambda t: f(chord * math.exp(t)), bounds=(-0.5, 3.0), method="bounded"
        )
        hi = chord * math.exp(float(best.x))
        least = f(hi) + target
        if least > target:
            raise InputError(key, target, f"at least {least:.6g} N (the least end tension)")
    grow = 1.0 if kind == "sag" else -1.0  # the sign of f at a long line
    while kind != "end_tension" and grow * f(hi) <= 0.0 and hi < 1e3 * chord:
        hi *= 2.0
    while (grow * f(lo) >= 0.0 if kind != "end_tension" else f(lo) <= 0.0) and lo > 1e-3 * chord:
        lo *= 0.5
    if f(lo) * f(hi) > 0.0:
        span_ = f"{lo:.6g} and {hi:.6g} m"
        raise InputError(key, target, f"a target that an unstretched length between {span_} meets")
    return float(brentq(f, lo, hi, xtol=1e-12 * chord, rtol=1e-14))
