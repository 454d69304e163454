"""A clamped quarter circle under a small tip load against Castigliano's deflection
``δ = π P R³ / (4 EI)`` along the load (the load parallel to the clamped end's tangent): the
numbers the README gives for how many RANCF and ANCF elements its deformation needs."""

from __future__ import annotations

import math

import pytest

from rancf.runs.static import run_static
from rancf.scenario.scenario import parse_scenario

R, P, E, RADIUS = 1.0, 1.0, 2.0e11, 0.01
EI = E * math.pi * RADIUS**4 / 4.0
EXACT = math.pi * P * R**3 / (4.0 * EI)


def _deflection(element: str, elements: int) -> float:
    s = math.sqrt(0.5)
    raw = {
        "geometry": {
            "kind": "conic",
            "start": [R, 0.0],
            "end": [0.0, R],
            "angles_deg": [45.0, 45.0],
            "point": [R * s, R * s],
        },
        "mesh": {"elements": elements, "element": element},
        "section": {"radius": RADIUS},
        "material": {"density": 7800.0, "youngs_modulus": E},
        "supports": [{"at": "start", "kind": "clamp"}],
        "loads": {"point": [{"at": "end", "force": [0.0, P]}]},
        "sensors": [{"name": "tip", "kind": "position", "at": "end"}],
    }
    return run_static(parse_scenario(raw)).sensors["tip_y"] - R


@pytest.mark.parametrize(
    ("element", "shares"),
    [("rancf", (0.39, 0.94, 0.99)), ("ancf", (0.11, 0.92, 0.99))],
)
def test_tip_deflection_share_with_one_two_and_four_elements(element, shares):
    got = [_deflection(element, n) / EXACT for n in (1, 2, 4)]
    assert got == pytest.approx(shares, abs=0.005), got
