"""Natural modes of a system of bodies: on the null space of its constraints, sparse.

Linearized about a configuration ``y`` with multipliers ``λ`` (an equilibrium; the reference
with ``λ = 0`` by default), free vibrations ``y = y* + φ e^{iωt}`` of the constrained equations
satisfy the saddle-point eigenproblem

    [K  Gᵀ] [φ]       [M  0] [φ]
    [G  0 ] [μ] = ω²  [0  0] [μ]

with the tangent ``K = ∂(f_int - f_ext + Gᵀλ)/∂y`` (the constraints' curvature through ``λ``),
the constraint Jacobian ``G`` and the mass ``M`` (rigid bodies' and rods' rotary inertia
included); held coordinates (supports) are removed.  Its finite eigenvalues are those of ``K``
on the null space ``Gφ = 0``, with no basis of that null space ever formed.  The matrices are
the compiled core's bordered ones (``System.core.sparse_jacobian``: band blocks, the constraint
border, couplings between bodies as border unknowns ``z = x_j``) in SciPy sparse form, balanced
by the square roots of the stiffness diagonal.  Small problems (up to :data:`DENSE` unknowns)
are solved by QZ (:func:`scipy.linalg.eig`); larger ones by shift-invert Arnoldi (ARPACK,
:func:`scipy.sparse.linalg.eigs`) on ``(K - σM)⁻¹ M`` with a sparse LU (SuperLU): no dense
``n × n`` matrix.  The shift ``σ`` is :data:`SHIFT` times the median stiffness-to-mass ratio
of the diagonals (the scale of the mesh's highest frequencies), far below the lowest
flexible mode and away from zero.  A computed pair is kept only if its residual
``|K φ - ω² M φ|`` is below 10⁻⁶ of ``|K φ| + (|ω²| + |σ|) |M φ|``.

Zero-frequency modes are found as for one body (:mod:`rancf.solvers.modal`): every body's
infinitesimal rigid motions (a flexible body's translations and rotations that its supports
allow, :func:`~rancf.solvers.modal.rigid_candidates`; all of a rigid body's or point mass's
coordinates) restricted to the null space of ``G`` are the candidates; the part the tangent does
not resist (:func:`~rancf.solvers.modal.unresisted_motions`, to :data:`FD_RTOL`: the tangent's
spring, load and constraint-curvature parts are central differences) are the rigid-body motions and
mechanisms of the system (a free body's 3 or 6, a pendulum's swing about its reference, a
crank turning).  Eigenvectors lying in that subspace (M-norm share above 0.99) are removed and
counted in ``n_rigid``.
"""

from __future__ import annotations

import numpy as np
import scipy.linalg
import scipy.sparse as sp
import scipy.sparse.linalg as spla
from numpy.typing import NDArray

from rancf.bodies.flexible import Model
from rancf.errors import InputError, RancfError
from rancf.solvers.modal import ModalResult, rigid_candidates, unresisted_motions
from rancf.system import System

__all__ = ["system_modes"]

#: Problems up to this many unknowns are solved densely (QZ); larger ones by Arnoldi.
DENSE = 300
#: The shift of the Arnoldi iteration, relative to the median stiffness-to-mass ratio.
SHIFT = -1e-8
#: Zero stiffness of a rigid candidate, relative to its size: above the error of the central
#: differences of the tangent's spring, load and constraint-curvature parts (step 1e-6).
FD_RTOL = 1e-9


def _matrix(
    system: System, y: NDArray, lam: NDArray, ck: float, ca: float, size: int | None = None
) -> sp.csc_matrix:
    """The core's bordered Jacobian ``ck ∂/∂y + ca ∂/∂a`` as a sparse matrix; ``ca``: only its
    coordinates' block (the mass), padded to ``size``."""
    z = np.zeros(system.n)
    ok, full, rows, cols, vals = system.core.sparse_jacobian(
        y, z, z, lam, 0.0, ck, 0.0, ca, ca != 0.0
    )
    if not ok:
        raise RancfError("the system's tangent is not finite at this configuration")
    rows, cols, vals = np.asarray(rows), np.asarray(cols), np.asarray(vals)
    if ca != 0.0:  # the mass: the coordinates' rows and columns (not the constraints')
        inside = (rows < system.n) & (cols < system.n)
        rows, cols, vals = rows[inside], cols[inside], vals[inside]
    n = full if size is None else size
    return sp.coo_matrix((vals, (rows, cols)), shape=(n, n)).tocsc()


def _eigenpairs(
    k: sp.csc_matrix, mass: sp.csc_matrix, sigma: float, want: int
) -> tuple[NDArray, NDArray]:
    """Finite eigenpairs ``K φ = λ M φ`` nearest ``σ`` (module docstring)."""
    size = k.shape[0]
    if size <= DENSE:
        lam, vec = scipy.linalg.eig(k.toarray(), mass.toarray())
        ok = np.isfinite(lam)
        lam, vec = lam[ok], vec[:, ok]
    else:
        try:
            lu = spla.splu((k - sigma * mass).tocsc())
        except RuntimeError as exc:
            raise RancfError(
                f"the shifted stiffness is singular ({exc}): redundant constraints?"
            ) from None
        op = spla.LinearOperator(k.shape, matvec=lambda x: lu.solve(mass @ x), dtype=float)
        mu, vec = spla.eigs(op, k=min(want, size - 2), which="LM", tol=1e-12, maxiter=10000)
        ok = mu != 0
        lam, vec = sigma + 1.0 / mu[ok], vec[:, ok]
    kv, mv = k @ vec, mass @ vec
    res = np.linalg.norm(kv - mv * lam, axis=0)
    size_of = np.linalg.norm(kv, axis=0) + (np.abs(lam) + abs(sigma)) * np.linalg.norm(mv, axis=0)
    good = (res <= 1e-6 * size_of) & (np.linalg.norm(mv, axis=0) > 0)
    return lam[good], vec[:, good]


