"""Buckling: the load factors at which the tangent along the static path becomes singular.

One implementation over :class:`~rancf.system.System` (a one-body model is its one-body system)
and its static problem :class:`~rancf.solvers.system_equilibrium.SystemEquilibrium`: unknowns
``z = (y, λ)``, coordinates and multipliers, with the bordered Jacobian ``J = [K Gᵀ; G 0]``
(:mod:`rancf.solvers.linearized`).  About a state ``(z*, p*)`` — the reference (``p* = 0``) or
the static equilibrium under the full loads (``p* = 1``, installed supports held where they
are) — the loads grow as ``p = p* + μ``.

1. **Linearized estimate** (Bathe, *Finite Element Procedures*, 2014, sec. 6.8.2): the path's
   direction ``u = dz/dp = J₀⁻¹ q`` (``q`` the loads' direction), the tangent's derivative
   along it ``J_σ = [J(z* + h u, p* + h) - J(z* - h u, p* - h)] / 2h`` (central differences of
   the exact tangent, ``h |u| =`` :data:`STEP` of the system's size: an error of order ``h²``;
   the multipliers' change carries the constraints' curvature, the load factor the loads'
   stiffness), and the pencil ``(J₀ + μ J_σ) φ = 0`` on the free coordinates and the
   multipliers, solved as ``-J_σ φ = (1/μ) J₀ φ``: symmetric-definite (``sygvd``) without
   constraints and with symmetric tangents, else QZ, balanced by the stiffness diagonal.
2. **Located on the nonlinear path.**  The linear model ``J₀ + μ J_σ`` of the tangent is
   poor where stiff elements rotate: the tangent of an element turned by ``θ`` is
   ``R K Rᵀ``, whose first-order part ``K + θ[W, K]`` is singular at ``θ ~ √(k_soft/k_stiff)``;
   very short elements (a small corner fillet meshed like the long spans) give spurious factors
   that fall with the element length, and pollute the true ones.  So the factors only guide a
   search on the static path itself: at factors (ascending; each at least :data:`THIN` above
   the last one checked) the equilibrium ``z(p* + μ)`` is found by Newton from the
   previous one, and the number of negative eigenvalues of its tangent on the constraints'
   null space is counted (Sylvester's law of inertia on the bordered ``J``, dense ``LDLᵀ``: its
   negative count minus ``m``; a non-symmetric or large tangent: the parity of ``det J``, which
   finds the first critical load only).  Where
   the count rises, the critical loads are bracketed and bisected to :data:`REFINE_TOL`; the
   mode is the tangent's null vector there (inverse iteration ``K(p) φ' = K₀ φ``).  Spurious
   factors leave the count unchanged.  For a straight pre-buckling path (an Euler column) the
   load found is the linear one; otherwise it is the bifurcation load of the path.

A mechanism (rigid motions the tangent does not resist), loads that never buckle the structure,
factors none of which the path confirms, and a tangent whose round-off hides its softest
stiffness (:data:`RESOLUTION`; very short stiff elements beside long ones: the range of element
lengths is given) are refused in one line.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Literal

import numpy as np
import scipy.linalg
import scipy.sparse as sp
import scipy.sparse.linalg as spla
from numpy.typing import NDArray

from rancf.bodies.flexible import Model
from rancf.errors import ConvergenceError, InputError
from rancf.solvers.linearized import Linearized, linearize
from rancf.solvers.modal import is_symmetric, rigid_motions
from rancf.solvers.system_equilibrium import SystemEquilibrium
from rancf.system import System, as_system
from rancf.system.sliding import start_multipliers

__all__ = ["BucklingResult", "linear_buckling"]

#: Central-difference step of the tangent along the path: ``h |u|`` relative to the size.
STEP = 1e-4
#: Relative width of the bracket at which the bisection of a critical load stops.
REFINE_TOL = 1e-5
#: After a check at ``μ``, the next check is at the first factor above ``(1 + THIN) μ``: the
#: inertia counts every critical load below a check, so none is missed between checks.
THIN = 1.0
#: Factors checked along the path before giving up.
MAX_CHECKED = 60
#: Newton on the path: scaled increments at most this (round-off of very short elements leaves
#: increments of 1e-10 in their stiffness).
NEWTON_TOL = 1e-9
#: The largest round-off of the softest stiffness of the tangent, relative to it, that is
#: accepted (the bound is pessimistic: the loads found are then within about 1e-2 of it).
RESOLUTION = 0.5
#: Pencils up to this size are solved densely; larger ones by Arnoldi.
DENSE = 2000


@dataclass(frozen=True)
class BucklingResult:
    """Critical load factors (ascending; totals: multiples of the scenario's loads) and mode
    shapes in full coordinates ``(count, n)`` (largest component +1)."""

    load_factors: NDArray[np.float64]
    modes: NDArray[np.float64]
    about: str
    symmetric: bool


class _Path:
    """The static path ``z(p)`` followed by Newton, and the linearized system on it."""

    def __init__(
        self, system: System, problem: SystemEquilibrium, z: NDArray, p: float, u: NDArray
    ) -> None:
        self.system, self.problem, self.u = system, problem, u
        self.z, self.p = z.copy(), p

    def lin(self, z: NDArray, p: float) -> Linearized:
        n = self.system.n
        return linearize(self.system, z[:n], z[n:], p)

    def go(self, p: float, depth: int = 0) -> None:
        """Move the state to the equilibrium at ``p`` (predictor along ``u``, Newton; halved
        steps where Newton fails)."""
        z = self.z + (p - self.p) * self.u
        for _ in range(30):
            r, ok = self.problem.tangent(z, p)
            dz = self.problem.solve(ok, -r)
            if dz is None:
                break
            z = z + dz
            if self.problem.norm(dz) <= NEWTON_TOL:
                self.z, self.p = z, p
                return
        if depth >= 6:
            raise ConvergenceError(
                f"the static path could not be followed to load factor {p:.6g} "
                "to check the buckling loads"
            )
        mid = 0.5 * (self.p + p)
        self.go(mid, depth + 1)
        self.go(p, depth + 1)


def linear_buckling(
    model: Model | System,
    count: int = 3,
    about: Literal["reference", "static"] = "reference",
    y: NDArray | None = None,
    lam: NDArray | None = None,
) -> BucklingResult:
    """Critical load factors of the loads of ``model`` (module docstring).

    Parameters
    ----------
    model : System or Model
    count : int
        Number of load factors (the smallest positive ones).
    about : {"reference", "static"}
    y, lam : ndarray, optional
        ``about = "static"``: the equilibrium under the full loads and its multipliers (e.g.
        ``solve_static(system)``'s ``y`` and ``lam``, with the rod triads it leaves); ``y``
        required then.

    Raises
    ------
    InputError
        ``count`` < 1, ``about`` unknown or ``y`` missing.
    ConvergenceError
        A mechanism, loads that never buckle the structure, or factors the static path does
        not confirm.
    """
    if isinstance(count, bool) or int(count) != count or count < 1:
        raise InputError("--count", count, "an integer >= 1")
    if about not in ("reference", "static"):
        raise InputError("--about", about, 'one of "reference", "static"')
    system = as_system(model)
    if any(j.entry.slides for j in system.joints):
        raise InputError(
            "joints.kind",
            "sliding",
            "no sliding joint in a buckling analysis (statics, modes and dynamics take them)",
        )
    problem = SystemEquilibrium(system)
    if about == "reference":
        system.reset_triads()
        z0, p0 = problem.start(), 0.0
    else:
        if y is None:
            raise InputError("y", None, "the static equilibrium when about = 'static'")
        mult = start_multipliers(system) if lam is None else np.asarray(lam, dtype=float)
        z0, p0 = np.r_[np.asarray(y, dtype=float), mult], 1.0
    problem.stage = 0  # the loads grow with p; held coordinates stay where they are in z
    n, free = system.n, ~system.fixed
    lin0 = _lin(system, z0, p0)
    if rigid_motions(system, z0[:n], lin0).shape[1]:
        raise ConvergenceError(
            "the tangent stiffness is singular: the structure is a mechanism (add supports)"
        )
    j0 = lin0.bordered()
    _check_resolution(system, lin0, j0)
    rows = np.r_[np.flatnonzero(free), n + np.arange(system.m)]
    q = problem.load_vector(z0, True)[rows]
    u = np.zeros(n + system.m)
    u[rows] = spla.splu(j0).solve(q)
    umax = float(np.max(np.abs(u * problem.scale)))
    if not umax > 0.0:
        raise ConvergenceError("the loads do not deform the structure: nothing can buckle")
    h = STEP / umax
    jp, jm = _lin(system, z0 + h * u, p0 + h), _lin(system, z0 - h * u, p0 - h)
    js = (jp.bordered() - jm.bordered()) / (2.0 * h)
    mu, phi, symmetric = _pencil(j0, js, lin0.k.shape[0], count)
    path = _Path(system, problem, z0, p0, u)
    factors, shapes = _confirm(path, lin0, mu, phi, count, p0)
    if about == "reference":
        system.reset_triads()
    modes = np.zeros((len(factors), n))
    for i, x in enumerate(shapes):
        modes[i, free] = x
        modes[i] /= modes[i, np.argmax(np.abs(modes[i]))]
    return BucklingResult(np.array(factors), system.q_from_y(modes), about, symmetric)


def _check_resolution(system: System, lin0: Linearized, j0: sp.spmatrix) -> None:
    """Refuse a tangent whose round-off hides its softest stiffness: for the softest mode ``x``
    of ``K₀`` on the constraints' null space (inverse iteration), the bound
    ``ε |x|ᵀ |K₀| |x|`` of the round-off of ``xᵀ K₀ x`` above :data:`RESOLUTION` of it (very
    short, stiff elements beside long ones)."""
    n_free, m = lin0.k.shape[0], lin0.g.shape[0]
    lu = spla.splu(j0)
    x = np.random.default_rng(0).standard_normal(n_free)
    for _ in range(30):
        x = lu.solve(np.r_[x, np.zeros(m)])[:n_free]
        x /= np.abs(x).max()
    bound = np.finfo(float).eps * float(np.abs(x) @ (abs(lin0.k) @ np.abs(x)))
    ratio = bound / abs(float(x @ (lin0.k @ x)))
    if not ratio <= RESOLUTION:
        raise ConvergenceError(
            f"the tangent's round-off is {ratio:.2g} times its softest stiffness, so no buckling "
            f"load is resolved in double precision: {_mesh_hint(system)}"
        )


def _lin(system: System, z: NDArray, p: float) -> Linearized:
    return linearize(system, z[: system.n], z[system.n :], p)


def _pencil(
    j0: sp.spmatrix, js: sp.spmatrix, n_free: int, count: int
) -> tuple[NDArray, NDArray, bool]:
    """Positive ``μ`` (ascending) and modes (coordinates, columns) of ``(J₀ + μ J_σ) φ = 0``
    (module docstring, step 1)."""
    size = j0.shape[0]
    dk = np.abs(j0.diagonal()[:n_free])
    kbar = float(np.mean(dk[dk > 0])) if np.any(dk > 0) else 1.0
    d = np.r_[1.0 / np.sqrt(np.where(dk > 0, dk, kbar)), np.full(size - n_free, np.sqrt(kbar))]
    bal = sp.diags(d)
    a, b = (bal @ (-js) @ bal).tocsc(), (bal @ j0 @ bal).tocsc()
    symmetric = size == n_free and is_symmetric(j0) and is_symmetric(js)
    pairs = None
    if size <= DENSE:
        ad, bd = a.toarray(), b.toarray()
        if symmetric:
            try:
                pairs = scipy.linalg.eigh(0.5 * (ad + ad.T), 0.5 * (bd + bd.T))
            except np.linalg.LinAlgError:
                symmetric = False
        if pairs is None:
            pairs = scipy.linalg.eig(ad, bd)
    else:
        lu = spla.splu(b)
        op = spla.LinearOperator(a.shape, matvec=lambda x: lu.solve(a @ x), dtype=float)
        pairs = spla.eigs(op, k=min(count + MAX_CHECKED, size - 2), which="LR", tol=1e-10)
        symmetric = False
    inv_mu, vec = pairs
    inv_mu = np.asarray(inv_mu)
    real = np.isfinite(inv_mu) & (np.abs(np.imag(inv_mu)) <= 1e-8 * np.abs(inv_mu))
    pos = real & (np.real(inv_mu) > 0.0)
    if not np.any(pos):
        raise ConvergenceError("no positive buckling load factor: these loads never buckle it")
    mu = 1.0 / np.real(inv_mu[pos])
    vec = (d[:, None] * np.real(vec[:, pos]))[:n_free]
    order = np.argsort(mu)
    return mu[order], vec[:, order], bool(symmetric)


def _negative(lin: Linearized) -> int:
    """The number of negative eigenvalues of ``K`` on the null space of ``G``: the inertia of
    the bordered ``J`` (Sylvester: ``neg(J) = neg(K|ker G) + m``, dense ``LDLᵀ``) when ``K``
    is symmetric and small; else the parity of ``det J`` (sparse LU: 0 or 1)."""
    j, m = lin.bordered(), lin.g.shape[0]
    if j.shape[0] <= DENSE and is_symmetric(lin.k):
        dk = np.abs(lin.k.diagonal())
        kbar = float(np.mean(dk[dk > 0])) if np.any(dk > 0) else 1.0
        bal = np.r_[1.0 / np.sqrt(np.where(dk > 0, dk, kbar)), np.full(m, np.sqrt(kbar))]
        jb = bal[:, None] * j.toarray() * bal[None, :]  # a congruence: the inertia is kept
        _, d, _ = scipy.linalg.ldl(0.5 * (jb + jb.T), lower=True)
        neg, i = 0, 0
        while i < d.shape[0]:
            if i + 1 < d.shape[0] and d[i + 1, i] != 0.0:
                neg += int(np.sum(np.linalg.eigvalsh(d[i : i + 2, i : i + 2]) < 0.0))
                i += 2
            else:
                neg += int(d[i, i] < 0.0)
                i += 1
        return neg - m
    lu = spla.splu(j.tocsc())
    sign = np.prod(np.sign(lu.U.diagonal())) * _perm_sign(lu.perm_r) * _perm_sign(lu.perm_c)
    return int(sign < 0) if m % 2 == 0 else int(sign > 0)


def _perm_sign(p: NDArray) -> int:
    seen, sign = np.zeros(p.size, dtype=bool), 1
    for i in range(p.size):
        if not seen[i]:
            j, length = i, 0
            while not seen[j]:
                seen[j], j, length = True, p[j], length + 1
            sign *= -1 if length % 2 == 0 else 1
    return sign


def _confirm(
    path: _Path, lin0: Linearized, mu: NDArray, phi: NDArray, count: int, p0: float
) -> tuple[list[float], list[NDArray]]:
    """The critical loads on the static path, bracketed by the inertia of its tangent at the
    linearized factors and refined by bisection (module docstring, step 2)."""
    n0 = _negative(lin0)
    found: list[tuple[float, NDArray]] = []
    checked = []
    prev, n_prev = p0, n0
    targets: list[float] = []
    for m_i in mu:  # ascending; candidates closer than THIN are checked together
        if not targets or m_i > (targets[-1] - p0) * (1.0 + THIN):
            targets.append(p0 + m_i)
    x_by_p = dict(zip((p0 + mu).tolist(), phi.T, strict=True))
    for p in targets[:MAX_CHECKED]:
        path.go(p)
        n_p = _negative(path.lin(path.z, p))
        checked.append(p)
        if n_p > n_prev:
            _bisect(path, prev, n_prev, p, n_p, found, count, x_by_p.get(p), lin0)
        if len(found) >= count:
            break
        prev, n_prev = p, n_p
    if not found:
        head = ", ".join(f"{c:.4g}" for c in checked[:4])
        raise ConvergenceError(
            f"no linearized buckling factor ({head}, ...) is confirmed on the static path (its "
            f"tangent stays positive definite there): {_mesh_hint(path.system)}"
        )
    found.sort(key=lambda t: t[0])
    return [f for f, _ in found[:count]], [x for _, x in found[:count]]


def _bisect(
    path: _Path,
    a: float,
    na: int,
    b: float,
    nb: int,
    found: list,
    count: int,
    x: NDArray | None,
    lin0: Linearized,
) -> None:
    """Critical loads in ``(a, b]`` where the negative count goes from ``na`` to ``nb``."""
    if len(found) >= count or nb <= na:
        return
    if b - a <= REFINE_TOL * max(abs(b), 1e-300):
        for _ in range(nb - na):
            found.append((b, _mode(path, lin0, b, x)))
        return
    mid = 0.5 * (a + b)
    path.go(mid)
    nm = _negative(path.lin(path.z, mid))
    _bisect(path, a, na, mid, nm, found, count, x, lin0)
    _bisect(path, mid, nm, b, nb, found, count, x, lin0)


def _mode(path: _Path, lin0: Linearized, p: float, x: NDArray | None) -> NDArray:
    """The mode of the tangent at the critical load ``p``: inverse iteration ``K(p) x' = K₀ x``
    on the null space of ``G`` (bordered solves)."""
    path.go(p)
    lin = path.lin(path.z, p)
    k0, n_free = lin0.k, lin0.k.shape[0]
    rng = np.random.default_rng(0)
    x = rng.standard_normal(n_free) if x is None else x
    try:
        lu = spla.splu(lin.bordered())
    except RuntimeError:  # exactly singular
        return x
    for _ in range(8):
        x = lu.solve(np.r_[k0 @ x, np.zeros(lin.g.shape[0])])[:n_free]
        x /= np.abs(x).max()
    return x


def _cos(k0: sp.spmatrix, a: NDArray, b: NDArray) -> float:
    return float(a @ (k0 @ b)) / np.sqrt(abs(float(a @ (k0 @ a)) * float(b @ (k0 @ b))))


def _mesh_hint(system: System) -> str:
    """What to change: the element lengths of the flexible bodies."""
    lengths = []
    for b in system.flex:
        pos = b.node_positions(b.q0)
        lengths.append(np.linalg.norm(np.diff(pos, axis=0), axis=1))
    if not lengths:
        return "check the loads and supports"
    ell = np.concatenate(lengths)
    return (
        f"elements from {ell.min():.3g} m to {ell.max():.3g} m long; use fewer, longer "
        "elements where the spans are short (mesh.elements)"
    )
