"""The default penalty stiffness of a seabed: a fixed plane that a line's own weight presses on.

A seabed is a fixed plane in a ``[fluid]`` facing up against the body's gravity.  A line resting
on it under its wet weight per reference length ``w_n`` (the component of
its weight in water along the plane's inward normal) sinks by ``δ = w_n / k + d / 2`` (the
penalty of :mod:`rancf.system.contact` with onset ``d``).  For a seabed (``w_n > 0``) with no
``stiffness`` of its own, ``k`` is chosen so
that the weight alone presses the tube in by :data:`SEABED_PENETRATION` of its diameter ``D``:

``k = w_n / (SEABED_PENETRATION D)``, ``w_n = (ρ A − ρ_f A_f) (−g · n̂)``

(``ρ A`` the body's mass per length, ``ρ_f A_f`` that of the fluid it displaces when it has
``hydro`` coefficients in a ``[fluid]``, ``A_f = π d² / 4`` with the hydrodynamic diameter,
``g`` the body's gravity, ``n̂`` the plane's unit outward normal; docs/guide/contact.md).
A chain of 2457 N/m in water and ``D = 0.216`` m gets 1.1e6 N/m² (MoorDyn's seabed
``kBot D`` is 6.5e5 N/m²); the steel-cable default ``E / 10`` would be 1e4 times stiffer, which a
static solve from a stress-free line cannot follow.  Every other obstacle (cylinders, spheres,
planes carried by a rigid body, walls, a ceiling, a weightless body, and dry ground: a cable
dropped on a floor needs the stiff default to stay within 1 % of its radius through the impact,
``tests/system/test_contact_ground.py``) keeps ``E / 10``.

The weight per length is one formula, ``(ρ A − ρ_f A_f s) g`` with ``s`` the share under water
(:func:`weight_per_length`): ``s = 1`` for the seabed's pressing weight (:func:`wet_weight`), the
share of each element's Gauss points below the free surface for the start shape and the
continuation in ``EA`` of a line crossing it (:func:`element_weights`).
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np

__all__ = [
    "SEABED_PENETRATION",
    "seabed_stiffness",
    "pressing_weight",
    "wet_weight",
    "weight_per_length",
    "submerged_shares",
    "element_weights",
]

#: The default seabed stiffness lets the line's own wet weight press it in by this fraction of
#: its diameter.
SEABED_PENETRATION = 0.01


def weight_per_length(system: Any, body: str, submerged: Any = 1.0) -> np.ndarray:
    """The weight per reference length [N/m] of flexible body ``body`` of ``system`` where the
    share ``submerged`` of it lies below the free surface, as vectors (3 components; one row per
    entry of an array ``submerged``):

    ``(ρ A − ρ_f A_f s) g``

    (module docstring; ``ρ_f A_f`` where the body has ``hydro`` coefficients in a ``[fluid]``,
    else 0; the one formula of :func:`wet_weight` and :func:`element_weights`); zero without
    gravity."""
    model = system.bodies[body]
    share = np.asarray(submerged, dtype=float)
    g = getattr(model, "gravity", None)
    if g is None:
        return np.zeros(share.shape + (3,))
    g3 = np.r_[np.asarray(g, float), np.zeros(3 - len(g))]
    mass = model.material.density * model.section.area
    fluid, hydro = getattr(system, "fluid", None), getattr(system, "hydro", {}) or {}
    displaced = 0.0
    if fluid is not None and body in hydro:
        d = hydro[body].line_diameter(model.section.area)
        displaced = fluid.density * math.pi * d * d / 4.0
    return np.asarray((mass - displaced * share)[..., None] * g3, dtype=float)


def wet_weight(system: Any, body: str) -> np.ndarray:
    """The wet weight per reference length [N/m] of flexible body ``body`` of ``system`` as a
    vector (3 components): :func:`weight_per_length` wholly submerged, ``(ρ A − ρ_f A_f) g``
    (the buoyancy counted wherever the body has ``hydro`` coefficients in a ``[fluid]``); zero
    without gravity, against ``g`` for a line lighter than the water it displaces."""
    return weight_per_length(system, body, 1.0)


def submerged_shares(system: Any, body: str, q: Any) -> np.ndarray:
    """Per element of cable body ``body`` of ``system`` in the nodal coordinates ``q``, the
    share of its reference length below the fluid's still free surface: the Gauss weights
    ``w_g J0`` of the points below it over the element's (the points the fluid's buoyancy acts
    at, src/cpp/fluid/fluid.cpp); ones without a surface (or for other elements)."""
    model = system.bodies[body]
    fluid = getattr(system, "fluid", None)
    cable = model.family.cable_kernel(model.kernel)
    if fluid is None or fluid.surface is None or cable is None:
        return np.ones(model.n_el)
    e = np.asarray(q, dtype=float)[model.element_dofs].reshape(model.n_el, 4, model.dim)
    height = np.einsum("eqk,ek->eq", cable.n0, e[:, :, -1])
    wet = cable.wj * (height < fluid.surface)
    return np.asarray(wet.sum(axis=1) / cable.wj.sum(axis=1), dtype=float)


def element_weights(system: Any, body: str, q: Any) -> np.ndarray:
    """The weight per reference length [N/m] of every element of cable body ``body`` of
    ``system`` in the nodal coordinates ``q``, ``(n_el, 3)``: :func:`weight_per_length` with
    the element's share below the free surface (:func:`submerged_shares`): the buoyancy of a
    line crossing the surface only where it is under water."""
    return weight_per_length(system, body, submerged_shares(system, body, q))


def pressing_weight(system: Any, body: str, normal: np.ndarray) -> float:
    """The wet weight per reference length [N/m] of flexible body ``body`` of ``system`` along
    the inward normal ``-normal`` (unit, 3 components) of a plane: ``(ρ A − ρ_f A_f) (−g · n̂)``
    (module docstring, :func:`wet_weight`); 0 without gravity, negative when it lifts the body
    off."""
    return float(-(wet_weight(system, body) @ normal))


def seabed_stiffness(system: Any, body: str, obstacle: Any, normal: np.ndarray) -> float | None:
    """The default penalty stiffness [N/m²] of ``obstacle`` for flexible body ``body`` when it is
    a seabed (a fixed plane the body's wet weight presses on; module docstring), else None (the
    caller's default ``E / 10``)."""
    if obstacle.kind != "plane" or obstacle.body is not None or system.fluid is None:
        return None
    w_n = pressing_weight(system, body, normal)
    if not w_n > 0.0:
        return None
    diameter = 2.0 * system.bodies[body].section.radius
    return w_n / (SEABED_PENETRATION * diameter)
