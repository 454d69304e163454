"""Natural frequencies and mode shapes of a system linearized about a configuration.

One implementation for every scenario: a one-body :class:`~rancf.bodies.flexible.Model` is solved
as the :class:`~rancf.system.System` of that one body (:func:`rancf.solvers.linearized.
as_system`).  Linearized about a configuration ``y*`` with multipliers ``λ`` (an equilibrium;
the unloaded reference with ``λ = 0`` by default), free vibrations ``y = y* + φ e^{iωt}`` of the
constrained equations satisfy

    K φ + Gᵀ μ = ω² M φ,        G φ = 0

with the tangent ``K`` (constraint curvature through ``λ``; about a loaded state the load
stiffness of configuration-dependent loads, e.g. a rod's point moments, at the loads' full
amplitude), the constraint Jacobian ``G`` and the mass ``M`` on the free coordinates
(:mod:`rancf.solvers.linearized`).  Its eigenvalues are those of ``K`` on the null space of
``G``:

* up to :data:`DENSE` unknowns, and whenever all modes are asked (``count=None``), densely: an
  orthonormal basis ``N`` of ``ker G`` (none without constraints), ``Nᵀ K N φ = λ Nᵀ M N φ``,
  symmetric-definite (LAPACK ``sygvd``, :func:`scipy.linalg.eigh`) when ``K`` is symmetric to
  :data:`SYM_RTOL` of ``√(|K_ii K_jj|)``, else the general QZ problem (:func:`scipy.linalg.eig`);
* beyond, the bordered pencil ``[K Gᵀ; G 0]``, ``[M 0; 0 0]``, balanced by the square roots of
  the stiffness diagonal, by shift-invert Arnoldi (ARPACK, :func:`scipy.sparse.linalg.eigs`) on
  ``(K - σM)⁻¹ M`` with a sparse LU, ``σ`` :data:`SHIFT` times the median stiffness-to-mass
  ratio; a pair is kept if its residual ``|K φ - ω² M φ|`` is below 10⁻⁶ of
  ``|K φ| + (|ω²| + |σ|) |M φ|``.

The eigenvalues ``λ = ω²`` may be negative (divergence: about a state past a buckling load) or
complex (flutter, a non-symmetric load stiffness): a motion ``e^{st}`` with ``s² = -λ``,
``√λ = a + ib`` (principal root) oscillates at ``a / 2π`` Hz and one of its roots grows like
``e^{|b| t}``: reported as ``growth_rates`` [1/s], never dropped.  Eigenvalues within
:data:`ZERO_RTOL` of the median stiffness-to-mass ratio of the diagonals of zero are round-off
(either sign): frequency and growth rate 0.

Rigid-body modes are the zero-frequency modes of the actual problem that are rigid motions:
every body's infinitesimal rigid motions (a flexible body's translations and rotations its
supports allow, :func:`rigid_candidates`; all of a rigid body's or point mass's coordinates)
restricted to ``ker G`` are the candidates; the part the tangent does not resist
(:func:`unresisted_motions`: the null space of ``Rᵀ K R`` to :data:`FD_RTOL` of
``|R|ᵀ |K| |R|``, above the error of the tangent's central-difference parts) are the rigid-body
motions and mechanisms (a free body's 3 or 6, a pendulum's swing about its reference, a crank
turning).  About a loaded state a rigid motion can be resisted by the loads: a hanging
pendulum's swing is a real mode, not a rigid-body mode.  Eigenvectors lying in the rigid
subspace (M-norm share above 0.99) are removed; ``n_rigid`` is the dimension of that subspace.
Any other zero or near-zero frequency is reported as it is (a curved spatial cable's
out-of-plane bending, which the magnitude curvature does not resist: docs/guide/rods.md).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import scipy.linalg
import scipy.sparse as sp
import scipy.sparse.linalg as spla
from numpy.typing import NDArray

from rancf.bodies.flexible import Model
from rancf.errors import InputError, RancfError
from rancf.solvers.linearized import Linearized, linearize
from rancf.system import System, as_system

__all__ = [
    "ModalResult",
    "natural_modes",
    "rigid_candidates",
    "rigid_motions",
    "tangent_stiffness",
    "unresisted_motions",
]

#: Problems up to this many unknowns (free coordinates and multipliers) are solved densely.
DENSE = 300
#: The shift of the Arnoldi iteration, relative to the median stiffness-to-mass ratio.
SHIFT = -1e-8
#: Zero stiffness of a rigid candidate, relative to its size: above the error of the central
#: differences of the tangent's spring, load and constraint-curvature parts (step 1e-6).
FD_RTOL = 1e-9
#: Eigenvalues ``|λ|`` below this share of the median stiffness-to-mass ratio of the diagonals
#: are round-off: frequency and growth rate 0.
ZERO_RTOL = 1e-12
#: A tangent is symmetric when ``|K_ij - K_ji| <= SYM_RTOL √(|K_ii K_jj|)``.
SYM_RTOL = 1e-8


@dataclass(frozen=True)
class ModalResult:
    """Frequencies (Hz, ascending, rigid-body modes removed) and full-coordinate mode shapes.

    Attributes
    ----------
    frequencies_hz : ndarray
        ``Re √λ / 2π`` (0 for ``λ <= 0``).
    modes : ndarray
        ``(count, n)`` shapes in full coordinates, M-normalized.  A complex mode (flutter) is
        stored as the real part of ``φ`` scaled so that ``φᴴ M φ = 1`` and its largest
        component is real and positive (the shape when that component peaks).
    n_rigid : int
        The dimension of the unresisted rigid motions and mechanisms (removed).
    eigenvalues : ndarray
        ``λ = ω²``: real for the symmetric problem, complex for the general one.
    growth_rates : ndarray
        ``|Im √λ|`` [1/s]: 0 for a stable mode, the e-folding rate of the growing root of an
        unstable one (flutter if the frequency is > 0, divergence if it is 0).
    symmetric : bool
        True when the symmetric problem was solved.
    """

    frequencies_hz: NDArray[np.float64]
    modes: NDArray[np.float64]
    n_rigid: int
    eigenvalues: NDArray[np.float64] | NDArray[np.complex128]
    growth_rates: NDArray[np.float64]
    symmetric: bool = True


def rigid_candidates(model: Model, y: NDArray) -> NDArray[np.float64]:
    """Infinitesimal rigid motions (translations, rotations about the centre of the nodes) of
    one flexible body's configuration ``y`` that its supports allow, ``(n, n_r)`` (model
    coordinates; combinations with zero held components)."""
    q = model.q_from_y(y)
    dim, dpn = model.dim, model.dpn
    nodes = q.reshape(model.n_nodes, dpn)
    pos = nodes[:, :dim]
    centre = pos.mean(axis=0)
    cols = []
    for i in range(dim):  # translations
        v = np.zeros_like(nodes)
        v[:, i] = 1.0
        cols.append(v.ravel())
    axes = [np.array([0.0, 0.0, 1.0])] if dim == 2 else list(np.eye(3))
    for w in axes:  # rotations
        v = np.zeros_like(nodes)
        if dim == 2:
            rel = pos - centre
            v[:, 0], v[:, 1] = -rel[:, 1], rel[:, 0]
            if not model.family.gradient:
                v[:, 2] = 1.0
            else:
                g = nodes[:, 2:4]
                v[:, 2], v[:, 3] = -g[:, 1], g[:, 0]
        else:
            v[:, :3] = np.cross(w, pos - centre)
            v[:, 3:6] = np.cross(w, nodes[:, 3:6])
            if model.family.has_triads:  # the cross-section turns with it: spin w·t about t
                g = nodes[:, 3:6]
                v[:, 6] = g @ w / np.linalg.norm(g, axis=1)
        cols.append(v.ravel())
    r = model.y_from_q(np.array(cols)).T  # (n, n_candidates)
    fixed = model.fixed
    if fixed.any():
        # combinations with zero fixed components
        _, s, vt = np.linalg.svd(r[fixed], full_matrices=True)
        rank = int(np.sum(s > 1e-10 * max(s.max(initial=0.0), 1.0)))
        r = r @ vt[rank:].T
    return r


def unresisted_motions(
    r: NDArray, k: NDArray | sp.spmatrix, m: NDArray | sp.spmatrix, rtol: float = 0.0
) -> NDArray[np.float64]:
    """The part of the rigid candidates ``r`` (M-orthonormal columns) that ``k`` does not
    resist: the null space of ``rᵀ k r`` to round-off (``10³ ε |r|ᵀ |k| |r|``), or to ``rtol``
    of ``|r|ᵀ |k| |r|`` when larger (a tangent with finite-difference parts)."""
    if r.shape[1] == 0:
        return r
    kr = r.T @ (k @ r)
    noise = max(1e3 * np.finfo(float).eps, rtol) * (np.abs(r).T @ (abs(k) @ np.abs(r)))
    w, u = np.linalg.eigh(0.5 * (kr + kr.T))  # r is M-orthonormal: rᵀ m r = I
    zero = np.abs(w) <= np.abs(np.diag(u.T @ noise @ u)) + 1e-300
    return r @ u[:, zero]


def rigid_motions(system: System, y: NDArray, lin: Linearized) -> NDArray[np.float64]:
    """The system's unresisted rigid motions and mechanisms on its free coordinates, M-
    orthonormal columns ``(n_free, n_r)`` (module docstring)."""
    cols = []
    for name in system.names:
        b, sl = system.bodies[name], system.body_slice(name)
        r = rigid_candidates(b, y[sl]) if isinstance(b, Model) else np.eye(sl.stop - sl.start)
        block = np.zeros((system.n, r.shape[1]))
        block[sl] = r
        cols.append(block)
    r = np.concatenate(cols, axis=1)[lin.free]
    if lin.g.shape[0] and r.shape[1]:  # the candidates' combinations that keep the constraints
        _, s, vt = np.linalg.svd(lin.g @ r, full_matrices=True)
        rank = int(np.sum(s > 1e-10 * max(s.max(initial=0.0), 1.0)))
        r = r @ vt[rank:].T
    if r.shape[1] == 0:
        return r
    gram = r.T @ (lin.mass @ r)
    w, u = np.linalg.eigh(0.5 * (gram + gram.T))
    keep = w > 1e-12 * w.max()
    r = r @ (u[:, keep] / np.sqrt(w[keep]))
    return unresisted_motions(r, lin.k, lin.mass, FD_RTOL)


def is_symmetric(k: sp.spmatrix) -> bool:
    """``|K_ij - K_ji| <= SYM_RTOL √(|K_ii K_jj|)`` for every entry (a zero diagonal counts as
    the largest one)."""
    d = np.abs(k.diagonal())
    d = np.sqrt(np.where(d > 0, d, d.max(initial=1.0)))
    a = sp.coo_matrix(k - k.T)
    return bool(np.all(np.abs(a.data) <= SYM_RTOL * d[a.row] * d[a.col]))


def _dense(lin: Linearized) -> tuple[NDArray, NDArray, bool]:
    """All eigenpairs on the null space of ``G`` (module docstring): ``λ``, ``φ`` (free
    coordinates, columns) and whether the symmetric problem was solved."""
    k, mass = lin.k.toarray(), lin.mass.toarray()
    basis = None
    if lin.g.shape[0]:
        basis = scipy.linalg.null_space(lin.g.toarray())
        k, mass = basis.T @ k @ basis, basis.T @ mass @ basis
    symmetric = is_symmetric(lin.k)
    try:
        if not (np.all(np.isfinite(k)) and np.all(np.isfinite(mass))):
            raise ValueError("non-finite stiffness or mass entries")
        pairs = None
        if symmetric:
            try:
                pairs = scipy.linalg.eigh(0.5 * (k + k.T), 0.5 * (mass + mass.T))
            except np.linalg.LinAlgError:
                symmetric = False
        lam, phi = pairs if pairs is not None else _general_modes(k, mass)
    except (np.linalg.LinAlgError, ValueError) as exc:
        raise RancfError(
            f"the eigenproblem K φ = λ M φ cannot be solved ({' '.join(str(exc).split())}): "
            "its mass or stiffness is singular or far out of scale; check material.density, "
            "material.youngs_modulus and the section"
        ) from None
    return lam, (phi if basis is None else basis @ phi), symmetric


def _sparse(lin: Linearized, want: int) -> tuple[NDArray, NDArray, bool]:
    """The ``want`` eigenpairs nearest the shift, on the bordered pencil (module docstring)."""
    k, mass = lin.bordered(), lin.bordered_mass()
    n_free = lin.k.shape[0]
    dk, dm = np.abs(lin.k.diagonal()), np.abs(lin.mass.diagonal())
    stiff = dk > 1e-12 * dk.max(initial=0.0)  # round-off (multipliers of 1e-27) is no stiffness
    both = stiff & (dm > 0)
    sigma = SHIFT * (float(np.median(dk[both] / dm[both])) if np.any(both) else 1.0)
    # balance: coordinates by their stiffness, the multipliers to match, so the constraint
    # rows (entries ~ 1) and the elastic ones (~ EA / l) are alike
    kbar = float(np.mean(dk[stiff])) if np.any(stiff) else 1.0
    d = np.r_[1.0 / np.sqrt(np.where(stiff, dk, kbar)), np.full(k.shape[0] - n_free, np.sqrt(kbar))]
    bal = sp.diags(d)
    k, mass = (bal @ k @ bal).tocsc(), (bal @ mass @ bal).tocsc()
    try:
        lu = spla.splu((k - sigma * mass).tocsc())
    except RuntimeError as exc:
        raise RancfError(
            f"the shifted stiffness is singular ({exc}): redundant constraints?"
        ) from None
    op = spla.LinearOperator(k.shape, matvec=lambda x: lu.solve(mass @ x), dtype=float)
    mu, vec = spla.eigs(op, k=min(want, k.shape[0] - 2), which="LM", tol=1e-12, maxiter=10000)
    ok = mu != 0
    lam, vec = sigma + 1.0 / mu[ok], vec[:, ok]
    kv, mv = k @ vec, mass @ vec
    res = np.linalg.norm(kv - mv * lam, axis=0)
    size_of = np.linalg.norm(kv, axis=0) + (np.abs(lam) + abs(sigma)) * np.linalg.norm(mv, axis=0)
    good = (res <= 1e-6 * size_of) & (np.linalg.norm(mv, axis=0) > 0)
    lam, vec = lam[good], (d[:, None] * vec[:, good])[:n_free]
    # a symmetric tangent (as the dense path decides it) has real eigenvalues: Arnoldi's
    # imaginary parts are then round-off (1.9e-8 of the real part on the rod ring)
    symmetric = is_symmetric(lin.k) or bool(np.all(np.abs(lam.imag) <= 1e-9 * np.abs(lam.real)))
    return (lam.real if symmetric else lam), vec, symmetric


def natural_modes(
    model: Model | System,
    y: NDArray | None = None,
    count: int | None = None,
    lam: NDArray | None = None,
) -> ModalResult:
    """Natural frequencies and modes about ``y`` (module docstring).

    Parameters
    ----------
    model : System or Model
        A model is solved as the system of that one body.
    y : ndarray, optional
        Configuration to linearize about, in equilibrium with the loads at their amplitude,
        e.g. :func:`rancf.solvers.static.solve_static`'s ``y`` (with the rod triads it
        leaves); the loads' stiffness enters the tangent.  Without ``y``: the unloaded
        reference configuration.
    count : int, optional
        Number of (non-rigid) modes, the lowest; default all of them (solved densely, at a
        cost of order ``n³``).
    lam : ndarray, optional
        The multipliers at ``y`` (the static solution's ``lam``); default zero.

    Raises
    ------
    InputError
        ``count`` not an integer in ``[1, n_free - 1]``.
    RancfError
        When the eigenproblem cannot be solved, or fewer than ``count`` modes are found.
    """
    system = as_system(model)
    if y is None:
        system.reset_triads()
        y, load = system.y0.copy(), 0.0  # the unloaded structure
    else:
        y, load = np.asarray(y, dtype=float), 1.0
    lin = linearize(system, y, lam, load)
    n_free = lin.k.shape[0]
    if count is not None and (isinstance(count, bool) or not 1 <= count < n_free):
        raise InputError("count", count, f"an integer in [1, {n_free - 1}]")
    rigid = rigid_motions(system, y, lin)
    if count is None or n_free + system.m <= DENSE:
        lam_w, phi, symmetric = _dense(lin)
    else:
        lam_w, phi, symmetric = _sparse(lin, count + rigid.shape[1] + 12)
    order = _ascending(lam_w)
    lam_w, phi = lam_w[order], phi[:, order]
    mc = lin.mass
    norms = np.sqrt(np.maximum(np.einsum("ij,ij->j", phi.conj(), mc @ phi).real, 1e-300))
    phi = phi / norms
    keep = np.ones(lam_w.size, dtype=bool)
    if rigid.shape[1]:
        share = np.sum(np.abs(rigid.T @ (mc @ phi)) ** 2, axis=0)
        best = np.argsort(-share)[: rigid.shape[1]]
        keep[best[share[best] > 0.99]] = False
    lam_w, phi = lam_w[keep], phi[:, keep]
    if count is not None:
        if lam_w.size < count:
            raise RancfError(f"only {lam_w.size} modes found of the {count} asked")
        lam_w, phi = lam_w[:count], phi[:, :count]
    modes = np.zeros((lam_w.size, system.n))
    modes[:, lin.free] = phi.real.T
    # eigenvalues within round-off of zero (of either sign) are zero frequencies, not growth
    dk, dm = np.abs(lin.k.diagonal()), np.abs(mc.diagonal())
    both = (dm > 0) & (dk > 0)
    with np.errstate(all="ignore"):  # a vanishing mass: no floor (eigenvalues overflow)
        floor = ZERO_RTOL * (float(np.median(dk[both] / dm[both])) if np.any(both) else 0.0)
    floor = floor if np.isfinite(floor) else 0.0
    lam_c = np.where(np.abs(lam_w) <= floor, 0.0, np.asarray(lam_w, dtype=complex))
    root = np.sqrt(lam_c)
    freqs = root.real / (2.0 * np.pi)
    growth = np.abs(root.imag)
    return ModalResult(freqs, system.q_from_y(modes), rigid.shape[1], lam_w, growth, symmetric)


def tangent_stiffness(
    model: Model | System, y: NDArray | None = None, lam: NDArray | None = None
) -> tuple[NDArray[np.float64], bool]:
    """The tangent :func:`natural_modes` linearizes with, dense ``(n, n)`` (zero on the held
    coordinates), and whether it is symmetric (:data:`SYM_RTOL`).  Without ``y``: the unloaded
    reference; with ``y``: the loads at their amplitude, their stiffness included."""
    system = as_system(model)
    if y is None:
        system.reset_triads()
    yy = system.y0 if y is None else np.asarray(y, dtype=float)
    lin = linearize(system, yy, lam, 0.0 if y is None else 1.0)
    k = np.zeros((system.n, system.n))
    k[np.ix_(lin.free, lin.free)] = lin.k.toarray()
    return k, is_symmetric(lin.k)


def _general_modes(
    k: NDArray[np.float64], m: NDArray[np.float64]
) -> tuple[NDArray[np.complex128], NDArray[np.complex128]]:
    """``k φ = λ m φ`` for a non-symmetric ``k`` (QZ): ``λ`` (not NaN) ascending by real, then
    imaginary part; ``φ`` scaled to ``φᴴ m φ = 1`` with its largest component real and
    positive."""
    with np.errstate(all="ignore"):  # infinite eigenvalues (a singular m) stay inf, quietly
        lam, phi = scipy.linalg.eig(k, m)
    ok = ~np.isnan(lam)  # an overflowing eigenvalue stays (infinite), last
    lam, phi = lam[ok].astype(np.complex128), phi[:, ok].astype(np.complex128)
    order = _ascending(lam)
    lam, phi = lam[order], phi[:, order]
    phi /= np.sqrt(np.einsum("ij,ik,kj->j", phi.conj(), m, phi).real)
    big = phi[np.argmax(np.abs(phi), axis=0), np.arange(phi.shape[1])]
    phi *= big.conj() / np.abs(big)
    return lam, phi


def _ascending(lam: NDArray) -> NDArray:
    """The order of eigenvalues ``lam`` ascending by real, then imaginary part, with real parts
    equal to 1e-10 of the largest taken as equal: the two of a conjugate pair, whose real parts
    the eigensolver returns apart by round-off, come in the same order (negative imaginary
    part first) whatever the LAPACK build."""
    finite = np.isfinite(lam.real)
    scale = float(np.abs(lam.real[finite]).max()) if finite.any() else 1.0
    key = np.where(finite, np.round(lam.real / max(scale, 1e-300), 10), lam.real)
    return np.lexsort((lam.imag, key))
