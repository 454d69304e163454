"""Where a dynamic run stands: everything :func:`rancf.solvers.dynamic.integrate` needs to go on
from there as if it had never stopped.

A :class:`DynamicState` holds the time, the coordinates ``y``, velocities ``v``, accelerations
``a``, algorithmic accelerations ``w`` and multipliers ``λ`` of the generalized-α recurrence
(:mod:`rancf.solvers.dynamic`: the step from ``t_n`` reads ``y_n, v_n, a_n, w_n`` and the
multipliers as its first guess), the step size
the step control chose next, the place on the output grid, the rods' nodal triads (which the
solver carries along the path of the run and the coordinates alone do not fix) and the memory
of the compiled loop (modified Newton: the point its factored Jacobian was assembled at, so
that the same factors are rebuilt).  Contact and friction carry no state of their own: the
penalty and the regularized Coulomb law are functions of the step's states.

A run resumed from a state takes the same steps as the run that wrote it would have taken,
with the same numbers: its outputs continue the earlier ones.
"""

from __future__ import annotations

import io
import json
import zipfile
import zlib
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np
from numpy.typing import NDArray

from rancf.atomic import atomic_write
from rancf.errors import InputError

__all__ = ["DynamicState", "COUNTERS"]

#: The run's counters a state carries on (the resumed result counts the whole run).
COUNTERS = (
    "n_steps",
    "n_newton",
    "n_factorizations",
    "n_rejected",
    "n_outputs",
    "wall_time",
    "min_step_taken",
    "max_step_taken",
    "error_estimate",
    "error_time",
    "error_step",
)

#: The counters a resumed result does not take over as they stand: the factorizations go to
#: the integrator (``restore``), the Newton iterations and wall time so far to the run's base,
#: to which the resumed run adds its own.
_GOING_ON = ("n_newton", "n_factorizations", "wall_time")

#: Version 2 holds ``w`` (rancf 0.4, the Arnold–Brüls form); version 1's runs go on with
#: ``w = a`` (the start of a run).
_VERSION = 2

#: What reading a damaged ``.npz`` file raises (a truncated or edited archive).
NPZ_ERRORS = (OSError, ValueError, KeyError, TypeError, EOFError, zipfile.BadZipFile, zlib.error)


