"""Scenario tables ``[geometry]``, ``[mesh]``, ``[solver]`` and ``[modes]``: keys, limits, parsers.

Called in this order by :func:`rancf.model.scenario.parse_scenario`; each parser returns the table
with defaults filled in and values checked (errors name the key, see
:mod:`rancf.model.scenario_checks`).
"""

from __future__ import annotations

from typing import TYPE_CHECKING, Any

from rancf.elements.mapping import K_RANGE  # the factors a scenario may fix
from rancf.geometry.conic import LENGTH_RANGE
from rancf.model.analysis import MAX_LOAD_STEPS, MAX_NEWTON
from rancf.model.scenario_checks import (
    _REQ,
    _choice,
    _err,
    _guard,
    _integer,
    _number,
    _repr,
    _table,
    _vector,
)

if TYPE_CHECKING:
    from rancf.model.analysis import DynamicOptions

__all__ = [
    "MAX_ELEMENTS",
    "K_RANGE",
    "ELEMENTS",
    "GEOMETRY_KEYS",
    "parse_geometry",
    "parse_mesh",
    "parse_solver",
    "dynamic_options",
    "parse_modes",
]


#: Largest size of a geometry coordinate [m] (``start``, ``end``, ``point``, ``control_points``):
#: the longest chord a conic may have (:data:`rancf.geometry.conic.LENGTH_RANGE`).
MAX_COORDINATE = LENGTH_RANGE[1]
#: Largest ratio of two NURBS weights (a curve's shape depends on the ratios only).
MAX_WEIGHT_RATIO = 1e12
#: Largest ``mesh.elements`` (and total number of elements of a NURBS mesh).
MAX_ELEMENTS = 1_000_000
#: Element kinds of ``mesh.element``.
ELEMENTS = ("rancf", "ancf", "beam", "rod")
#: Keys of ``[geometry]`` for each kind.
GEOMETRY_KEYS = {
    "conic": ("start", "end", "angles_deg", "point"),
    "line": ("start", "end"),
    "nurbs": ("degree", "knots", "control_points", "weights"),
    "cad": ("file", "curve"),
}


