"""Linear buckling: load factors ``λ`` with ``(K₀ + λ K_σ) φ = 0`` and their mode shapes.

Linearized pre-buckling analysis (e.g. Bathe, *Finite Element Procedures*, 2014, sec. 6.8.2;
Wriggers, *Nonlinear Finite Element Methods*, 2008, sec. 7.2).  Along the load path of
:class:`~rancf.solvers.equilibrium.EquilibriumProblem` the tangent is ``K_T(y(λ), λ)``.  About a
state ``(y*, λ*)``:

* ``about = "reference"``: ``λ* = 0``, ``y* = y0``; the path is linearized, ``dy/dλ = K₀⁻¹ q``;
* ``about = "static"``: ``(y*, λ*)`` the static equilibrium at ``λ* = 1`` (pre-loaded state).

With ``K₀ = K_T(y*, λ*)``, ``u = dy/dλ = K₀⁻¹ q`` (``q = -∂r/∂λ``, supports installed along
the path included) and the derivative of the tangent along the path

    K_σ = d/dλ K_T(y* + λ u, λ* + λ)  at λ = 0

(by central differences of the exact tangent, step ``h`` with ``h |u| = 10⁻⁶`` of the model
size: an error of order ``h²``), the critical factors solve ``(K₀ + μ K_σ) φ = 0``; the load
factors are ``λ = λ* + μ``, positive ones in ascending order.  Solved as ``-K_σ φ = (1/μ) K₀ φ``
on the free coordinates: a symmetric-definite problem when ``K₀`` is positive definite and the
loads are conservative (LAPACK ``sygvd``), else the general QZ problem (real roots kept).
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Literal

import numpy as np
import scipy.linalg
from numpy.typing import NDArray

from rancf.bodies.flexible import Model
from rancf.errors import ConvergenceError, InputError
from rancf.solvers.equilibrium import EquilibriumProblem
from rancf.solvers.modal import rigid_body_modes, unresisted_motions

__all__ = ["BucklingResult", "linear_buckling"]


@dataclass(frozen=True)
class BucklingResult:
    """Critical load factors (ascending) and mode shapes in full coordinates ``(count, n)``
    (largest component +1)."""

    load_factors: NDArray[np.float64]
    modes: NDArray[np.float64]
    about: str
    symmetric: bool


def linear_buckling(
    model: Model,
    count: int = 3,
    about: Literal["reference", "static"] = "reference",
    y: NDArray | None = None,
) -> BucklingResult:
    """Linear buckling load factors of the model's loads (module docstring).

    Parameters
    ----------
    model : Model
    count : int
        Number of load factors (the smallest positive ones).
    about : {"reference", "static"}
    y : ndarray, optional
        ``about = "static"``: the equilibrium at ``λ = 1`` (e.g. ``solve_static(model).y``,
        with the rod triads it leaves); required then.

    Raises
    ------
    InputError
        ``count`` < 1, ``about`` unknown or ``y`` missing.
    ConvergenceError
        When the tangent about the state is singular (a mechanism) or no positive load factor
        exists (the loads never buckle the structure).
    """
    if isinstance(count, bool) or int(count) != count or count < 1:
        raise InputError("--count", count, "an integer >= 1")
    if about not in ("reference", "static"):
        raise InputError("--about", about, 'one of "reference", "static"')
    problem = EquilibriumProblem(model)
    if about == "reference":
        model.reset_triads()
        ys, lam0 = model.y0.copy(), 0.0
    else:
        if y is None:
            raise InputError("y", None, "the static equilibrium when about = 'static'")
        # the end of the path: loads on, supports installed
        ys, lam0 = np.asarray(y, dtype=float), problem.stages[-1][1]
        problem.stage = len(problem.stages) - 1
    _, k0 = problem.tangent(ys, lam0)
    free = problem.free
    kd = _dense_tangent(problem, ys, lam0)
    mass = model.dense(model.mass_band)[np.ix_(free, free)]
    rigid = unresisted_motions(rigid_body_modes(model, ys)[free], kd[np.ix_(free, free)], mass)
    u = problem.solve(k0, _loads(problem, ys, k0)) if rigid.shape[1] == 0 else None
    if u is None:
        raise ConvergenceError(
            "the tangent stiffness is singular: the structure is a mechanism (add supports)"
        )
    umax = float(np.max(np.abs(u * problem.scale)))
    if not umax > 0.0:
        raise ConvergenceError("the loads do not deform the structure: nothing can buckle")
    h = 1e-6 / umax
    kp = _dense_tangent(problem, ys + h * u, lam0, h)
    km = _dense_tangent(problem, ys - h * u, lam0, -h)
    ks = (kp - km) / (2.0 * h)
    a, b = -ks[np.ix_(free, free)], kd[np.ix_(free, free)]
    symmetric = problem.conservative and np.allclose(b, b.T, rtol=0, atol=1e-9 * np.abs(b).max())
    inv_mu = None
    if symmetric:
        try:
            inv_mu, phi = scipy.linalg.eigh(0.5 * (a + a.T), 0.5 * (b + b.T))
        except np.linalg.LinAlgError:
            symmetric = False
    if not symmetric:
        w, phi = scipy.linalg.eig(a, b)
        real = np.isfinite(w) & (np.abs(w.imag) <= 1e-8 * np.maximum(np.abs(w.real), 1e-300))
        inv_mu, phi = w.real[real], phi[:, real].real
    pos = inv_mu > 0.0
    if not np.any(pos):
        raise ConvergenceError("no positive buckling load factor: these loads never buckle it")
    mu = 1.0 / inv_mu[pos]
    phi = phi[:, pos]
    order = np.argsort(mu)[:count]
    modes = np.zeros((order.size, model.n))
    modes[:, free] = phi[:, order].T
    modes /= modes[np.arange(order.size), np.argmax(np.abs(modes), axis=1)][:, None]
    base = problem.load_factor(lam0)  # 0 about the reference, 1 about the loaded state
    return BucklingResult(base + mu[order], model.q_from_y(modes), about, bool(symmetric))


def _loads(problem: EquilibriumProblem, y: NDArray, ab: NDArray) -> NDArray[np.float64]:
    """The loads' direction of the path (``f_ext`` on the free rows), whatever the stage."""
    stage, problem.stage = problem.stage, 0
    try:
        return problem.load_vector(y, ab)
    finally:
        problem.stage = stage


def _dense_tangent(
    problem: EquilibriumProblem, y: NDArray, p: float, dlam: float = 0.0
) -> NDArray[np.float64]:
    """The dense tangent at ``y`` with the supports of ``p`` and the loads ``dlam`` more than
    at ``p`` (only point moments make the tangent depend on the load level)."""
    y = np.array(y, dtype=float)
    problem.place_supports(y, p)
    _, ab = problem.tangent(y, p)
    if dlam and not problem.conservative:
        m = problem.model
        ab = ab - dlam * m.load_stiffness(problem._t, y, problem._amp)
    return problem.model.dense(ab)
