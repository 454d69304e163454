"""Touchdown-aware refinement of the static mesh: a line that meets a seabed with a bend its
elements cannot follow is solved on a finer mesh, and the user is told.

Where a cable leaves a seabed (a fixed plane its wet weight ``w`` presses on) under the axial
force ``T`` it bends with the catenary's radius ``T / w``, from none on the seabed to ``w / T``
off it.  A cubic element cannot take that jump in curvature while keeping its length, and a line
whose axial stiffness ``EA`` is many orders above its tension locks (membrane locking): the
stiff element resists the bend and the line settles where its forces are far off.  MoorPy's
U-shaped line (inextensible, ``EA = 1e12`` N; the half: 65 m, 100 N/m, ends 50 m apart and 20 m
above the bed, ``T / w = 2.63`` m) measured (docs/guide/statics.md, "Touchdown resolution"):
elements of 0.62 ``T / w``: H 16 % low (2.1 % of the fairlead tension), of 0.31 ``T / w``:
0.3 %, of 0.16: 0.2 % (the rest: the line's bending stiffness); the same line with ``EA = 1e8``
N is within 0.24 % already at 0.62 ``T / w``.  At 0.31 the stiff full U also holds several
equilibria that pass the checks (Newton from the start shape: V = 2262 N; relaxation: an
asymmetric state, V = 2246 and 2242 N at its ends; the heavy elastica: 2243 N), and the
continuation in ``EA`` (:mod:`rancf.solvers.axial_continuation`) does not converge there; at
0.16 and finer Newton, relaxation and the continuation agree (H = 258.04, 258.08 N at 0.16,
0.08: toward the elastica's 258.11 N).  Neither the seabed's quadrature (8 or 64 contact
points per element: the same H to 0.1 %) nor its stiffness (1e4 to 1e7 N/m²: H 225.6 to 219.6
N, MoorPy's 263.2 N) is the cause.

The static driver (:func:`rancf.runs.static.run_static`, ``rancf static``) therefore divides
every element of such a body into ``2^m`` (the same curve: a uniform refinement of the
geometry's mesh, ``[mesh] elements`` times ``2^m``) so that its elements are at most
:data:`TOUCHDOWN_RESOLUTION` of the bend radius:

* before solving, with the radius ``a = H / w`` of the line's sagged start shape where it meets
  the seabed (:func:`rancf.solvers.sag_start.touchdown_radius`: the inextensible catenary lying
  on the seabed, MoorPy's frictionless shape);
* after solving, with ``T / w`` of the solved state at its touchdowns
  (:func:`rancf.solvers.static_checks.touchdown_ratios`): the body is refined further and the
  static solve repeated once.

Each refinement is one line of the run's warnings naming the body, its element counts and the
radius.  At most :data:`MAX_ELEMENTS` elements per body; a scenario that names nodes by index
(a support, load, sensor or joint at node ``N`` other than the ends) is not refined (its nodes
would move) and its warning line says so; a touchdown longer than its bend radius there is
refused by the static checks as before.
A time-domain run that starts from its static equilibrium (``solver.initial_state =
"static"``, :func:`rancf.runs.simulate.plan_simulate`) takes the same rule before its solve
(:func:`refine_for_start`): the line whose sagged start shape meets the seabed with a bend its
elements do not resolve is refined for the static start and the dynamics that go on from it
(the same curve and model, on the finer mesh that the static solve needs: the unresolved bend
would lock the dynamics as it locks the statics), with the same warning line; its sensors and
outputs are those of the refined line.  The check after the solve is ``rancf static``'s only:
a time-domain run whose solved touchdown is still unresolved is refused by the static checks,
naming the bend and the element.  The other analyses (modes, buckling) keep the user's mesh.
"""

from __future__ import annotations

import math
import re
from dataclasses import dataclass
from typing import Any

__all__ = [
    "TOUCHDOWN_RESOLUTION",
    "FREE_RESOLUTION",
    "MAX_ELEMENTS",
    "MeshNote",
    "Refinement",
    "refine_for_touchdowns",
    "refine_for_start",
    "refined",
]

#: Elements at a touchdown at most this fraction of the bend radius ``T / w`` (module docstring:
#: a third left the stiff U with several equilibria).
TOUCHDOWN_RESOLUTION = 1.0 / 6.0
#: Elements of a line hanging free at most this multiple of its smallest bend radius ``H / w``
#: (module docstring; its curvature has no jump there).
FREE_RESOLUTION = 1.0
#: A refined body has at most this many elements.
MAX_ELEMENTS = 2560


def _halvings(ratio: float, n: int, resolution: float = TOUCHDOWN_RESOLUTION) -> int:
    """How many times ``n`` elements whose length is ``ratio`` bend radii are halved to at most
    ``resolution`` of it (0 when resolved or at :data:`MAX_ELEMENTS`)."""
    if not ratio > resolution:
        return 0
    m = math.ceil(math.log2(ratio / resolution) - 1e-12) if math.isfinite(ratio) else 1
    while m > 0 and n * 2**m > MAX_ELEMENTS:
        m -= 1
    return max(m, 0)


@dataclass(frozen=True)
class MeshNote:
    """One warning line about a body's mesh at a touchdown: the body and the line."""

    body: str
    text: str

    def __str__(self) -> str:
        return self.text


