"""A system linearized about a configuration: the matrices modes and buckling are solved with.

About a configuration ``y`` with multipliers ``λ`` and the loads at ``load_factor`` times their
amplitude, the balance ``f_int(y) - p f_ext(y) + f_springs(y) + G(y)ᵀ λ = 0`` and the constraints
``g(y) = 0`` (docs/derivations/systems.md,
sec. 1 and 4) have the bordered Jacobian

    J = [ K   Gᵀ ]        K = ∂(f_int - p f_ext + f_springs + Gᵀλ)/∂y
        [ G   0  ]

(the constraints' curvature enters ``K`` through ``λ``; the load stiffness of configuration-
dependent loads through ``p``), and the mass matrix ``M`` (rigid bodies' and rods' rotary
inertia included).  The compiled core assembles ``J`` as its bordered solver holds it: band
blocks, the constraint border and, for couplings between bodies (springs, the second
derivatives of joints), extra border unknowns ``z = x_j`` with ``D = -I``; those are eliminated
here (``K + P_z Q_z``).  Held coordinates (supports) are removed: every matrix is on the free
coordinates, in SciPy sparse form.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import scipy.sparse as sp
from numpy.typing import NDArray

from rancf.errors import RancfError
from rancf.kernels.call_records import StatePoint, TangentOptions
from rancf.system import System
from rancf.system.joint_data import normals as _normals
from rancf.system.sliding import start_multipliers

__all__ = ["Linearized", "linearize", "system_jacobian"]


@dataclass(frozen=True)
class Linearized:
    """The linearized system on its free coordinates (module docstring).

    Attributes
    ----------
    k : scipy.sparse.csr_matrix
        ``(n_free, n_free)`` tangent stiffness.
    g : scipy.sparse.csr_matrix
        ``(m, n_free)`` constraint Jacobian (its rows).
    gt : scipy.sparse.csr_matrix
        ``(n_free, m)`` the multipliers' columns (``Gᵀ``).
    mass : scipy.sparse.csr_matrix
        ``(n_free, n_free)``.
    free : ndarray of bool
        ``(n,)`` the free coordinates of the system.
    """

    k: sp.csr_matrix
    g: sp.csr_matrix
    gt: sp.csr_matrix
    mass: sp.csr_matrix
    free: NDArray[np.bool_]

    def bordered(self) -> sp.csc_matrix:
        """``J = [K Gᵀ; G 0]``, ``(n_free + m)²``."""
        m = self.g.shape[0]
        return sp.bmat([[self.k, self.gt], [self.g, sp.csr_matrix((m, m))]]).tocsc()

    def bordered_mass(self) -> sp.csc_matrix:
        """``[M 0; 0 0]`` of the size of :meth:`bordered`."""
        m = self.g.shape[0]
        return sp.block_diag([self.mass, sp.csr_matrix((m, m))]).tocsc()


def system_jacobian(
    system: System,
    y: NDArray,
    lam: NDArray,
    ck: float,
    ca: float,
    load_factor: float,
    amplitude: bool,
    t: float,
) -> sp.csr_matrix:
    """The core's ``ck ∂/∂y + ca ∂/∂a`` over ``(y, λ)``, coupling unknowns eliminated."""
    z = np.zeros(system.n)
    ok, size, rows, cols, vals = system.core.sparse_jacobian(
        StatePoint(np.ascontiguousarray(y), z, z, np.ascontiguousarray(lam)),
        TangentOptions(t, ck, 0.0, ca, ca != 0.0, load_factor, amplitude),
    )
    if not ok:
        raise RancfError("the system's tangent is not finite at this configuration")
    j = sp.coo_matrix(
        (np.asarray(vals), (np.asarray(rows), np.asarray(cols))), shape=(size, size)
    ).tocsr()
    keep = system.n + system.m
    if size == keep:
        return j
    a, p = j[:keep, :keep], j[:keep, keep:]
    q, d = j[keep:, :keep], j[keep:, keep:]
    if abs(d + sp.identity(size - keep)).max() > 0:  # D = -I: z = Q x
        raise RancfError("unexpected coupling block in the system's Jacobian")
    return (a + p @ q).tocsr()


def linearize(
    system: System,
    y: NDArray,
    lam: NDArray | None = None,
    load_factor: float = 1.0,
    amplitude: bool = True,
    t: float = 0.0,
) -> Linearized:
    """The matrices of ``system`` linearized about ``(y, λ)`` with the loads at ``load_factor``
    times their amplitude (``amplitude=False``: as they act at time ``t``); module docstring."""
    y = np.asarray(y, dtype=float)
    lam = start_multipliers(system) if lam is None else np.asarray(lam, dtype=float)
    n, m = system.n, system.m
    free = ~system.fixed
    idx = np.flatnonzero(free)
    j = system_jacobian(system, y, lam, 1.0, 0.0, load_factor, amplitude, t)
    mass = system_jacobian(system, y, lam, 0.0, 1.0, load_factor, amplitude, t)
    k = j[idx][:, idx].tocsr()
    g = j[n : n + m][:, idx].tocsr()
    gt = j[idx][:, n : n + m].tocsr()
    if any(jt.entry.slides for jt in system.joints):
        k, g, gt = _condense_sliding(system, j, k, g, gt)
    return Linearized(k, g, gt, mass[idx][:, idx].tocsr(), free)


def _condense_sliding(
    system: System, j: sp.csr_matrix, k: sp.csr_matrix, g: sp.csr_matrix, gt: sp.csr_matrix
) -> tuple[sp.csr_matrix, sp.csr_matrix, sp.csr_matrix]:
    """The sliding joints' material coordinates ``σ`` eliminated (docs/derivations/sliding.md
    sec. 4): along the rope, ``G_y dy + r_σ dσ = 0`` gives ``dσ = T dy``,
    ``T = -r_σᵀ G_y / |r_σ|²``, and the stiffness ``K + k_yσ T + Tᵀ k_σy + Tᵀ k_σσ T``; normal
    to it the rows ``Nᵀ G_y`` (``N``: the ``dim - 1`` unit normals of ``r_σ``) remain, with the
    multipliers' columns ``Gᵀ N``."""
    n, d = system.n, system.dim
    keep, rows, cols = np.ones(system.m, dtype=bool), [], []
    for jj, joint in enumerate(system.joints):
        if not joint.entry.slides:
            continue
        r0 = system.joint_rows[jj]
        slot = r0 + d
        keep[r0 : slot + 1] = False
        rs = j[n + r0 : n + slot, n + slot].toarray().ravel()
        gy = g[r0:slot].toarray()
        t = sp.csr_matrix(-(rs @ gy) / (rs @ rs))
        kys, ksy = gt[:, slot], g[slot]
        k = k + kys @ t + t.T @ ksy + float(j[n + slot, n + slot]) * (t.T @ t)
        e = rs / np.linalg.norm(rs)
        normals = [np.array([-e[1], e[0]])] if d == 2 else list(_normals(e))
        for nv in normals:
            rows.append(sp.csr_matrix(nv @ gy))
            cols.append(sp.csr_matrix(gt[:, r0:slot] @ nv[:, None]))
    g = sp.vstack([g[keep], *rows]).tocsr()
    gt = sp.hstack([gt[:, keep], *cols]).tocsr()
    return k.tocsr(), g, gt
