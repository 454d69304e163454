"""Lines in water against closed forms (docs/derivations/fluid.md section 5): a horizontal cable
sinking in still water reaches its terminal speed; a vertical line weightless in water, held up
by a buoy's pull, leans in a uniform current to the closed-form shape tan(phi) = k (L - s) / B."""

from __future__ import annotations

import math

import numpy as np

from rancf.bodies.flexible import Material, Model, PointLoad, Section, Support
from rancf.mesh.factories import mesh_line
from rancf.options import DynamicOptions
from rancf.solvers.dynamic import integrate
from rancf.solvers.static import solve_static
from rancf.system import System
from rancf.system.fluid import Fluid, Hydro

RHO_W, G = 1000.0, 9.81


def test_sinking_cable_reaches_terminal_speed():
    """v_T = sqrt(2 (rho_c - rho_w) g A / (rho_w C_d d)): the drag balances the weight in water;
    the whole free cable falls at it within 1 % after ten time constants."""
    d, rho_c, cd = 0.02, 2000.0, 1.2
    g = [0.0, -G]
    cable = Model(
        mesh_line([0, 0], [4, 0], 2),
        "rancf",
        Section.circular(d / 2),
        Material(rho_c, 1e9),
        [],
        gravity=g,
    )
    s = System(
        {"cable": cable},
        gravity=g,
        fluid=Fluid(RHO_W),
        hydro={"cable": Hydro(d, cd, 0.0, 1.0, 0.0)},
    )
    res = integrate(s, DynamicOptions(t_end=2.0, step=0.02))
    area = math.pi * d**2 / 4
    v_t = math.sqrt(2 * (rho_c - RHO_W) * G * area / (RHO_W * cd * d))
    v = res.v[-1].reshape(-1, 4)
    assert np.abs(v[:, 0]).max() < 1e-9  # no sideways motion
    assert np.allclose(v[:, 1], -v_t, rtol=1e-2, atol=0)
    assert np.abs(v[:, 1] / -v_t - 1).max() < 1e-2


def test_buoyed_line_leans_in_current_to_closed_form():
    """A line pinned at the seabed, weightless in water (its weight equals its buoyancy),
    pulled up at its free top by a buoy force B, in a uniform current U (normal drag only):
    the tension is B all along and tan(phi) = c (L - s), c = rho d Cd U^2 / (2 B), so the anchor
    leans at atan(c L) and the top sits at ((sqrt(1 + (cL)^2) - 1) / c, asinh(cL) / c)."""
    length, b_force, u, cd, d = 20.0, 600.0, 1.0, 1.2, 0.05
    r_sec = 0.002
    rho_line = RHO_W * (d / (2 * r_sec)) ** 2  # weight = buoyancy
    g = [0.0, -G]
    line = Model(
        mesh_line([0, 0], [0, length], 12),
        "rancf",
        Section.circular(r_sec),
        Material(rho_line, 2e11),
        [Support(0, "pin")],
        gravity=g,
        point_loads=[PointLoad(12, force=(0.0, b_force))],
    )
    s = System(
        {"line": line},
        gravity=g,
        fluid=Fluid(RHO_W, current=(u, 0.0)),
        hydro={"line": Hydro(d, cd, 0.0, 1.0, 0.0)},
    )
    res = solve_static(s, load_steps=5)
    c = 0.5 * RHO_W * d * cd * u**2 / b_force
    q = res.q.reshape(-1, 4)
    tan_anchor = q[0, 2] / q[0, 3]
    assert abs(tan_anchor / (c * length) - 1) < 1e-2
    top = q[-1, :2]
    want = np.array([(math.hypot(1, c * length) - 1) / c, math.asinh(c * length) / c])
    assert np.allclose(top, want, rtol=5e-3, atol=0)


def test_fluid_force_sensor_carries_the_weight_at_terminal_speed():
    """The scenario path: the sinking cable as a file; at terminal speed the ``fluid_force``
    sensor (buoyancy and drag) carries the cable's weight rho_c A L g, and its ``tension`` is
    zero (a free cable under uniform loads)."""
    import rancf
    from rancf.scenario import parse_scenario

    d = {
        "geometry": {"kind": "line", "start": [0.0, 0.0], "end": [4.0, 0.0]},
        "mesh": {"elements": 2},
        "section": {"radius": 0.01},
        "material": {"density": 2000.0, "youngs_modulus": 1e9},
        "fluid": {"density": RHO_W},
        "hydro": {"drag_normal": 1.2},
        "loads": {"gravity": [0.0, -G]},
        "solver": {"t_end": 2.0, "step": 0.02},
        "sensors": [
            {"name": "fluid", "kind": "fluid_force"},
            {"name": "mid", "kind": "tension", "at": 1},
        ],
    }
    result, names, values = rancf.simulate(parse_scenario(d))
    assert names == ["fluid_x", "fluid_y", "mid"]
    last = dict(zip(names, values[-1], strict=True))
    weight = 2000.0 * math.pi * 0.01**2 * 4.0 * G
    assert abs(last["fluid_x"]) < 1e-9 * weight
    assert abs(last["fluid_y"] / weight - 1) < 1e-2
    assert abs(last["mid"]) < 1e-6 * weight


