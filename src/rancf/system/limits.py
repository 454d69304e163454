"""The admissible range of the coordinates a run must not leave: a winch's length outside the
drum (``L > 0``: a driven drum's torque that reels in the whole line, or a length law of a
system built in Python that reaches 0; a scenario file's laws are refused when it is read,
:mod:`rancf.scenario.winches`) and the material coordinate of a
sliding joint on an open body (``0 <= σ <= elements``: past it, the rope's end has passed
through its guide and the joint would hold the end element continued beyond the body).

:func:`state_limits` gives :func:`rancf.solvers.dynamic.integrate` one function of a state that
names the first coordinate out of its range; the run stops at the first step that leaves it and
stores nothing from it on.
"""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

import numpy as np
from numpy.typing import NDArray

__all__ = ["state_limits", "LimitCheck"]

#: ``check(t, y, lam)``: None, or one line naming what left its range at time ``t``.
LimitCheck = Callable[[float, NDArray[np.float64], NDArray[np.float64]], "str | None"]


def _drums(system: Any) -> list[tuple[str, int]]:
    return sorted(getattr(system, "drums", {}).items(), key=lambda item: item[1])


def _laws(system: Any) -> list[tuple[str, Any]]:
    """``(name, L(t))`` of the winches whose length is given (a ``length`` or ``speed`` law)."""
    drums = getattr(system, "drums", {})
    lengths = getattr(system, "winch_lengths", {})
    return [
        (w.name, lengths[w.name])
        for w in getattr(system, "winches", ())
        if w.name not in drums and w.name in lengths
    ]


def _guides(system: Any) -> list[tuple[str, str, int, int]]:
    """``(joint name, body name, slot of σ in λ, elements)`` of the sliding joints on open
    bodies."""
    from rancf.system.sliding import sliding_body

    out = []
    for k, j in enumerate(getattr(system, "joints", ())):
        if not j.entry.slides:
            continue
        name, body = sliding_body(system, j)
        if not body.closed:
            out.append((str(j.name or k), name, system.joint_rows[k] + system.dim, body.n_el))
    return out


def state_limits(system: Any) -> LimitCheck | None:
    """The check of ``system``'s bounded coordinates (module docstring), or None if it has
    none."""
    drums, laws, guides = _drums(system), _laws(system), _guides(system)
    if not drums and not laws and not guides:
        return None

    def check(t: float, y: NDArray[np.float64], lam: NDArray[np.float64]) -> str | None:
        for name, index in drums:
            length = float(y[index])
            if not length > 0.0:
                return (
                    f"winch {name!r}: the length outside the drum is {length:.6g} m at "
                    f"t = {t:.6g} s, not > 0 (the drum has reeled in the whole line); the "
                    "run stops at the step before"
                )
        for name, f in laws:
            length = float(np.ravel(f.value(t))[0])
            if not length > 0.0:
                return (
                    f"winch {name!r}: its length law gives {length:.6g} m at t = {t:.6g} s, "
                    "not > 0; the run stops at the step before"
                )
        for joint, body, slot, n_el in guides:
            sigma = float(lam[slot])
            if not 0.0 <= sigma <= n_el:
                end = "start" if sigma < 0.0 else "end"
                return (
                    f"sliding joint {joint!r}: the {end} of body {body!r} passes through "
                    f"its place at t = {t:.6g} s (material coordinate {sigma:.6g} of "
                    f"0..{n_el} elements); the run stops at the step before (make the body "
                    "longer)"
                )
        return None

    return check


def first_outside(check: LimitCheck, ts: NDArray, ys: NDArray, lams: NDArray | None) -> int:
    """The index of the first row ``(ts[i], ys[i], lams[i])`` out of range, or -1."""
    for i in range(len(ts)):
        lam = lams[i] if lams is not None and len(lams) else np.empty(0)
        if check(float(ts[i]), ys[i], lam) is not None:
            return i
    return -1
