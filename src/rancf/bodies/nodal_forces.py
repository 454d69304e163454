"""The axial force at the nodes of a line from its nodal forces (equilibrium), not its strain.

A cable or rod element whose stress-free reference is curved cannot take a straight shape with
a uniform stretch: its rational shape functions carry the reference's weights, and a straight
segment's speed ``|r'(ξ)|`` then deviates from ``λ |r0'(ξ)|`` by a relative amount of the order
of ``1 - ω ≈ θ_e² / 8`` (``θ_e``: the angle the element's reference turns through).  The
pointwise strain ``ε = (|r'|² - |r0'|²) / (2 |r0'|²)`` oscillates inside every such element by
that amount, so ``EA ε`` oscillates by ``EA θ_e² / 8``: more than the tension itself where the
line is stiff (``EA / T`` in the thousands, a chain) and its reference much more curved than its
shape.  The oscillation leaves the element's nodal forces (its energy's gradient) balanced and
exact to the discretization, so the axial force is read from them (docs/derivations/cable.md
section 7):

* at an inner node ``j``, with ``F_L`` the force element ``j-1`` exerts on node ``j``'s position
  (the position rows of its internal force) and ``F_R`` element ``j``'s,
  ``N_j = ½ (F_L - F_R) · t_j`` (``t_j`` the unit tangent): the section force from the left and
  from the right, averaged (their difference is the two elements' shares of the distributed
  loads at the node, which the average cancels to first order);
* at an end node, the force everything attached there exerts on the line: the node's position
  rows of the body's own terms of the balance residual (internal force, weight, inertia, fluid
  and contact loads; not the multipliers' forces, point loads or springs), which the support's
  reaction, a joint's force, point loads and springs there balance (zero at a free end), along
  the outward tangent.

``F_L`` needs no element-by-element assembly: every element's internal force vanishes under a
rigid translation, so translating the nodes ``j, j+1, ...`` gives ``F_L = Σ_{k ≥ j} f_int[r_k]``
and ``F_R = f_int[r_j] - F_L``.  Between the nodes the value is interpolated linearly in ``ξ``.
Beams (their co-rotational axial force is exact per element), C²-reduced bodies (their nodes do
not own their coordinates) and bodies under a winch keep the strain's value.
"""

from __future__ import annotations

import numpy as np
from numpy.typing import NDArray

from rancf.bodies.flexible import Model

__all__ = ["nodal_axial_forces", "recovers_axial_force"]


def recovers_axial_force(model: Model) -> bool:
    """Whether :func:`nodal_axial_forces` applies to ``model`` (a cable or rod without C²
    reduction)."""
    return model.element != "beam" and model.reduction is None


def nodal_axial_forces(model: Model, y: NDArray, residual: NDArray) -> NDArray[np.float64]:
    """The axial force ``(n_nodes,)`` at the nodes (module docstring); of a stack of ``k``
    states ``(k, n_nodes)``.

    Parameters
    ----------
    model : Model
        A cable or rod body (:func:`recovers_axial_force`).
    y : ndarray, shape (n,) or (k, n)
        Model coordinates.
    residual : ndarray, shape (n,) or (k, n)
        The body's rows of its own terms of the balance residual, ``M a + c M v + f_int -
        f_gravity`` with the fluid and contact loads (``distributed_only`` of the compiled
        residual: no multipliers' forces, point loads or springs): on an end node's position,
        the force everything attached there exerts on the line.
    """
    y = np.asarray(y, dtype=float)
    ys, res = np.atleast_2d(y), np.atleast_2d(np.asarray(residual, dtype=float))
    k, dim, dpn, nn = ys.shape[0], model.dim, model.dpn, model.n_nodes
    q = model.q_from_y(ys).reshape(k, nn, dpn)
    f_int = np.stack([model.internal_force(row) for row in ys])
    f = model.forces_at_nodes(f_int).reshape(k, nn, dpn)[:, :, :dim]
    ends = model.forces_at_nodes(res).reshape(k, nn, dpn)[:, [0, -1], :dim]
    tangent = q[:, :, dim : 2 * dim]
    tangent = tangent / np.linalg.norm(tangent, axis=2, keepdims=True)
    left = np.cumsum(f[:, ::-1], axis=1)[:, ::-1]  # F_L[j] = sum over k >= j of f[k]
    right = f - left
    out = 0.5 * np.einsum("kij,kij->ki", left - right, tangent)
    out[:, 0] = -np.einsum("kj,kj->k", ends[:, 0], tangent[:, 0])
    out[:, -1] = np.einsum("kj,kj->k", ends[:, 1], tangent[:, -1])
    return out[0] if y.ndim == 1 else out
