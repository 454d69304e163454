"""The seabed friction of static states (``[solver] static_friction``): the generalized force of
the seabeds' friction fully mobilized toward each line's anchor, capped where the tension would
go negative (:mod:`rancf.solvers.static_friction` solves with it; the static outputs count it in
the reactions)."""

from __future__ import annotations

import numpy as np
from numpy.typing import NDArray

from rancf.bodies.nodal_forces import nodal_axial_forces, recovers_axial_force
from rancf.bodies.section_outputs import SectionSampler
from rancf.system.seabed import pressing_weight

__all__ = ["seabed_friction", "static_friction_load"]


def static_friction_load(system, y: NDArray) -> NDArray[np.float64] | None:
    """:func:`seabed_friction` at ``y`` if ``system`` was solved with ``static_friction`` (its
    attribute set by :func:`rancf.solvers.static.solve_static`), else None."""
    return seabed_friction(system, y) if getattr(system, "static_friction", False) else None


#: Slip velocity over the obstacle's regularization ``ε`` (fully mobilized friction).
_SLIP = 1e6


def _seabed_pairs(system) -> list[tuple[int, str, NDArray, float]]:
    """(pair index, body, unit normal (3), ε) of every frictional seabed pair."""
    from rancf.system.contact import _geometry  # a system with contact has it loaded

    out = []
    for k, (body, name) in enumerate(getattr(system, "contact_pairs", [])):
        ob = system.obstacles[system.obstacle_names.index(name)]
        if ob.kind != "plane" or ob.body is not None or ob.friction <= 0.0:
            continue
        _, normal, _ = _geometry(ob, system.dim)
        if pressing_weight(system, body, normal) > 0.0:
            out.append((k, body, normal, float(ob.slip_velocity)))
    return out


def seabed_friction(system, y: NDArray, totals: dict | None = None) -> NDArray[np.float64]:
    """The generalized seabed friction force ``(n,)`` at model coordinates ``y`` (module
    docstring); zeros without frictional seabed contact.  ``totals``: filled with the friction
    force ``(dim,)`` each seabed (by name) exerts (a body on two seabeds: on its first)."""
    n, dim = system.n, system.dim
    pairs = _seabed_pairs(system)
    f = np.zeros(n)
    if not pairs:
        return f
    y = np.ascontiguousarray(y, dtype=float)
    v = np.zeros(n)
    plan = []
    seen: set[str] = set()
    for k, body, normal, eps in pairs:
        if body in seen:  # a body's nodes move once (on its first seabed)
            continue
        seen.add(body)
        model = system.bodies[body]
        sl = system.body_slice(body)
        nodes = model.q_from_y(y[sl]).reshape(model.n_nodes, model.dpn)
        x, g = nodes[:, :dim], nodes[:, dim : 2 * dim]
        nd = normal[:dim]
        at_start = float(x[0] @ nd) <= float(x[-1] @ nd)  # the anchor: the lower end
        t = g * (1.0 if at_start else -1.0)
        t = t - np.outer(t @ nd, nd)
        t /= np.maximum(np.linalg.norm(t, axis=1), 1e-300)[:, None]
        pts = np.empty(8 * model.n_el * system.contact_points)
        system.contact.points(k, y, None, pts)
        on = (pts.reshape(model.n_el, -1, 8)[..., 4] > 0.0).any(axis=1)
        moving = np.zeros(model.n_nodes, dtype=bool)
        moving[:-1] |= on
        moving[1:] |= on
        vb = np.zeros((model.n_nodes, model.dpn))
        vb[moving, :dim] = _SLIP * eps * t[moving]
        v[sl] += model.y_from_q(vb.ravel())
        plan.append((system.contact_pairs[k][1], model, sl, at_start))
    r0, r1 = np.zeros(n), np.zeros(n)
    system.contact.assemble(y, None, y, 0.0, 0.0, r0)
    system.contact.assemble(y, v, y, 0.0, 0.0, r1)
    full = r0 - r1  # r = -(contact forces): the friction part
    for name, model, sl, at_start in plan:
        fb = full[sl].reshape(model.n_nodes, model.dpn).copy()
        share = np.linalg.norm(fb[:, :dim], axis=1)
        order = np.arange(model.n_nodes)[::-1] if at_start else np.arange(model.n_nodes)
        touch = order[share[order] > 0.0]
        if touch.size:
            budget = max(_tension(model, y[sl], int(touch[0])), 0.0)
            before = np.r_[0.0, np.cumsum(share[touch])[:-1]]
            cut = np.clip((budget - before) / share[touch], 0.0, 1.0)
            fb[touch] *= cut[:, None]
        f[sl] = fb.ravel()
        if totals is not None:
            totals[name] = totals.get(name, np.zeros(dim)) + fb[:, :dim].sum(axis=0)
    return f


def _tension(model, y: NDArray, node: int) -> float:
    """The axial force at ``node`` of ``model`` at ``y``: from the nodal forces at an inner node
    (:func:`rancf.bodies.nodal_forces.nodal_axial_forces`, free of the strain's oscillation
    inside the elements), from the strain at an end."""
    if 0 < node < model.n_nodes - 1 and recovers_axial_force(model):
        return float(nodal_axial_forces(model, y, np.zeros_like(y))[node])
    return float(SectionSampler(model, 1).values(y)[node, 1])
