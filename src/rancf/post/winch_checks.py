"""Warnings for what a winch's body does not yet carry exactly.

A winch's material flows through the body's mesh (docs/derivations/variable-length.md §2): the
material's velocity is the mesh's plus a part along the tangent.  The inertia of the line takes
it; the friction of contact and the fluid's axial loads (axial drag, axial added mass) take the
mesh's velocity and acceleration.  Normal contact and the fluid's normal loads are exact (the
difference is along the tangent); friction and axial loads along a paid-out or reeled-in line
are not, so a run that has them says so once.
"""

from __future__ import annotations

from rancf.system import System

__all__ = ["winch_warnings"]


def winch_warnings(system: System) -> list[str]:
    """One warning per winch whose body touches a frictional obstacle or has axial fluid
    coefficients (module docstring)."""
    friction: dict[str, list[str]] = {}
    if system.contact is not None:
        obstacles = dict(zip(system.obstacle_names, system.obstacles, strict=True))
        for body, ob in system.contact_pairs:
            if obstacles[ob].friction > 0.0:
                friction.setdefault(body, []).append(ob)
    out = []
    for w in system.winches:
        body = w.at.split(":", 1)[0]
        what = []
        if body in friction:
            what.append("friction on " + ", ".join(repr(o) for o in friction[body]))
        h = system.hydro.get(body)
        if system.fluid is not None and h is not None:
            axial = (("axial drag", h.drag_axial), ("axial added mass", h.added_mass_axial))
            what += [k for k, v in axial if v > 0.0]
        if what:
            out.append(
                f"winch {w.name!r}: {' and '.join(what)} along {body} use the mesh's velocity, "
                "not the material's (the part along the line is missed while it is paid out or "
                "reeled in; normal forces are exact)"
            )
    return out
