"""The records the compiled integrator's and system's entry points take, two a call: what to
work on and how (the convention of :mod:`rancf.kernels.records`).

``SystemIntegrator.run(RunBuffers, RunOptions)``, ``SystemIntegrator.factor_static`` and
``static_increment(StaticPoint, StaticOptions)``, ``System.residual(ResidualPoint,
ResidualOptions)`` (the balance residual and the constraints), ``System.sparse_jacobian`` and
``dense_jacobian(StatePoint, TangentOptions)`` (statics and modes).  Arrays are float64 and
C-contiguous; those written in place are never converted (a wrong one is refused in one line
naming its field).
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

import numpy as np
from numpy.typing import NDArray

from rancf.kernels import _core

__all__ = [
    "RunBuffers",
    "RunOptions",
    "ResidualOptions",
    "ResidualPoint",
    "StaticPoint",
    "StaticOptions",
    "StatePoint",
    "TangentOptions",
    "evaluator",
]


@dataclass(frozen=True, eq=False)
class RunBuffers:
    """The arrays a run of fixed steps writes in place (float64, C-contiguous): the state ``y``,
    ``v``, ``a``, ``w`` (algorithmic accelerations) ``(n,)`` and ``lam`` ``(m,)``; the stored
    rows ``out_y``, ``out_v`` ``(k, n)``, ``out_l`` ``(k, m)``, ``out_e`` ``(k, 3)`` energies
    (or None); ``out_yf``, ``out_vf`` ``(k, n)`` each row's step's α point (systems with contact,
    both or neither)."""

    y: NDArray[np.float64]
    v: NDArray[np.float64]
    a: NDArray[np.float64]
    w: NDArray[np.float64]
    lam: NDArray[np.float64]
    out_y: NDArray[np.float64]
    out_v: NDArray[np.float64]
    out_l: NDArray[np.float64]
    out_e: NDArray[np.float64] | None = None
    out_yf: NDArray[np.float64] | None = None
    out_vf: NDArray[np.float64] | None = None


@dataclass(frozen=True)
class RunOptions:
    """A run of fixed steps (``SystemIntegrator::run``, ``src/cpp/solvers/system_integrator.hpp``):
    from ``t0`` with steps ``h``, ``n_steps`` of them, a row stored every ``out_every`` counted
    from ``done_before`` steps already taken, stopping after ``max_seconds`` of wall time; with
    ``out_dt > 0`` the steps' times are ``out_dt k + i h`` from the last output ``k_last``."""

    t0: float
    h: float
    n_steps: int
    out_every: int = 1
    done_before: int = 0
    max_seconds: float = 1e300
    out_dt: float = 0.0
    k_last: int = 0


@dataclass(frozen=True, eq=False)
class StaticPoint:
    """Where the statics' entry points evaluate: ``y`` ``(n,)``, ``lam`` ``(m,)``; written in
    place: ``residual`` ``(n + m,)`` and (``static_increment``) the increments ``dy``, ``dlam``."""

    y: NDArray[np.float64]
    lam: NDArray[np.float64]
    residual: NDArray[np.float64]
    dy: NDArray[np.float64] | None = None
    dlam: NDArray[np.float64] | None = None


@dataclass(frozen=True)
class StaticOptions:
    """The statics' loads: times ``load_factor``, at their ``amplitude`` (else at time ``t``);
    ``stab > 0`` adds ``stab M`` to the factored Jacobian (the residual unchanged)."""

    load_factor: float = 1.0
    amplitude: bool = False
    t: float = 0.0
    stab: float = 0.0


@dataclass(frozen=True, eq=False)
class StatePoint:
    """A state ``(y, v, a)`` ``(n,)`` each and multipliers ``lam`` ``(m,)``."""

    y: NDArray[np.float64]
    v: NDArray[np.float64]
    a: NDArray[np.float64]
    lam: NDArray[np.float64]


@dataclass(frozen=True)
class TangentOptions:
    """A Jacobian ``ck ∂/∂y + cv ∂/∂v + ca ∂/∂a`` at time ``t`` (``dynamic`` False: statics, no
    velocity or inertia terms; the loads times ``load_factor``, at their ``amplitude``)."""

    t: float
    ck: float
    cv: float = 0.0
    ca: float = 0.0
    dynamic: bool = True
    load_factor: float = 1.0
    amplitude: bool = False


@dataclass(frozen=True, eq=False)
class ResidualPoint:
    """Where ``System.residual`` evaluates: ``y`` ``(n,)``, ``lam`` ``(m,)``, and ``v``, ``a``
    ``(n,)`` where :attr:`ResidualOptions.dynamic` (unread in statics); written in place:
    ``residual`` ``(n + m,)`` (the balance, then the constraints).  ``contact_yf``,
    ``contact_vf``, ``contact_y1`` ``(n,)`` (all three or none): the contact forces of a time
    step, at its α point and end, instead of those at ``(y, v)``."""

    y: NDArray[np.float64]
    lam: NDArray[np.float64]
    residual: NDArray[np.float64]
    v: NDArray[np.float64] | None = None
    a: NDArray[np.float64] | None = None
    contact_yf: NDArray[np.float64] | None = None
    contact_vf: NDArray[np.float64] | None = None
    contact_y1: NDArray[np.float64] | None = None


@dataclass(frozen=True)
class ResidualOptions:
    """The residual at time ``t`` (``dynamic`` False: statics, no velocity or inertia terms; the
    loads times ``load_factor``, at their ``amplitude``; ``distributed_only``: the bodies' own
    terms only, no point loads, loads at places or springs)."""

    t: float = 0.0
    load_factor: float = 1.0
    amplitude: bool = False
    dynamic: bool = True
    distributed_only: bool = False


def evaluator(core: Any, damping: float = 0.0) -> Any:
    """A core integrator of the system ``core`` used only for what it evaluates at a given state
    (consistent accelerations, residuals, reactions), never to step: the trapezoidal scheme
    (``alpha_m = alpha_f = 0``, ``gamma = 1/2``, ``beta = 1/4``), mass-proportional ``damping``
    [1/s], one Newton iteration."""
    scheme = _core.Scheme(
        alpha_m=0.0,
        alpha_f=0.0,
        gamma=0.5,
        beta=0.25,
        damping=damping,
        tol=1e-10,
        max_iter=1,
        modified=False,
    )
    return _core.SystemIntegrator(core, scheme)