@dataclass
class DynamicState:
    """The state of a dynamic run after a stored output (see the module docstring).

    Attributes
    ----------
    t : float
        Time [s] the state is at.
    y, v, a : ndarray
        Model coordinates, velocities and accelerations ``(n,)``.
    w : ndarray
        Algorithmic accelerations of the Newmark relations ``(n,)``.
    lam : ndarray
        Multipliers of the constraints ``(m,)``.
    step : float
        The next step size [s] (adaptive runs; fixed steps: the step).
    k_out : int
        Output grid points passed (the next output is the ``k_out``-th after the initial one).
    within : int
        Fixed steps taken since the last output time (the compiled loop stops after any step).
    triads : list of ndarray
        Rods: each rod's nodal reference tangents and directors, body by body; else empty.
    memory : ndarray
        What the compiled loop keeps between steps (empty: nothing).
    counters : dict
        The run's counters so far (:data:`COUNTERS`).
    t_end : float
        The end time of the run that wrote the state.
    """

    t: float
    y: NDArray[np.float64]
    v: NDArray[np.float64]
    a: NDArray[np.float64]
    w: NDArray[np.float64]
    lam: NDArray[np.float64]
    step: float
    k_out: int = 0
    within: int = 0
    triads: list[NDArray[np.float64]] = field(default_factory=list)
    memory: NDArray[np.float64] = field(default_factory=lambda: np.empty(0))
    counters: dict[str, Any] = field(default_factory=dict)
    t_end: float = 0.0

    def copy(self) -> DynamicState:
        """A deep copy (the arrays of a running integration change in place)."""
        return DynamicState(
            self.t,
            self.y.copy(),
            self.v.copy(),
            self.a.copy(),
            self.w.copy(),
            self.lam.copy(),
            self.step,
            self.k_out,
            self.within,
            [x.copy() for x in self.triads],
            self.memory.copy(),
            dict(self.counters),
            self.t_end,
        )

    def to_bytes(self) -> bytes:
        """The state as an ``.npz`` archive (what :meth:`save` writes)."""
        meta = {
            "version": _VERSION,
            "t": self.t,
            "step": self.step,
            "k_out": self.k_out,
            "within": self.within,
            "counters": self.counters,
            "t_end": self.t_end,
            "n_triads": len(self.triads),
        }
        arrays: dict[str, Any] = {
            "y": self.y,
            "v": self.v,
            "a": self.a,
            "w": self.w,
            "lam": self.lam,
            "memory": self.memory,
        }
        arrays.update({f"triads_{i}": x for i, x in enumerate(self.triads)})
        buf = io.BytesIO()
        np.savez(buf, meta=np.array(json.dumps(meta)), **arrays)
        return buf.getvalue()

    def save(self, path: str | Path) -> None:
        """Write the state to ``path`` (``.npz``, atomically)."""
        atomic_write(path, self.to_bytes())

    @classmethod
    def load(cls, path: str | Path) -> DynamicState:
        """Read a state :meth:`save` wrote.

        Raises
        ------
        InputError
            Naming the file if it is missing or not a state.
        """
        try:
            with np.load(path, allow_pickle=False) as z:
                meta = json.loads(str(z["meta"]))
                arrays = {k: np.array(z[k], dtype=float) for k in z.files if k != "meta"}
            if meta.get("version") not in (1, _VERSION):
                raise ValueError(f"version {meta.get('version')}")
            triads = [arrays[f"triads_{i}"] for i in range(int(meta["n_triads"]))]
            w = arrays["w"] if meta["version"] == _VERSION else arrays["a"]
            return cls(
                float(meta["t"]),
                arrays["y"],
                arrays["v"],
                arrays["a"],
                w,
                arrays["lam"],
                float(meta["step"]),
                int(meta["k_out"]),
                int(meta["within"]),
                triads,
                arrays["memory"],
                dict(meta["counters"]),
                float(meta["t_end"]),
            )
        except NPZ_ERRORS as exc:
            raise InputError(
                "checkpoint", str(path), f"a state written by a rancf run (reading it: {exc})"
            ) from None

    def check_finite(self, where: str = "state") -> None:
        """Refuse a state with a number that is not finite, a time < 0, a step <= 0 or a
        count (``k_out``, ``within``, ``n_outputs``) that is not a whole number >= 0 (a damaged
        file).

        Raises
        ------
        InputError
            Naming the first such entry.
        """
        arrays = {
            "y": self.y,
            "v": self.v,
            "a": self.a,
            "w": self.w,
            "lam": self.lam,
            "memory": self.memory,
        }
        arrays.update({f"triads_{i}": x for i, x in enumerate(self.triads)})
        bad = [
            f"a NaN or infinite number in {k}"
            for k, x in arrays.items()
            if not np.all(np.isfinite(x))
        ]
        counts = {
            "k_out": self.k_out,
            "within": self.within,
            "n_outputs": self.counters.get("n_outputs", 0),
        }
        bad[:0] = [f"{k} = {n!r}" for k, n in counts.items() if not (isinstance(n, int) and n >= 0)]
        if not (np.isfinite(self.step) and self.step > 0.0):
            bad.insert(0, f"step = {self.step!r}")
        if not (np.isfinite(self.t) and self.t >= 0.0):
            bad.insert(0, f"t = {self.t!r}")
        if bad:
            raise InputError(
                where,
                bad[0],
                "a state of finite numbers, t >= 0, step > 0 and "
                "counts k_out, within, n_outputs >= 0",
            )

    def check_fits(self, n: int, m: int, triad_sizes: list[int], where: str = "state") -> None:
        """Refuse a state of another system: ``n`` coordinates, ``m`` multipliers and rods whose
        triads hold ``triad_sizes`` numbers.

        Raises
        ------
        InputError
            Naming what differs.
        """
        sizes = [x.size for x in self.triads]
        for what, have, want in (
            ("coordinates", self.y.size, n),
            ("multipliers", self.lam.size, m),
            ("rod triad numbers", sizes, triad_sizes),
        ):
            if have != want:
                raise InputError(where, f"{what} {have}", f"a state of this system ({what} {want})")


def triads_of(system: Any) -> list[NDArray[np.float64]]:
    """Copies of the rods' nodal reference tangents and directors, body by body."""
    return [
        x.copy()
        for b in system.flex
        if b.family.has_triads
        for x in (b.kernel.tref, b.kernel.m1ref)
    ]


def take_up(system: Any, integ: Any, state: DynamicState, result: Any, base: dict) -> tuple:
    """Put ``system`` (rods' triads), the integrator ``integ`` (its memory) and ``result`` (the
    counters; ``base`` gets the iterations and wall time so far) where ``state`` stands.

    Returns ``(t, y, v, a, w, lam, step, k_out, within)`` (copies: the run changes them in
    place).

    Raises
    ------
    InputError
        If the state is of another system.
    """
    rods = [b for b in system.flex if b.family.has_triads]
    sizes = [x.size for b in rods for x in (b.kernel.tref, b.kernel.m1ref)]
    state.check_fits(system.n, system.m, sizes)
    for i, b in enumerate(rods):
        b.kernel.tref[...] = state.triads[2 * i].reshape(b.kernel.tref.shape)
        b.kernel.m1ref[...] = state.triads[2 * i + 1].reshape(b.kernel.m1ref.shape)
    c = state.counters
    integ.restore(state.memory, int(c.get("n_factorizations", 0)))
    for key in COUNTERS:
        if key not in _GOING_ON and c.get(key) is not None:
            setattr(result, key, c[key])
    base["n_newton"] = int(c.get("n_newton", 0))
    base["wall_time"] = float(c.get("wall_time", 0.0))
    return (
        state.t,
        state.y.copy(),
        state.v.copy(),
        state.a.copy(),
        state.w.copy(),
        state.lam.copy(),
        state.step,
        state.k_out,
        state.within,
    )