def _chain_on_the_seabed(elements: int) -> tuple[dict, float]:
    """The 2D chain of the touchdown tests solved in statics: its sensors and its weight in
    water per length."""
    import rancf
    from rancf.post.results import sensor_table
    from rancf.scenario import parse_scenario

    area, rho_c, ea = 0.0366435, 7859.5, 1.2326e9
    d = {
        "geometry": {
            "kind": "nurbs",
            "degree": 2,
            "knots": [0, 0, 0, 1, 1, 1],
            "control_points": [[-300.0, -100.0], [-54.61196092449089, -100.0], [0.0, 0.0]],
        },
        "mesh": {"elements": elements},
        "section": {"area": area, "inertia": 3e-8},
        "material": {"density": rho_c, "youngs_modulus": ea / area},
        "fluid": {"density": 1025.0, "surface": 0.0},
        "hydro": {"diameter": 0.216},
        "obstacles": [
            {
                "name": "seabed",
                "kind": "plane",
                "point": [0.0, -100.108],
                "normal": [0.0, 1.0],
                "stiffness": 1e8,
            }
        ],
        "supports": [{"at": "start"}, {"at": "end"}],
        "loads": {"gravity": [0.0, -G]},
        "sensors": [
            {"name": "td", "kind": "touchdown", "obstacle": "seabed"},
            {"name": "fair", "kind": "reaction", "at": "end"},
            {"name": "bed", "kind": "contact_force", "obstacle": "seabed"},
        ],
    }
    sc = parse_scenario(d)
    system = sc.build_system()
    res = rancf.solve_static(system, 10)
    names, vals = sensor_table(system, sc.sensors, res.q, static=True, t=np.ones(1), lam=res.lam)
    w = (rho_c * area - 1025.0 * math.pi * 0.216**2 / 4) * G
    return dict(zip(names, vals[0], strict=True)), w


def _catenary_touchdown(v: dict, w: float) -> float:
    """Where the catenary of the model's horizontal tension leaves the seabed: its suspended
    part is sqrt(h^2 + 2 h H / w) long (no friction)."""
    suspended = math.sqrt(100.0**2 + 2 * 100.0 * v["fair_x"] / w)
    return -300.0 + 330.0 - suspended


def test_touchdown_of_a_mooring_line_against_the_catenary():
    """A 2D chain from an anchor on the seabed to a fairlead 100 m above it, in water: with the
    horizontal tension H the model gives and the weight in water w per length, the suspended
    part is a catenary of length sqrt(h^2 + 2 h H / w) (no friction), so the chain leaves the
    seabed that far along it from the fairlead; the ``touchdown`` sensor agrees within 0.15 of
    an element (11 m: the curvature's jump at the touchdown point is spread over the element
    holding it; measured 0.99 m), and the seabed and the anchor carry the laid length's
    weight."""
    v, w = _chain_on_the_seabed(30)
    laid = 300.0 + _catenary_touchdown(v, w)
    assert abs(v["td_x"] - (-300.0 + laid)) < 0.15 * 11.0
    assert abs(v["td_y"] + 100.0) < 0.05 * 0.108
    anchor = w * 330.0 - v["fair_y"] - v["bed_y"]  # the anchor's share of the weight
    assert abs((v["bed_y"] + anchor) / (w * laid) - 1) < 2e-3


def test_the_touchdown_sensor_converges_past_the_lift_off_by_its_tolerance():
    """Refined (60 elements of 5.5 m), the sensor lies where the catenary of radius a = H / w
    has risen its tolerance (a twentieth of the tube radius) off the bed: sqrt(2 a tol) (1.5 m)
    beyond the catenary's lift-off point, within a tenth of that."""
    v, w = _chain_on_the_seabed(60)
    beyond = math.sqrt(2.0 * v["fair_x"] / w * 0.05 * 0.108)
    assert 1.4 < beyond < 1.6
    assert abs(v["td_x"] - _catenary_touchdown(v, w) - beyond) < 0.1 * beyond