def parse_geometry(path: str, raw: Any) -> tuple[dict[str, Any], int]:
    """Validate the ``[geometry]`` table.

    Parameters
    ----------
    path : str
        The scenario file, named in errors.
    raw : Any
        ``[geometry]`` as read.

    Returns
    -------
    dict
        The table with the keys of its kind checked (``kind = "cad"`` also reads the file).
    int
        The dimension of the geometry, 2 or 3.
    """
    g = _table(
        path,
        "geometry",
        raw,
        {
            "kind": _REQ,
            "start": None,
            "end": None,
            "angles_deg": None,
            "point": None,
            "degree": None,
            "knots": None,
            "control_points": None,
            "weights": None,
            "file": None,
            "curve": None,
        },
    )
    kind = _choice(path, "geometry.kind", g["kind"], tuple(GEOMETRY_KEYS))
    for k in g:
        if k != "kind" and g[k] is not None and k not in GEOMETRY_KEYS[kind]:
            raise _err(
                path,
                f"geometry.{k}",
                f"does not apply to kind = {kind!r} (its keys: {', '.join(GEOMETRY_KEYS[kind])})",
            )
    if kind == "cad":
        from rancf.model.cad_geometry import parse_cad_geometry

        dim = parse_cad_geometry(path, g)
    if kind in ("conic", "line"):
        for k in ("start", "end"):
            if g[k] is None:
                raise _err(path, f"geometry.{k}", f"required key is missing for kind = {kind!r}")
        g["start"] = _vector(path, "geometry.start", g["start"], (2, 3), MAX_COORDINATE)
        dim = len(g["start"])
        g["end"] = _vector(path, "geometry.end", g["end"], (dim,), MAX_COORDINATE)
    if kind == "conic":
        for k in ("angles_deg", "point"):
            if g[k] is None:
                raise _err(path, f"geometry.{k}", "required key is missing for kind = 'conic'")
        g["angles_deg"] = _vector(path, "geometry.angles_deg", g["angles_deg"], (2,))
        g["point"] = _vector(path, "geometry.point", g["point"], (dim,), MAX_COORDINATE)
    if kind == "nurbs":
        for k in ("degree", "knots", "control_points"):
            if g[k] is None:
                raise _err(path, f"geometry.{k}", "required key is missing for kind = 'nurbs'")
        g["degree"] = _integer(path, "geometry.degree", g["degree"], 2)
        if g["degree"] > 3:
            raise _err(path, "geometry.degree", f"must be 2 or 3, got {_repr(g['degree'])}")
        if not isinstance(g["control_points"], list) or not g["control_points"]:
            raise _err(path, "geometry.control_points", "must be a list of points")
        if len(g["control_points"]) < g["degree"] + 1:
            raise _err(
                path,
                "geometry.control_points",
                f"a NURBS of degree {g['degree']} needs at least {g['degree'] + 1} control "
                f"points, got {len(g['control_points'])}",
            )
        first = _vector(
            path, "geometry.control_points[0]", g["control_points"][0], (2, 3), MAX_COORDINATE
        )
        dim = len(first)
        g["control_points"] = [
            _vector(path, f"geometry.control_points[{i}]", p, (dim,), MAX_COORDINATE)
            for i, p in enumerate(g["control_points"])
        ]
        if not isinstance(g["knots"], list):
            raise _err(path, "geometry.knots", "must be a list of numbers")
        g["knots"] = [_number(path, f"geometry.knots[{i}]", x) for i, x in enumerate(g["knots"])]
        if g["weights"] is not None:
            if not isinstance(g["weights"], list):
                raise _err(path, "geometry.weights", "must be a list of numbers")
            g["weights"] = [
                _number(path, f"geometry.weights[{i}]", x) for i, x in enumerate(g["weights"])
            ]
            w = [abs(x) for x in g["weights"] if x != 0.0]
            if w and max(w) > MAX_WEIGHT_RATIO * min(w):
                raise _err(
                    path,
                    "geometry.weights",
                    f"the largest weight may be at most {MAX_WEIGHT_RATIO:g} times the smallest, "
                    f"got {max(w):g} and {min(w):g}",
                )
    return g, dim


def parse_mesh(path: str, raw: Any, dim: int) -> dict[str, Any]:
    """Validate the ``[mesh]`` table for a geometry of dimension ``dim``.

    Parameters
    ----------
    path : str
        The scenario's path (named in errors).
    raw : Any
        The table as read from the file.
    dim : int
        Dimension of the geometry, 2 or 3 (beams need 2, rods 3).

    Returns
    -------
    dict
        The table with defaults filled in.
    """
    m = _table(
        path,
        "mesh",
        raw,
        {
            "elements": _REQ,
            "element": "rancf",
            "k": "opt",
            "spacing": "arc",
            "quadrature_points": None,
        },
    )
    m["elements"] = _integer(path, "mesh.elements", m["elements"], 1)
    if m["elements"] > MAX_ELEMENTS:
        raise _err(
            path, "mesh.elements", f"must be at most {MAX_ELEMENTS}, got {_repr(m['elements'])}"
        )
    m["element"] = _choice(path, "mesh.element", m["element"], ELEMENTS)
    if m["k"] != "opt":
        k = _number(path, "mesh.k", m["k"])
        lo, hi = K_RANGE
        if not lo <= k <= hi:
            raise _err(path, "mesh.k", f'must be "opt" or a number in [{lo:g}, {hi:g}], got {k!r}')
        m["k"] = k
    m["spacing"] = _choice(path, "mesh.spacing", m["spacing"], ("arc", "parameter"))
    if m["quadrature_points"] is not None:
        q = _integer(path, "mesh.quadrature_points", m["quadrature_points"], 2)
        if q > 64:
            raise _err(path, "mesh.quadrature_points", f"must be at most 64, got {_repr(q)}")
        m["quadrature_points"] = q
    if m["element"] == "beam" and dim != 2:
        raise _err(path, "mesh.element", "the beam element is planar: use 2-coordinate geometry")
    if m["element"] == "rod" and dim != 3:
        raise _err(path, "mesh.element", "the rod element is spatial: use 3-coordinate geometry")
    return m


