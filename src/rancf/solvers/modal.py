"""Natural frequencies and mode shapes of a model linearized about a configuration.

``K_T(y*) φ = ω² M φ`` on the free coordinates.  About the reference configuration, and about any
configuration whose loads do not depend on the configuration, ``K_T`` is the (symmetric) elastic
tangent: generalized symmetric eigenproblem, LAPACK ``sygvd`` via :func:`scipy.linalg.eigh`.
About a loaded configuration (``y`` given, e.g. the static equilibrium) ``K_T`` also holds the
load stiffness ``-∂f_ext/∂y`` of the loads at their amplitude: gravity and point forces are dead
loads (none), a rod's point moments have one, non-symmetric in general (the core's, as in the
static Newton tangent).  That problem is solved by the general QZ algorithm
(:func:`scipy.linalg.eig`); its eigenvalues ``λ = ω²`` may be complex (flutter) or negative
(divergence): a motion ``e^{μt}`` with ``μ² = -λ``, ``√λ = a + ib`` (principal root) oscillates
at ``a / 2π`` Hz and one of its roots grows like ``e^{|b| t}`` — reported as ``growth_rates``
[1/s], never dropped.

Rigid-body modes are the zero-frequency modes of the actual problem that are rigid motions.  The
infinitesimal translations and rotations of the configuration that the supports allow span a
candidate subspace ``R``; only its part that the tangent does not resist is rigid: the null space
of ``Rᵀ K R`` to round-off (an eigenvalue ``λ`` of ``(Rᵀ K R, Rᵀ M R)`` counts as zero when
``|λ| Rᵀ M R`` is below 10³ ε times ``|R|ᵀ |K| |R|``, the size of the round-off of ``Rᵀ K R``).
About a loaded state a rigid motion can be resisted by the loads: a pendulum's swing about its
pin is a real mode (gravity's tension stiffens it, ``K r = W f_ext ≠ 0``), not a rigid-body mode.
An eigenvector lying in the rigid subspace (M-norm share above 0.99) is removed.  Any other zero
or near-zero frequency is reported as it is — for instance the out-of-plane bending of a curved
spatial cable, which the magnitude curvature ``|r' × r''|/|r'|³`` does not resist to first order
(docs/derivations/cable.md sec. 6); the rod element (``"rod"``) has that stiffness.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import scipy.linalg
from numpy.typing import NDArray

from rancf.bodies.flexible import Model
from rancf.errors import RancfError
from rancf.system import System

__all__ = [
    "ModalResult",
    "natural_modes",
    "rigid_body_modes",
    "rigid_candidates",
    "tangent_stiffness",
    "unresisted_motions",
]


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
        component is real and positive (the shape when that component peaks); the two modes
        of a conjugate pair then show the same shape.
    n_rigid : int
    eigenvalues : ndarray
        ``λ = ω²``: real for the symmetric problem, complex for the general one.
    growth_rates : ndarray
        ``|Im √λ|`` [1/s]: 0 for a stable mode, the e-folding rate of the growing root of an
        unstable one (flutter if the frequency is > 0, divergence if it is 0).
    symmetric : bool
        True when the symmetric problem was solved (no configuration-dependent loads).
    """

    frequencies_hz: NDArray[np.float64]
    modes: NDArray[np.float64]
    n_rigid: int
    eigenvalues: NDArray[np.float64] | NDArray[np.complex128]
    growth_rates: NDArray[np.float64] | None = None
    symmetric: bool = True


def rigid_candidates(model: Model, y: NDArray) -> NDArray[np.float64]:
    """Infinitesimal rigid motions (translations, rotations about the centre of the nodes) of
    configuration ``y`` that the supports allow, ``(n, n_r)`` (model coordinates; combinations
    with zero held components)."""
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
            if model.element == "beam":
                v[:, 2] = 1.0
            else:
                g = nodes[:, 2:4]
                v[:, 2], v[:, 3] = -g[:, 1], g[:, 0]
        else:
            v[:, :3] = np.cross(w, pos - centre)
            v[:, 3:6] = np.cross(w, nodes[:, 3:6])
            if model.element == "rod":  # the cross-section turns with it: spin w·t about t
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


def rigid_body_modes(model: Model, y: NDArray) -> NDArray[np.float64]:
    """Infinitesimal rigid motions of configuration ``y`` allowed by the supports, ``(n, n_r)``.

    Columns are M-orthonormal and vanish on the fixed coordinates.
    """
    r = rigid_candidates(model, y)
    if r.shape[1] == 0:
        return r
    m = model.dense(model.mass_matrix(y))
    gram = r.T @ m @ r
    w, u = np.linalg.eigh(gram)
    keep = w > 1e-12 * w.max()
    return r @ (u[:, keep] / np.sqrt(w[keep]))


