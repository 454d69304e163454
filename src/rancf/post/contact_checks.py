"""Warnings for contact set up wrongly, read off the system's initial configuration (``y0``):
the run goes on, each warning is one line (:mod:`rancf.post.checks`).

* A body that starts inside an obstacle by more than its section radius (its centre line is
  then past the obstacle's surface): the penalty pushes it out with a force of ``k`` times that
  depth over the whole length inside, at ``t = 0``.  Likewise two flexible bodies in contact
  (``body_contacts``) that start inside each other by more than the thinner radius.
* A frictional wrap with too few elements.  An element on a pulley of pitch radius ``R_c`` (the
  obstacle's radius plus the section's) spans the angle ``α = L_e / R_c``.  As the body moves
  over the pulley, elements pass from the free spans onto the wrap and off it, and a cubic
  element cannot follow a shape that is part straight and part arc: the friction transmitted
  errs.  Measured on an Atwood machine whose rope sticks to a turning pulley
  (``benchmarks/wrap_elements.py``: 1.2 kg and 1 kg, μ = 0.5, the rope moving 0.11 m over the
  pulley), the acceleration comes out low by 7.4 % with 45° per element, 1.0 % with 22.5°,
  0.19 % with 11.25° and 0.13 % with 5.6°: about ``7.4 % (α / 45°)^2.8``
  (:func:`wrap_error`), Euler–Eytelwein's ``e^{μφ}`` being reached as ``α → 0``.  Above
  :data:`WRAP_ANGLE_LIMIT` (15°: about 0.3 %) the warning gives that estimate and the number
  of elements the wrap needs.

The points of a pair are the contact's own (``Contact.points``: the compiled gap at each of the
``contact_points`` Gauss points per element); a point touches when its gap is below a tenth of
the section radius and an element is on the wrap when most of its points touch.
"""

from __future__ import annotations

import numpy as np

from rancf.bodies.flexible import Model
from rancf.system import System

__all__ = ["contact_warnings", "wrap_error", "WRAP_ANGLE_LIMIT", "TOUCH_FACTOR"]

#: Largest angle one element may span on a frictional wrap without a warning [rad].
WRAP_ANGLE_LIMIT = np.radians(15.0)
#: A point touches an obstacle when its gap is below this fraction of the section radius.
TOUCH_FACTOR = 0.1


def wrap_error(alpha: float) -> float:
    """The error [%] of the motion over a frictional wrap with ``alpha`` [rad] per element: the
    fit ``7.4 (α / 45°)^2.8`` of the Atwood machine's (module docstring)."""
    return 7.4 * (alpha / np.radians(45.0)) ** 2.8


def _gaps(system: System, k: int, n_el: int) -> np.ndarray:
    """Gap ``(n_el, n_c)`` of pair ``k``'s contact points at ``y0``."""
    n_c = system.contact_points
    out = np.empty(8 * n_el * n_c)
    system.contact.points(k, np.ascontiguousarray(system.y0, float), None, out)
    return out.reshape(n_el, n_c, 8)[..., 3]


def _body_pairs(system: System) -> list[str]:
    """Pairs of flexible bodies in contact (``body_contacts``) that start inside each other by
    more than the thinner section radius (the gap of ``src/cpp/contact/body_contact.hpp``: the
    centre lines' distance less both radii)."""
    if not system.body_contacts:
        return []
    bo = np.empty(3 * len(system.body_contacts))
    system.contact.body_outputs(np.ascontiguousarray(system.y0, float), bo)
    out = []
    for k, (a, b) in enumerate(system.body_contacts):
        r = min(float(_flexible(system, x).section.radius) for x in (a, b))
        depth = -float(bo[3 * k])
        if depth > r:
            who = (
                f"{a} starts {depth:.4g} m inside itself"
                if a == b
                else (f"{a} and {b} start {depth:.4g} m inside each other")
            )
            out.append(
                f"{who}, more than the section radius {r:.4g} m: the contact pushes them apart "
                f"with {float(bo[3 * k + 2]):.4g} N at t = 0; check the bodies' geometry"
            )
    return out


def contact_warnings(system: System) -> list[str]:
    """The module docstring's warnings for every (flexible body, obstacle) pair of ``system``
    and every pair of flexible bodies in contact."""
    if system.contact is None:
        return []
    if not system.contact_pairs:
        return _body_pairs(system)
    from rancf.system.contact_states import contact_outputs

    forces = {
        k: float(np.linalg.norm(c.normal)) for k, c in contact_outputs(system, system.y0).items()
    }
    obstacles = dict(zip(system.obstacle_names, system.obstacles, strict=True))
    out = []
    for k, (name, ob_name) in enumerate(system.contact_pairs):
        body, ob = _flexible(system, name), obstacles[ob_name]
        rt = float(body.section.radius)
        g = _gaps(system, k, body.n_el)
        if -g.min() > rt:
            out.append(
                f"{name} starts {-g.min():.4g} m inside obstacle {ob_name!r}, more than its "
                f"section radius {rt:.4g} m: the contact pushes it out with {forces[ob_name]:.4g}"
                f" N at t = 0; check the obstacle's position and the body's geometry"
            )
        if ob.kind == "plane" or ob.friction <= 0.0:
            continue
        touch = g < TOUCH_FACTOR * rt  # (n_el, n_c)
        on = touch.mean(axis=1) > 0.5  # elements on the wrap: most of their points touch
        if not on.any():
            continue
        assert ob.radius is not None  # a cylinder's or a sphere's
        pitch = float(ob.radius) + rt
        lengths = body.mesh.arc_lengths()
        alpha = lengths[on] / pitch
        if alpha.max() <= WRAP_ANGLE_LIMIT * (1.0 + 1e-9):  # round-off of the arc lengths
            continue
        wrap = float(alpha.sum())
        need = int(np.ceil(wrap / WRAP_ANGLE_LIMIT - 1e-9))
        out.append(
            f"{name}: {int(on.sum())} element(s) on its {np.degrees(wrap):.3g}° frictional "
            f"wrap of {ob_name!r} (up to {np.degrees(alpha.max()):.3g}° each): the motion it "
            f"transmits errs by about {wrap_error(alpha.max()):.2g} % (measured on an Atwood "
            f"machine); give at least {need} elements on the wrap (at most "
            f"{np.degrees(WRAP_ANGLE_LIMIT):g}° each)"
        )
    return out + _body_pairs(system)


def _flexible(system: System, name: str) -> Model:
    """The flexible body ``name`` (bodies in contact are flexible)."""
    body = system.bodies[name]
    assert isinstance(body, Model)
    return body
