"""The unstretched length of a flexible body: its unloaded state stretched uniformly.

A cable or rod paid out by a winch or hoisted keeps its mesh and its exact reference geometry;
what changes is how much material the mesh holds.  Scaling the material coordinate uniformly by
``λ = L / L_ref`` (docs/derivations/variable-length.md §2.1) scales the reference metric
(``s0 → λ² s0``, ``J0 → λ J0``), the stress-free curvatures (``κ0 → κ0 / λ``) and, exactly, the
mass matrix and the gravity forces (``M → λ M_ref``, ``Q_g → λ Q_g,ref``): the body's mass is
``ρ A L`` to round-off, and a rigid motion of the reference stretched by ``λ`` carries no
elastic force.  The model's arrays are changed in place, so its compiled core, and every system
that holds the body, see the new length at once: statics and modes at any length.
"""

from __future__ import annotations

import numpy as np

from rancf.bodies.flexible import Model
from rancf.errors import InputError
from rancf.kernels.cable import CableKernel

__all__ = ["length_scale", "reference_length", "set_unstretched_length", "unstretched_length"]


def _cable(model: Model) -> CableKernel:
    c = model.family.centre_line(model.kernel)
    if c is not None:
        return c
    raise InputError("unstretched length", model.element, "cable or rod elements")


def length_scale(model: Model) -> float:
    """``λ``: the unstretched length over the reference's (1 for a beam)."""
    c = model.family.centre_line(model.kernel)
    return float(c.length_scale) if c is not None else 1.0


def reference_length(model: Model) -> float:
    """Arc length of the reference, ``Σ_e ∫ |r0'| dξ`` (Gauss rule of the elements)."""
    c = _cable(model)
    return float(np.sum(c.wj) / c.length_scale)


def unstretched_length(model: Model) -> float:
    """The unstretched length of the body, ``λ L_ref``."""
    c = _cable(model)
    return float(np.sum(c.wj))


def set_unstretched_length(model: Model, length: float, anchor: int | None = None) -> None:
    """Give the body the unstretched length ``length`` [m] (module docstring; in place).

    Parameters
    ----------
    model : Model
        A cable or rod body (beams have no stretched reference).
    length : float
        The new unstretched length, > 0.
    anchor : int, optional
        A node (a winch's end): the reference configuration is scaled about its position by the
        same factor (positions ``a + f (r - a)``, gradients ``f r_x``), so the body starts
        unloaded at its new length, with the anchor where it was; the held coordinates of every
        support move with it.  Without it the start shape stays and is stretched or compressed.
    """
    if not (np.isfinite(length) and length > 0.0):
        raise InputError("length", length, "a finite length > 0 [m]")
    c = _cable(model)
    scale = float(length) / reference_length(model)
    ratio = scale / c.length_scale
    rod = model.family.rod_kernel(model.kernel)
    (rod if rod is not None else c).scale_length(scale)  # a cable's kernel is c
    model.mass_band *= ratio  # shared with the core: in place
    model.mass_el *= ratio
    model.f_gravity *= ratio
    if anchor is None:
        return
    node = model.check_node(anchor, "anchor")
    d = model.dim
    for y in (model.y0, model.y_installed):  # y0 is the core's reference: in place
        q = model.q_from_y(y).reshape(model.n_nodes, model.dpn)
        a = q[node, :d].copy()
        q[:, :d] = a + ratio * (q[:, :d] - a)
        q[:, d : 2 * d] *= ratio
        y[...] = model.y_from_q(q.ravel())
    model.q0 = model.q_from_y(model.y0)