def natural_modes(
    model: Model | System,
    y: NDArray | None = None,
    count: int | None = None,
    lam: NDArray | None = None,
) -> ModalResult:
    """Natural frequencies about ``y`` (default: the reference configuration).

    A :class:`~rancf.system.System` is solved on the null space of its constraints, sparse
    (:func:`rancf.solvers.system_modal.system_modes`; ``lam``: the multipliers at ``y``, as the
    static solution gives them; ``count`` default 6), and so is a closed model (a ring: the seam
    is a constraint of a one-body system).

    Parameters
    ----------
    model : Model
    y : ndarray, optional
        Configuration to linearize about, in equilibrium with the model's loads at their
        amplitude, e.g. :func:`rancf.solvers.static.solve_static`'s ``y`` (with the rod triads
        it leaves).  Its load stiffness (point moments) enters the tangent.  Without ``y``: the
        unloaded reference configuration.
    count : int, optional
        Number of (non-rigid) modes to return; default all.
    """
    if isinstance(model, Model) and model.closed:  # a ring: its seam rows make it a system
        model = System({"body": model})
    if isinstance(model, System):
        from rancf.solvers.system_modal import system_modes

        return system_modes(model, y, 6 if count is None else count, lam)
    if y is None:
        model.reset_triads()
    k_full, symmetric = tangent_stiffness(model, y)  # the reference: no loads
    y = model.y0 if y is None else np.asarray(y, dtype=float)
    free = ~model.fixed
    k = k_full[np.ix_(free, free)]
    m = model.dense(model.mass_matrix(y))[np.ix_(free, free)]
    try:
        if not (np.all(np.isfinite(k)) and np.all(np.isfinite(m))):
            raise ValueError("non-finite stiffness or mass entries")
        if symmetric:
            k = 0.5 * (k + k.T)
            lam, phi = scipy.linalg.eigh(k, m)
        else:
            lam, phi = _general_modes(k, m)
    except (np.linalg.LinAlgError, ValueError) as exc:
        raise RancfError(
            f"the eigenproblem K φ = λ M φ cannot be solved ({' '.join(str(exc).split())}): "
            "its mass or stiffness is singular or far out of scale; check material.density, "
            "material.youngs_modulus and the section"
        ) from None
    rigid = unresisted_motions(rigid_body_modes(model, y)[free], k, m)
    n_rigid = rigid.shape[1]
    keep = np.ones(lam.size, dtype=bool)
    if n_rigid:
        share = np.sum(np.abs(rigid.T @ m @ phi) ** 2, axis=0)  # φ M-normalized
        order = np.argsort(-share)[:n_rigid]
        keep[order[share[order] > 0.99]] = False
    lam, phi = lam[keep], phi[:, keep]
    if count is not None:
        lam, phi = lam[:count], phi[:, :count]
    modes = np.zeros((lam.size, model.n))
    modes[:, free] = phi.real.T
    modes = model.q_from_y(modes)
    if symmetric:
        freqs = np.sqrt(np.clip(lam, 0.0, None)) / (2.0 * np.pi)
        growth = np.sqrt(np.clip(-lam, 0.0, None))
    else:
        root = np.sqrt(lam)  # principal branch: real part >= 0
        freqs = root.real / (2.0 * np.pi)
        growth = np.abs(root.imag)
    return ModalResult(freqs, modes, int(np.sum(~keep)), lam, growth, symmetric)


def unresisted_motions(
    r: NDArray, k: NDArray, m: NDArray, rtol: float = 0.0
) -> NDArray[np.float64]:
    """The part of the rigid candidates ``r`` (M-orthonormal columns) that ``k`` does not
    resist: the null space of ``rᵀ k r`` to round-off (module docstring), or to ``rtol`` of
    ``|r|ᵀ |k| |r|`` when larger (a tangent with finite-difference parts)."""
    if r.shape[1] == 0:
        return r
    kr = r.T @ (k @ r)
    noise = max(1e3 * np.finfo(float).eps, rtol) * (np.abs(r).T @ (abs(k) @ np.abs(r)))
    w, u = np.linalg.eigh(0.5 * (kr + kr.T))  # r is M-orthonormal: rᵀ m r = I
    zero = np.abs(w) <= np.abs(np.diag(u.T @ noise @ u)) + 1e-300
    return r @ u[:, zero]


def tangent_stiffness(model: Model, y: NDArray | None = None) -> tuple[NDArray[np.float64], bool]:
    """The tangent :func:`natural_modes` linearizes with, dense ``(n, n)``, and whether it is the
    symmetric elastic tangent alone.

    Without ``y``: the elastic tangent at the reference (the unloaded structure).  With ``y``:
    ``∂(f_int - f_ext)/∂y`` at ``y`` with the loads at their amplitude (as in statics) — the
    elastic tangent minus the point moments' load stiffness; ``False`` when the latter is
    present (non-zero), so that the general eigenproblem is solved.
    """
    yy = model.y0 if y is None else np.asarray(y, dtype=float)
    _, kb = model.internal_force_and_tangent(yy)
    k = model.dense(kb)
    if y is None:
        return k, True
    kl = model.dense(model.load_stiffness(0.0, yy, amplitude=True))
    if not kl.any():
        return k, True
    return k - kl, False


def _general_modes(
    k: NDArray[np.float64], m: NDArray[np.float64]
) -> tuple[NDArray[np.complex128], NDArray[np.complex128]]:
    """``k φ = λ m φ`` for a non-symmetric ``k`` (QZ): ``λ`` ascending by real, then imaginary
    part; ``φ`` scaled to ``φᴴ m φ = 1`` with its largest component real and positive."""
    with np.errstate(all="ignore"):  # infinite eigenvalues (a singular m) stay inf, quietly
        lam, phi = scipy.linalg.eig(k, m)
    lam = lam.astype(np.complex128)
    order = np.lexsort((lam.imag, lam.real))
    lam, phi = lam[order], phi[:, order].astype(np.complex128)
    phi /= np.sqrt(np.einsum("ij,ik,kj->j", phi.conj(), m, phi).real)
    big = phi[np.argmax(np.abs(phi), axis=0), np.arange(phi.shape[1])]
    phi *= big.conj() / np.abs(big)
    return lam, phi
