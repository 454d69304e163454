"""A line crossing the free surface: its buoyancy only under water, in the start shape, the
continuation's weight and the equilibrium, against a catenary of two weights by hand."""

from __future__ import annotations

import math

import numpy as np
import pytest
from scipy.optimize import fsolve

from rancf.scenario.scenario import load_scenario
from rancf.solvers.sag_start import SAG_START, sag_state
from rancf.solvers.static import solve_static
from rancf.solvers.system_equilibrium import SystemEquilibrium
from rancf.system.outputs import SystemOutputs
from rancf.system.seabed import element_weights, submerged_shares

#: A 150 m fibre rope (20 kg/m, displacing 14.9 kg/m of sea water: 196.2 N/m in air, 50.1 N/m
#: in water) from a pin 80 m under the surface to a pin 15 m above it, 100 m away; drawn
#: straight and lying along the bottom, its end installed at the upper pin.
CROSSING = """
[geometry]
kind = "line"
start = [0.0, -80.0]
end = [150.0, -80.0]
[mesh]
elements = {n}
[section]
area = 0.014492753623188406
inertia = 1.0e-7
[material]
density = 1380.0
youngs_modulus = 6.9e9
axial_strain = "engineering"
[fluid]
density = 1025.0
surface = 0.0
[hydro]
diameter = 0.136
[[supports]]
at = "start"
kind = "pin"
[[supports]]
at = "end"
kind = "pin"
position = [100.0, 15.0]
[loads]
gravity = [0.0, -9.81]
"""
LENGTH, EA = 150.0, 6.9e9 * 0.014492753623188406
MASS = 1380.0 * 0.014492753623188406
DRY = MASS * 9.81
WET = (MASS - 1025.0 * math.pi * 0.136**2 / 4.0) * 9.81


def _piece(h: float, va: float, w: float, ell: float, ea: float) -> tuple[float, float, float]:
    """The elastic catenary (tension ``EA (λ − 1)``) of weight ``w`` over ``ell`` unstretched
    metres from the vertical force ``va``: the horizontal and vertical moves and ``V`` after."""
    vb = va + w * ell
    x = h * ell / ea + h / w * (math.asinh(vb / h) - math.asinh(va / h))
    z = (vb * vb - va * va) / (2.0 * w * ea) + (math.hypot(h, vb) - math.hypot(h, va)) / w
    return x, z, vb


def _by_hand(ea: float) -> tuple[float, float, float]:
    """``(H, V0, s_c)``: the horizontal tension, the vertical force at the lower pin and the
    unstretched length under water of the rope, by its two catenaries meeting at the surface."""

    def gaps(p):
        h, v0, sc = p
        x1, z1, vc = _piece(h, v0, WET, sc, ea)
        x2, z2, _ = _piece(h, vc, DRY, LENGTH - sc, ea)
        return [z1 - 80.0, x1 + x2 - 100.0, z1 + z2 - 95.0]

    return tuple(fsolve(gaps, [2000.0, -300.0, 100.0], xtol=1e-13))


def _system(tmp_path, n):
    path = tmp_path / f"crossing{n}.toml"
    path.write_text(CROSSING.format(n=n))
    sc = load_scenario(path)
    return sc, sc.build_system()


def test_the_start_of_a_line_crossing_the_surface_is_its_catenary_of_two_weights(tmp_path):
    """The sagged start is the inextensible catenary of the rope's dry weight above the
    surface and its wet weight below (2 cm off it at 40 elements, the Gauss points' share of
    the crossing element; the catenary of the wet weight throughout is 0.63 m off)."""
    h, v0, sc = _by_hand(math.inf)
    for n, tol in ((40, 0.02), (80, 0.01)):
        _, system = _system(tmp_path, n)
        model = system.flex[0]
        z = sag_state(SystemEquilibrium(system), True)
        q = model.q_from_y(z[system.body_slice("body")])
        x = q.reshape(-1, 4)[:, :2]
        want = []
        for s in np.linspace(0.0, LENGTH, n + 1):
            x1, z1, vc = _piece(h, v0, WET, min(s, sc), math.inf)
            x2, z2, _ = _piece(h, vc, DRY, max(s - sc, 1e-300), math.inf)
            want.append((x1 + x2, z1 + z2 - 80.0))
        assert np.abs(x - np.array(want)).max() < tol
        shares = submerged_shares(system, "body", q)
        assert shares[0] == 1.0 and shares[-1] == 0.0
        w = element_weights(system, "body", q)[:, 1]
        assert w[0] == pytest.approx(-WET) and w[-1] == pytest.approx(-DRY)


@pytest.mark.parametrize("n", [40, 80, 160])
def test_a_line_crossing_the_surface_meets_the_catenary_of_two_weights(tmp_path, n):
    """``rancf static``'s end forces of the rope crossing the surface: within 0.2 % of its
    tension from the elastic catenaries of its two weights (H = 2681.3 N, V = 9308.5 N at the
    upper pin; the buoyancy of the element crossing the surface acts at its Gauss points under
    water: 0.15 %, 0.05 %, 0.08 % at 40, 80, 160 elements)."""
    h, v0, sc = _by_hand(EA)
    top = np.array([h, v0 + WET * sc + DRY * (LENGTH - sc)])
    scenario, system = _system(tmp_path, n)
    res = solve_static(system, **scenario.static_options())
    assert res.method == SAG_START and res.relaxation_steps == 0
    ends = SystemOutputs(system, []).static_reactions(res.y, res.lam)
    assert np.abs(ends[1].force - top).max() < 2e-3 * np.linalg.norm(top)
    assert np.abs(ends[0].force + [h, v0]).max() < 2e-3 * np.linalg.norm(top)