def _rigid(system: System, y: NDArray, g: sp.csr_matrix, k: sp.csc_matrix,
           mass: sp.csc_matrix) -> NDArray:  # fmt: skip
    """The system's unresisted rigid motions and mechanisms on its free coordinates, M-
    orthonormal columns (module docstring)."""
    cols = []
    for name in system.names:
        b, sl = system.bodies[name], system.body_slice(name)
        r = rigid_candidates(b, y[sl]) if isinstance(b, Model) else np.eye(sl.stop - sl.start)
        block = np.zeros((system.n, r.shape[1]))
        block[sl] = r
        cols.append(block)
    r = np.concatenate(cols, axis=1)[~system.fixed]
    if g.shape[0] and r.shape[1]:  # the candidates' combinations that keep the constraints
        gr = g @ r
        _, s, vt = np.linalg.svd(gr, full_matrices=True)
        rank = int(np.sum(s > 1e-10 * max(s.max(initial=0.0), 1.0)))
        r = r @ vt[rank:].T
    if r.shape[1] == 0:
        return r
    gram = r.T @ (mass @ r)
    w, u = np.linalg.eigh(0.5 * (gram + gram.T))
    keep = w > 1e-12 * w.max()
    r = r @ (u[:, keep] / np.sqrt(w[keep]))
    return unresisted_motions(r, k, mass, FD_RTOL)


def system_modes(
    system: System, y: NDArray | None = None, count: int = 6, lam: NDArray | None = None
) -> ModalResult:
    """The ``count`` lowest natural frequencies and modes of ``system`` about ``y`` (default its
    reference) with multipliers ``lam`` (default zero), zero-frequency modes removed (module
    docstring).  Modes are M-normalized, in full coordinates ``(count, n)``."""
    if y is None:
        system.reset_triads()
    y = system.y0.copy() if y is None else np.asarray(y, dtype=float)
    lam = np.zeros(system.m) if lam is None else np.asarray(lam, dtype=float)
    n, free = system.n, ~system.fixed
    n_free = int(np.sum(free))
    if isinstance(count, bool) or not 1 <= count < n_free:
        raise InputError("count", count, f"an integer in [1, {n_free - 1}]")
    k = _matrix(system, y, lam, 1.0, 0.0)
    size = k.shape[0]
    mass = _matrix(system, y, lam, 0.0, 1.0, size)
    idx = np.flatnonzero(np.r_[free, np.ones(size - n, dtype=bool)])
    k, mass = k[idx][:, idx].tocsc(), mass[idx][:, idx].tocsc()
    kc, mc = k[:n_free, :n_free], mass[:n_free, :n_free]
    rigid = _rigid(system, y, k[n_free : n_free + system.m, :n_free].tocsr(), kc, mc)
    dk, dm = np.abs(kc.diagonal()), np.abs(mc.diagonal())
    # stiff coordinates: round-off (a static solve's multipliers of 1e-27) is no stiffness
    stiff = dk > 1e-12 * dk.max(initial=0.0)
    both = stiff & (dm > 0)
    sigma = SHIFT * (float(np.median(dk[both] / dm[both])) if np.any(both) else 1.0)
    # balance: coordinates by their stiffness, the border (multipliers, couplings) to match,
    # so the constraint rows (entries ~ 1) and the elastic ones (~ EA / l) are alike
    kbar = float(np.mean(dk[stiff])) if np.any(stiff) else 1.0
    d = np.r_[1.0 / np.sqrt(np.where(stiff, dk, kbar)), np.full(k.shape[0] - n_free, np.sqrt(kbar))]
    bal = sp.diags(d)
    lam_w, vec = _eigenpairs((bal @ k @ bal).tocsc(), (bal @ mass @ bal).tocsc(), sigma,
                             count + rigid.shape[1] + 12)  # fmt: skip
    vec = (d[:, None] * vec)[:n_free]
    order = np.argsort(lam_w.real)
    lam_w, vec = lam_w[order], vec[:, order]
    phi = vec.real
    norms = np.sqrt(np.maximum(np.einsum("ij,ij->j", phi, mc @ phi), 1e-300))
    phi = phi / norms
    keep = np.ones(lam_w.size, dtype=bool)
    n_rigid = rigid.shape[1]
    if n_rigid:
        share = np.sum(np.abs(rigid.T @ (mc @ phi)) ** 2, axis=0)
        order = np.argsort(-share)[:n_rigid]
        keep[order[share[order] > 0.99]] = False
    lam_w, phi = lam_w[keep][:count], phi[:, keep][:, :count]
    if lam_w.size < count:
        raise RancfError(f"only {lam_w.size} modes found of the {count} asked")
    modes = np.zeros((lam_w.size, n))
    modes[:, free] = phi.T
    modes = system.q_from_y(modes)
    symmetric = bool(np.all(np.abs(lam_w.imag) <= 1e-9 * np.abs(lam_w.real)))
    root = np.sqrt(lam_w.astype(complex))
    eig = lam_w.real if symmetric else lam_w
    # the zero-frequency motions found (their eigenpairs may be dropped by the residual filter)
    return ModalResult(root.real / (2 * np.pi), modes, n_rigid, eig,
                       np.abs(root.imag), symmetric)  # fmt: skip