@dataclass(frozen=True)
class Refinement:
    """What :func:`refine_for_touchdowns` decided: the refined scenario (None: the mesh is
    kept) and one note per body it refined or would have refined."""

    scenario: Any | None
    notes: tuple[MeshNote, ...] = ()


def refine_for_touchdowns(
    sc: Any,
    system: Any,
    ratios: dict[str, tuple[float, float]],
    use: str = "the static solve",
    free: dict[str, tuple[float, float]] | None = None,
) -> Refinement:
    """``sc`` with the elements of every body of ``system`` whose touchdown ``ratios``
    (element length over bend radius, and that element's length) exceed
    :data:`TOUCHDOWN_RESOLUTION`, or whose ``free`` ratios (of a line hanging free, at its
    smallest bend radius) exceed :data:`FREE_RESOLUTION`, divided (module docstring), and the
    notes; no scenario and no notes when nothing needs it, no scenario and notes saying so
    where the scenario names nodes by index.  ``use``: what the refined mesh is for, named in
    the notes."""
    counts = _element_counts(sc)
    factors: dict[str, int] = {}
    why: dict[str, str] = {}
    rules = (
        (ratios, TOUCHDOWN_RESOLUTION, "where it meets the seabed it bends with the radius T/w"),
        (free or {}, FREE_RESOLUTION, "hanging free it bends with the radius H/w"),
    )
    for found, resolution, where in rules:
        for name, (ratio, ell) in found.items():
            n = system.bodies[name].n_el
            m = 0 if name not in counts else _halvings(ratio, n, resolution)
            if m > 0:
                factors[name] = 2**m
                why[name] = (
                    f"{where} = {ell / ratio:.3g} m, which its {ell:.3g} m elements there do "
                    f"not resolve (at most {resolution:.2g} of it: docs/guide/statics.md)"
                )
    if not factors:
        return Refinement(None)
    if _node_indexed(sc.model_dump(by_alias=True, exclude_unset=True)):
        return Refinement(
            None,
            tuple(
                MeshNote(
                    name,
                    f"body {name!r}: {text}; the scenario names nodes by index, so {use} "
                    f"keeps its {system.bodies[name].n_el} elements: refine [mesh] elements",
                )
                for name, text in why.items()
            ),
        )
    notes = tuple(
        MeshNote(
            name,
            f"body {name!r}: its {system.bodies[name].n_el} elements refined to "
            f"{system.bodies[name].n_el * f} for {use}: {why[name]}",
        )
        for name, f in factors.items()
    )
    return Refinement(refined(sc, factors), notes)


def refine_for_start(sc: Any, system: Any, use: str = "the static solve") -> Refinement:
    """:func:`refine_for_touchdowns` of ``sc`` (its ``system``) before a static solve, with the
    bend radii of the lines' sagged start shapes where they meet a seabed
    (:func:`start_ratios`): the one rule of ``rancf static`` and of a time-domain run's static
    start (module docstring); ``use`` as there."""
    from rancf.solvers.sag_start import start_free_bends

    return refine_for_touchdowns(sc, system, start_ratios(system), use, start_free_bends(system))


def refined(sc: Any, factors: dict[str, int]) -> Any:
    """The scenario ``sc`` with the ``[mesh] elements`` of each body in ``factors`` multiplied
    by its factor (a one-body file's body is ``"body"``)."""
    from rancf.scenario.scenario import Scenario

    d = sc.model_dump(by_alias=True, exclude_unset=True)
    if "mesh" in d and "body" in factors:
        d["mesh"]["elements"] *= factors["body"]
    for b in d.get("bodies", []):
        if b.get("name") in factors and "mesh" in b:
            b["mesh"]["elements"] *= factors[b["name"]]
    return Scenario.from_dict(d, sc.path)


def _element_counts(sc: Any) -> dict[str, int]:
    """``[mesh] elements`` per line body of ``sc`` (one-body file: ``"body"``; a shell's
    ``[nu, nv]`` is not refined here)."""
    return {
        b.name: int(b.mesh.elements)
        for _, b in sc.body_tables
        if getattr(b, "mesh", None) is not None and isinstance(b.mesh.elements, int)
    }


_NODE = re.compile(r"(?:^|:)(-?\d+)$")


def _node_indexed(d: Any) -> bool:
    """Whether the dumped scenario ``d`` names a node by index other than the ends (``at`` or
    ``between`` values ``N`` or ``"BODY:N"``, ``N`` not 0 or -1)."""
    if isinstance(d, list):
        return any(_node_indexed(v) for v in d)
    if not isinstance(d, dict):
        return False
    for k, v in d.items():
        if k in ("at", "between"):
            for p in v if isinstance(v, list) else [v]:
                m = _NODE.search(p) if isinstance(p, str) else None
                node = int(m.group(1)) if m else p if isinstance(p, int) else None
                if node is not None and node not in (0, -1):
                    return True
        elif _node_indexed(v):
            return True
    return False


def start_ratios(system: Any) -> dict[str, tuple[float, float]]:
    """Per cable body whose sagged start shape meets a seabed, the largest ratio of the length
    of an element holding a touchdown point of that shape to its bend radius there, and that
    element's length (:func:`rancf.solvers.sag_start.start_touchdowns`)."""
    from rancf.solvers.sag_start import start_touchdowns

    return start_touchdowns(system)
