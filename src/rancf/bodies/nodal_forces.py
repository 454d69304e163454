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
    return model.family.gradient and model.reduction is None


def nodal_axial_forces(
    model: Model, y: NDArray, residual: NDArray, internal: NDArray | None = None
) -> NDArray[np.float64]:
    """The axial force ``(n_nodes,)`` at the nodes (module docstring); ``(k, n_nodes)`` for a
    stack of ``k`` states.

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
    internal : ndarray, shape like ``y``, optional
        The elastic force ``f_int(y)`` (:meth:`Model.internal_force`, computed if not given).
    """
    dim, dpn, nn = model.dim, model.dpn, model.n_nodes
    y = np.asarray(y, dtype=float)
    if internal is None:
        stack = y.reshape(-1, y.shape[-1])
        internal = np.array([model.internal_force(x) for x in stack]).reshape(y.shape)
    lead = y.shape[:-1]
    q = model.q_from_y(y).reshape(*lead, nn, dpn)
    f = model.forces_at_nodes(internal).reshape(*lead, nn, dpn)[..., :dim]
    ends = model.forces_at_nodes(residual).reshape(*lead, nn, dpn)[..., [0, -1], :dim]
    g = q[..., dim : 2 * dim]
    tangent = g / np.sqrt(_dot(g, g))[..., None]
    left = np.flip(np.cumsum(np.flip(f, axis=-2), axis=-2), axis=-2)  # F_L[j] = Σ_{k≥j} f[k]
    right = f - left
    out = 0.5 * _dot(left - right, tangent)
    out[..., 0] = -_dot(ends[..., 0, :], tangent[..., 0, :])
    out[..., -1] = _dot(ends[..., 1, :], tangent[..., -1, :])
    return out


def _dot(a: NDArray, b: NDArray) -> NDArray[np.float64]:
    """``Σ_i a_i b_i`` over the last axis (2 or 3 components: a sum of whole-array products,
    far faster than a reduction over so short an axis)."""
    out = a[..., 0] * b[..., 0]
    for i in range(1, a.shape[-1]):
        out = out + a[..., i] * b[..., i]
    return out
