"""The lengths by which the Newton test of a time step measures each coordinate's increment.

A position increment moves the material by itself; an increment ``δr'`` of a node's gradient
(cables, rods' centre lines) or ``δθ`` of its angle (beams) moves the material of the elements
at the node by at most ``(4/27) ℓ |δr'|`` each, ``ℓ`` the element's length (the Hermite shape
functions,
``docs/derivations/newton.md``).  The test ``max_i s_i |Δy_i| <= tol`` therefore takes
``s_i = 1`` for positions and ``s_i = ℓ_min / |r'_ref|`` for gradients (``ℓ_min`` the shorter
of the node's elements, ``|r'_ref|`` the gradient's length in the reference, 1 for the
arc-length gradients of a mesh from exact geometry): the displacements an increment causes,
not the gradient in units of 1, which at fine meshes held the iteration to a far tighter
test than the positions (``ℓ = 2.3 mm`` at 512 elements of 1.2 m).

A rod's twist, coordinates that are not nodal (C² control points), rigid bodies, drums, and
cables whose length changes (winches) keep the scale 1 (the plain test).
"""

from __future__ import annotations

import numpy as np
from numpy.typing import NDArray

from rancf.bodies.flexible import Model
from rancf.system import System

__all__ = ["increment_scale"]


def _winched(system: System) -> set[str]:
    """Names of the bodies whose length a winch changes."""
    return {str(w.at).split(":", 1)[0] for w in getattr(system, "winches", ())}


def body_scale(model: Model) -> NDArray[np.float64] | None:
    """The scales of one body's coordinates (module docstring), or None where they are all 1.

    Cables (``"rancf"``, ``"ancf"``), rods and beams with nodal coordinates: positions 1, each
    node's gradient (beams: angle) ``ℓ_min / |r'_ref|`` (beams: ``ℓ_min``); a rod's twist 1.
    """
    if model.reduction is not None:
        return None
    q = np.asarray(model.q0, dtype=float).reshape(model.n_nodes, model.dpn)
    d = model.dim
    x = q[:, :d]
    lengths = np.linalg.norm(np.diff(x, axis=0), axis=1)  # chords: at most the arc lengths
    if lengths.size == 0 or not np.all(lengths > 0.0):
        return None
    near = np.minimum(np.r_[lengths[0], lengths], np.r_[lengths, lengths[-1]])
    if not model.family.gradient:
        grad = near
    else:
        size = np.linalg.norm(q[:, d : 2 * d], axis=1)
        if not np.all(size > 0.0):
            return None
        grad = near / size
    out = np.ones((model.n_nodes, model.dpn))
    out[:, d : min(2 * d, model.dpn)] = grad[:, None]  # rods: not the twist (the last)
    return np.minimum(out, 1.0).ravel()


def increment_scale(system: System) -> NDArray[np.float64]:
    """The scale ``s_i`` of every coordinate of ``system`` (module docstring), ``(n,)``."""
    out = np.ones(system.n)
    winched = _winched(system)
    for name, body in zip(system.names, system.flex, strict=False):
        if name in winched:
            continue
        s = body_scale(body)
        if s is not None:
            out[system.body_slice(name)] = s
    return out