def parse_solver(path: str, raw: Any) -> dict[str, Any]:
    """Validate the ``[solver]`` table, also as :class:`~rancf.model.analysis.DynamicOptions`.

    Parameters
    ----------
    path : str
        The scenario's path (named in errors).
    raw : Any
        The table as read from the file (``{}`` when absent).

    Returns
    -------
    dict
        The table with defaults filled in.
    """
    sv = _table(
        path,
        "solver",
        raw,
        {
            "t_end": 1.0,
            "step": 1e-3,
            "rho_inf": 0.9,
            "load_steps": 10,
            "adaptive": False,
            "rtol": 1e-5,
            "output_step": None,
            "min_step": None,
            "newton_tol": 1e-10,
            "max_newton": 12,
            "newton": "full",
            "static_method": "load",
            "initial_state": "reference",
        },
    )
    sv["t_end"] = _number(path, "solver.t_end", sv["t_end"], positive=True)
    sv["step"] = _number(path, "solver.step", sv["step"], positive=True)
    sv["rho_inf"] = _number(path, "solver.rho_inf", sv["rho_inf"])
    if not 0 <= sv["rho_inf"] <= 1:
        raise _err(path, "solver.rho_inf", f"must be in [0, 1], got {_repr(sv['rho_inf'])}")
    sv["load_steps"] = _integer(path, "solver.load_steps", sv["load_steps"], 1)
    if sv["load_steps"] > MAX_LOAD_STEPS:
        raise _err(
            path,
            "solver.load_steps",
            f"must be at most {MAX_LOAD_STEPS}, got {_repr(sv['load_steps'])}",
        )
    if not isinstance(sv["adaptive"], bool):
        raise _err(path, "solver.adaptive", f"must be true or false, got {_repr(sv['adaptive'])}")
    sv["rtol"] = _number(path, "solver.rtol", sv["rtol"], positive=True)
    for k in ("output_step", "min_step"):
        if sv[k] is not None:
            sv[k] = _number(path, f"solver.{k}", sv[k], positive=True)
    sv["newton_tol"] = _number(path, "solver.newton_tol", sv["newton_tol"], positive=True)
    sv["max_newton"] = _integer(path, "solver.max_newton", sv["max_newton"], 1)
    if sv["max_newton"] > MAX_NEWTON:
        raise _err(
            path,
            "solver.max_newton",
            f"must be at most {MAX_NEWTON}, got {_repr(sv['max_newton'])}",
        )
    sv["newton"] = _choice(path, "solver.newton", sv["newton"], ("full", "modified"))
    sv["static_method"] = _choice(
        path, "solver.static_method", sv["static_method"], ("load", "arc_length")
    )
    sv["initial_state"] = _choice(
        path, "solver.initial_state", sv["initial_state"], ("reference", "static")
    )
    _guard(path, "solver", lambda: dynamic_options(sv))
    return sv


def dynamic_options(sv: dict[str, Any]) -> DynamicOptions:
    """:class:`~rancf.model.analysis.DynamicOptions` of a validated ``[solver]`` table.

    Parameters
    ----------
    sv : dict
        The table as returned by :func:`parse_solver`.

    Returns
    -------
    DynamicOptions
        The options of a dynamic run (their own checks raise :class:`~rancf.errors.InputError`).
    """
    from rancf.model.analysis import DynamicOptions

    keys = ("t_end", "step", "rho_inf", "adaptive", "rtol", "min_step", "output_step")
    keys += ("newton_tol", "max_newton", "newton")
    return DynamicOptions(**{k: sv[k] for k in keys})


def parse_modes(path: str, raw: Any) -> dict[str, Any]:
    """Validate the ``[modes]`` table: ``count`` >= 1, ``about`` the reference or static state.

    Parameters and return value as for :func:`parse_solver` (``raw`` is ``{}`` when absent).
    """
    md = _table(path, "modes", raw, {"count": 6, "about": "reference"})
    md["count"] = _integer(path, "modes.count", md["count"], 1)
    md["about"] = _choice(path, "modes.about", md["about"], ("reference", "static"))
    return md
