"""Natural frequencies and mode shapes of a model linearized about a configuration.

``K_T(y*) φ = ω² M φ`` on the free coordinates (generalized symmetric eigenproblem, LAPACK
``sygvd`` via :func:`scipy.linalg.eigh`).  Rigid-body modes are identified geometrically: the
infinitesimal translations and rotations of the configuration that the supports allow span the
rigid subspace; an eigenvector lying in it (M-norm share above 0.99) is a rigid-body mode and is
removed.  Any other zero or near-zero frequency is reported as it is — for instance the
out-of-plane bending of a curved spatial cable, which the magnitude curvature ``|r' × r''|/|r'|³``
does not resist to first order (math note sec. 6); the rod element (``"rod"``) has that stiffness.
Rod models linearized about a static equilibrium under point moments leave out the moments'
(non-symmetric) load stiffness: the problem solved is the symmetric part of the elastic tangent.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import scipy.linalg
from numpy.typing import NDArray

from rancf.model.system import Model

__all__ = ["ModalResult", "natural_modes", "rigid_body_modes"]


@dataclass(frozen=True)
class ModalResult:
    """Frequencies (Hz, ascending, rigid-body modes removed) and full-coordinate mode shapes."""

    frequencies_hz: NDArray[np.float64]
    modes: NDArray[np.float64]
    n_rigid: int
    eigenvalues: NDArray[np.float64]


def rigid_body_modes(model: Model, y: NDArray) -> NDArray[np.float64]:
    """Infinitesimal rigid motions of configuration ``y`` allowed by the supports, ``(n, n_r)``.

    Columns are M-orthonormal and vanish on the fixed coordinates.
    """
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
    if r.shape[1] == 0:
        return r
    m = model.dense(model.mass_band)
    gram = r.T @ m @ r
    w, u = np.linalg.eigh(gram)
    keep = w > 1e-12 * w.max()
    return r @ (u[:, keep] / np.sqrt(w[keep]))


def natural_modes(model: Model, y: NDArray | None = None, count: int | None = None) -> ModalResult:
    """Natural frequencies about ``y`` (default: the reference configuration).

    Parameters
    ----------
    model : Model
    y : ndarray, optional
        Configuration to linearize about, e.g. a static equilibrium.
    count : int, optional
        Number of (non-rigid) modes to return; default all.
    """
    if y is None:
        model.reset_triads()
    y = model.y0 if y is None else np.asarray(y, dtype=float)
    _, kb = model.internal_force_and_tangent(y)
    free = ~model.fixed
    k = model.dense(kb)[np.ix_(free, free)]
    m = model.dense(model.mass_band)[np.ix_(free, free)]
    k = 0.5 * (k + k.T)
    lam, phi = scipy.linalg.eigh(k, m)
    rigid = rigid_body_modes(model, y)[free]
    n_rigid = rigid.shape[1]
    keep = np.ones(lam.size, dtype=bool)
    if n_rigid:
        share = np.sum((rigid.T @ m @ phi) ** 2, axis=0)  # φ M-normalized by eigh
        order = np.argsort(-share)[:n_rigid]
        keep[order[share[order] > 0.99]] = False
    lam, phi = lam[keep], phi[:, keep]
    if count is not None:
        lam, phi = lam[:count], phi[:, :count]
    modes = np.zeros((lam.size, model.n))
    modes[:, free] = phi.T
    modes = model.q_from_y(modes)
    freqs = np.sqrt(np.clip(lam, 0.0, None)) / (2.0 * np.pi)
    return ModalResult(freqs, modes, int(np.sum(~keep)), lam)