def _paid_out_in_water(t_end: float) -> dict:
    """A steel cable hanging in water from a winch that pays it out from 5 m to 15 m in 10 s
    (strain-rate damping settles the axial waves of the stop)."""
    cable = {
        "name": "cable",
        "geometry": {"kind": "line", "start": [0.0, 0.0], "end": [0.0, -5.0]},
        "mesh": {"elements": 10},
        "section": {"radius": 0.005},
        "material": {"density": 7850.0, "youngs_modulus": 2.0e11},
        "damping": {"axial": 2.0e4},
        "hydro": {"diameter": 0.01, "drag_normal": 1.2},
    }
    return {
        "bodies": [cable],
        "fluid": {"density": RHO_W},
        "supports": [{"at": "cable:start", "kind": "pin"}],
        "winches": [
            {
                "name": "drum",
                "at": "cable:start",
                "position": [0.0, 0.0],
                "length": {"table": [[0.0, 5.0], [10.0, 15.0]], "build_up": 2.0},
            }
        ],
        "loads": {"gravity": [0.0, -G]},
        "damping": {"mass_proportional": 0.5},
        "solver": {"t_end": t_end, "step": 0.01, "initial_state": "static"},
        "sensors": [
            {"name": "top", "kind": "reaction", "at": "cable:start"},
            {"name": "fluid", "kind": "fluid_force"},
        ],
    }


def test_a_line_paid_out_in_water_carries_its_submerged_weight_at_its_new_length():
    """Buoyancy (every fluid term) is per unstretched length: a line paid out from 5 to 15 m
    hangs with its submerged weight of 15 m, and the fluid force output is the buoyancy of
    15 m, not of the 5 m its arrays were built at."""
    import rancf
    from rancf.scenario import parse_scenario

    result, names, values = rancf.simulate(parse_scenario(_paid_out_in_water(22.0)))
    last = dict(zip(names, values[-1], strict=True))
    area = math.pi * 0.005**2
    submerged = (7850.0 - RHO_W) * G * area * 15.0
    buoyancy = RHO_W * G * area * 15.0
    assert abs(last["top_y"] / submerged - 1) < 1e-6, last
    assert abs(last["fluid_y"] / buoyancy - 1) < 1e-6, last


def test_a_driven_drum_holds_a_line_in_water_by_its_submerged_weight():
    """A driven drum on a line in water (scenario keys): the torque r w L0 with the line's
    weight in water w = (ρ − ρ_w) A g holds it at rest at its 5 m (statics: within 1e-4 m, its
    stretch), and it stays there over 0.5 s (the dry weight would balance 4.35 m), the pull at
    the drum (the ``winch`` sensor's tension) the torque over the radius (within 1e-5;
    measured 8e-7)."""
    import rancf
    from rancf.scenario import parse_scenario

    d = _paid_out_in_water(0.5)
    d["winches"][0].pop("length")
    area = math.pi * 0.005**2
    torque = 0.1 * (7850.0 - RHO_W) * area * G * 5.0
    d["winches"][0].update({"torque": torque, "radius": 0.1, "inertia": 0.01})
    d["sensors"].append({"name": "drum", "kind": "winch", "winch": "drum"})
    _, names, values = rancf.simulate(parse_scenario(d))
    length = values[:, names.index("drum_length")]
    assert np.abs(length - 5.0).max() < 1e-4, length
    pull = values[:, names.index("drum_tension")]
    assert np.abs(pull / (torque / 0.1) - 1.0).max() < 1e-5, pull


def test_the_default_hydro_diameter_is_one_formula_for_the_loads_and_the_wet_weight(
    monkeypatch,
):
    """Without ``diameter`` the line's is the volume-equivalent sqrt(4 A / pi); the fluid's
    line record and the statics' wet weight both take it from ``Hydro.line_diameter``."""
    from rancf.system.seabed import wet_weight

    area = math.pi * 0.01**2
    assert Hydro().line_diameter(area) == math.sqrt(4.0 * area / math.pi)
    assert Hydro(0.05).line_diameter(area) == 0.05
    g = [0.0, -G]

    def system() -> System:
        mesh, section = mesh_line([0, 0], [4, 0], 2), Section(area, 1e-8)
        cable = Model(mesh, "rancf", section, Material(2000.0, 1e9), [], gravity=g)
        return System({"cable": cable}, gravity=g, fluid=Fluid(RHO_W), hydro={"cable": Hydro()})

    plain = wet_weight(system(), "cable")[1]
    assert math.isclose(plain, -(2000.0 - RHO_W) * area * G, rel_tol=1e-12)
    monkeypatch.setattr(Hydro, "line_diameter", lambda self, a: 0.0)  # no buoyancy at all
    s = system()
    assert math.isclose(wet_weight(s, "cable")[1], -2000.0 * area * G, rel_tol=1e-12)
    assert s.model.lines[0].diameter == 0.0
