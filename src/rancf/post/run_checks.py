"""Checks of a run folder read back: its ``results.npz`` arrays fit together (not cut short, not
mixed from two runs) and its scenario is the one of its results, so that
:func:`rancf.post.run_data.load_body` refuses a damaged folder in one line instead of failing
later."""

from __future__ import annotations

from pathlib import Path
from typing import Any

import numpy as np

from rancf.bodies.families import FAMILIES
from rancf.errors import InputError

__all__ = ["check_results", "scenario_fits"]


def check_results(npz: Path, data: dict[str, Any]) -> None:
    """Refuse a ``results.npz`` whose arrays do not fit together (cut short, or mixed from two
    runs), naming what disagrees."""

    def bad(problem: str) -> InputError:
        return InputError("RUN_DIR", str(npz), f"a consistent results.npz ({problem})")

    meta = data["metadata"]
    if not isinstance(meta, dict):
        raise bad("its metadata is not a table")
    element, dim = meta.get("element"), meta.get("dim")
    dpn = None
    fam = FAMILIES.get(element) if isinstance(element, str) else None
    if fam is not None and isinstance(dim, int) and dim in fam.dims:
        dpn = fam.dofs_per_node(dim)
    if dpn is None:
        raise bad(f"element {element!r} in {dim!r} dimensions is not a known kind")
    names = meta.get("sensor_columns")
    if not isinstance(names, list) or not all(isinstance(n, str) for n in names):
        raise bad("its sensor columns are not a list of names")
    t = np.asarray(data["t"])
    n_t = t.size
    if t.ndim != 1 or n_t < 1 or not np.all(np.isfinite(t)) or np.any(np.diff(t) <= 0):
        raise bad("its times are not an increasing list of finite numbers")
    n_el = np.shape(data["scales"])[0] if np.ndim(data["scales"]) == 1 else -1
    n = (n_el + 1) * dpn
    shapes = {
        "scales": (n_el,),
        "weights": (n_el, 4),
        "reference": (n,),
        "q": (n_t, n),
        "v": (n_t, n),
        "kinetic": (n_t,),
        "strain": (n_t,),
        "gravity": (n_t,),
        "sensors": (n_t, len(names)),
    }
    if "directors" in data:
        shapes["directors"] = (n_t, n_el + 1, 3)
    if "a" in data:
        shapes["a"] = (n_t, n)
    if "along" in data:
        shapes["along"] = (n_t, *np.shape(data["along"])[1:])  # its columns: checked by its use
    if n_el < 1 or meta.get("n_elements", n_el) != n_el:
        raise bad(f"{n_el} element scales for {meta.get('n_elements')!r} elements")
    for key, shape in shapes.items():
        got = np.shape(data[key])
        if key == "sensors" and got == (n_t * len(names),):
            continue
        if got != shape:
            raise bad(f"{key} has shape {got}, expected {shape} for {n_t} times")


def scenario_fits(sc: Any, meta: dict[str, Any]) -> str | None:
    """Why the scenario ``sc`` is not the one of a run with ``meta`` (None: it fits)."""
    bodies = sc.data["bodies"]
    if len(bodies) != 1 or bodies[0]["kind"] != "flexible":
        return "the scenario is a system of several bodies, not one body's results"
    mesh = bodies[0]["mesh"]
    if mesh["element"] != meta["element"] or sc.dim != meta["dim"]:
        return (
            f"the scenario has {mesh['element']} elements in {sc.dim} dimensions, the results "
            f"{meta['element']} elements in {meta['dim']}"
        )
    kind = bodies[0]["geometry"]["kind"]
    if kind in ("conic", "line") and mesh["elements"] != meta["n_elements"]:
        return f"the scenario has {mesh['elements']} elements, the results {meta['n_elements']}"
    return None
