"""The shipped example scenarios: their names, what each is and which analyses ``rancf example
run`` makes of it, and their files.  Standard library only, so that ``rancf example list`` and
``copy`` load none of the studies."""

from __future__ import annotations

from importlib import resources
from pathlib import Path

__all__ = ["EXAMPLES", "SCENARIO_ANALYSES", "example_path"]

#: Shipped example scenarios (name -> what it is).
EXAMPLES = {
    "planar-pendulum": "paper 6.1 planar pendulum with an elliptical-arc cable",
    "spatial-pendulum": "paper 6.2 spatial pendulum with an elliptical-arc cable",
    "arc-vibration": "paper 6.3 free and forced vibration of a cable arc",
    "exact-geometry": "where exact geometry pays: 6.1 pendulum, E from 2e6 to 2e10 Pa",
}

#: Shipped scenarios that are not paper studies, and what ``rancf example run`` does with each
#: (:mod:`rancf.studies.scenario_example`): ``"simulate"``, ``"static"``, ``"modes"`` and/or
#: ``"buckling"``.
SCENARIO_ANALYSES: dict[str, tuple[str, ...]] = {
    "argyris-frame": ("modes", "buckling"),
    "atwood-guides": ("simulate",),
    "belt-drive": ("simulate",),
    "capstan": ("simulate",),
    "cantilever": ("static", "modes"),
    "crane-hoist": ("simulate",),
    "drum-hoist": ("static", "simulate"),
    "installed-hose": ("static", "simulate"),
    "mooring-line": ("static",),
    "power-line-gust": ("simulate",),
    "polyester-rope": ("static", "modes"),
    "power-line-sag": ("static",),
    "ring": ("modes", "simulate"),
    "scordelis-lo-roof": ("static", "modes"),
    "robot-cable": ("simulate",),
    "slider-crank": ("simulate",),
    "spin-up-beam": ("simulate",),
    "tether-payload": ("simulate",),
    "tether-reel-out": ("simulate",),
}


def example_path(name: str) -> Path:
    """Path of a shipped example scenario file."""
    return Path(str(resources.files("rancf.examples").joinpath(f"{name}.toml")))
