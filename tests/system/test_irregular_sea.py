"""Irregular seas in the fluid kernel: the free surface's elevation as the ``wave_elevation``
sensor reads it (an hour of a JONSWAP sea holds Hs and Tp; a measured record is reproduced at
the origin; the seed fixes the sea), a line's fluid force in a sea against the sum of its
components' Airy kinematics, and bad ``[fluid] waves`` tables refused in one line."""

from __future__ import annotations

import copy
import math

import numpy as np
import pytest
from scipy.signal import welch

from rancf.bodies.flexible import Material, Model, Section
from rancf.errors import ScenarioError
from rancf.mesh.factories import mesh_line
from rancf.scenario.scenario import parse_scenario
from rancf.system import System
from rancf.system.fluid import Fluid, Hydro, JonswapWaves, RecordedWaves, Waves, surface_elevation

HS, TP, G = 6.0, 10.0, 9.80665
SEC, MAT = Section.circular(0.02), Material(3000.0, 1e7)


def _system(waves, surface: float = 0.0, mid=(0.0, 0.0, -5.0), length: float = 2.0) -> System:
    mid = np.asarray(mid, dtype=float)
    along = np.array([0.0, 1.0, 0.0])
    m = Model(
        mesh_line(mid - along * length / 2, mid + along * length / 2, 2),
        "rancf",
        SEC,
        MAT,
        [],
        gravity=[0.0, 0.0, -G],
    )
    fl = Fluid(1025.0, surface=surface, waves=waves)
    return System(
        {"line": m}, gravity=[0.0, 0.0, -G], fluid=fl, hydro={"line": Hydro(0.05, 1.1, 0, 0, 0)}
    )


def test_an_hour_of_the_kernels_sea_has_hs_and_tp():
    """One hour at 4 Hz of the sensor's elevation: std Hs / 4 within 3 %, spectral peak (Welch,
    2048 s segments) within 5 % of Tp."""
    s = _system(JonswapWaves(HS, TP, 3.3, depth=200.0, components=200, seed=7))
    t = np.arange(0.0, 3600.0, 0.25)
    eta = surface_elevation(s, (0.0, 0.0), t)
    assert eta.shape == t.shape
    assert np.std(eta) == pytest.approx(HS / 4.0, rel=3e-2)
    f, p = welch(eta, fs=4.0, nperseg=8192)
    assert 1.0 / f[np.argmax(p)] == pytest.approx(TP, rel=5e-2)


def test_the_elevation_is_the_sum_of_the_components():
    """Away from the origin, on a still surface at 1.5 m: 1.5 m plus eq. (1) of the components
    written out here (direction 30 deg)."""
    sea = JonswapWaves(HS, TP, depth=80.0, components=40, seed=5, direction_deg=30.0)
    s = _system(sea, surface=1.5)
    c = sea.wave_components(G)
    x = np.array([40.0, -25.0])
    e = np.array([math.cos(math.radians(30.0)), math.sin(math.radians(30.0))])
    t = np.linspace(0.0, 60.0, 121)
    want = 1.5 + sum(
        a * np.cos(w * t - k * (x @ e) + p)
        for a, w, k, p in zip(c.amplitude, c.omega, c.k, c.phase, strict=True)
    )
    got = surface_elevation(s, (*x, -3.0), t)
    assert np.abs(got - want).max() <= 1e-10 * HS


def test_a_measured_record_is_reproduced_at_the_origin(tmp_path):
    """A record of 1024 samples at 0.5 s given as ``elevation = "eta.csv"`` comes back at the
    origin at its times within 1e-3 Hs; between the samples it stays a sea of that size."""
    sea = JonswapWaves(HS, TP, depth=100.0, components=80, seed=11)
    t = 3.0 + 0.5 * np.arange(1024)
    eta = sea.wave_components(G).elevation(t)
    (tmp_path / "eta.csv").write_text(
        "t,eta\n" + "".join(f"{float(a)!r},{float(b)!r}\n" for a, b in zip(t, eta, strict=True))
    )
    d = _scenario({"elevation": "eta.csv", "depth": 100.0}, t_end=0.1)
    (tmp_path / "sea.toml").write_text("")
    sc = parse_scenario(d, path=str(tmp_path / "sea.toml"))
    s = sc.build_system()
    assert isinstance(s.fluid.waves, RecordedWaves)
    got = surface_elevation(s, (0.0, 0.0, 0.0), t)
    assert np.abs(got - eta).max() <= 1e-3 * HS
    mid = surface_elevation(s, (0.0, 0.0, 0.0), t[:-1] + 0.25)
    assert 0.8 * np.std(eta) <= np.std(mid) <= 1.2 * np.std(eta)


def test_a_line_in_a_sea_feels_the_sum_of_the_components_kinematics():
    """A short line across the waves at depth: its fluid force is the Morison drag and
    Froude-Krylov force of the components' Airy velocities and accelerations summed here, plus
    buoyancy; 1e-9 relative.  A regular wave is the sea of one component."""
    h, z0, x0, t = 30.0, -4.0, 3.0, 1.3
    sea = JonswapWaves(2.0, 7.0, depth=h, components=12, seed=4, direction_deg=25.0)
    c = sea.wave_components(G)
    e = np.array([math.cos(math.radians(25.0)), math.sin(math.radians(25.0)), 0.0])
    mid = np.array([x0, 0.0, z0])
    s = _system(sea, mid=mid, length=1e-3)
    z = np.zeros(s.n)
    f = np.asarray(s.core.fluid_forces(s.y0, z, z, t))
    u, du = np.zeros(3), np.zeros(3)
    for a, w, k, p in zip(c.amplitude, c.omega, c.k, c.phase, strict=True):
        th = k * (mid @ e) - w * t - p
        ch, sh = np.cosh(k * (z0 + h)) / np.sinh(k * h), np.sinh(k * (z0 + h)) / np.sinh(k * h)
        u += a * w * (ch * np.cos(th) * e + sh * np.sin(th) * np.array([0, 0, 1.0]))
        du += a * w * w * (ch * np.sin(th) * e - sh * np.cos(th) * np.array([0, 0, 1.0]))
    rho, d = 1025.0, 0.05
    area = np.pi * d**2 / 4
    # the line lies along y, the waves travel at 25 deg: drag on the normal part of u
    un = u - u[1] * np.array([0.0, 1.0, 0.0])
    want = 1e-3 * (
        0.5 * rho * d * 1.1 * np.linalg.norm(un) * un
        + rho * area * du
        + rho * area * G * np.array([0.0, 0.0, 1.0])
    )
    assert np.allclose(f, want, rtol=1e-9, atol=1e-12 * np.abs(want).max())
    # a regular wave and the same wave as a one-component record of its own
    reg = Waves(2.0, 7.0, 25.0, depth=h)
    one = reg.wave_components(G)
    assert one.amplitude.tolist() == [1.0] and one.phase.tolist() == [0.0]


def test_the_same_seed_gives_the_same_sea():
    t = np.arange(0.0, 200.0, 0.5)
    a = surface_elevation(_system(JonswapWaves(HS, TP, depth=100.0, seed=3)), (5.0, 2.0), t)
    b = surface_elevation(_system(JonswapWaves(HS, TP, depth=100.0, seed=3)), (5.0, 2.0), t)
    c = surface_elevation(_system(JonswapWaves(HS, TP, depth=100.0, seed=4)), (5.0, 2.0), t)
    np.testing.assert_array_equal(a, b)
    assert np.abs(a - c).max() > 0.5


def _scenario(waves: dict, t_end: float = 1.0, seed_sensors: bool = True) -> dict:
    return {
        "geometry": {"kind": "line", "start": [0.0, 0.0, -20.0], "end": [10.0, 0.0, -5.0]},
        "mesh": {"elements": 4},
        "section": {"radius": 0.02},
        "material": {"density": 3000.0, "youngs_modulus": 1e9},
        "supports": [{"at": "start"}, {"at": "end"}],
        "loads": {"gravity": [0.0, 0.0, -G]},
        "fluid": {"density": 1025.0, "surface": 0.0, "waves": waves},
        "hydro": {"diameter": 0.05, "drag_normal": 1.2},
        "solver": {"t_end": t_end, "step": 0.025, "initial_state": "static"},
        "sensors": [
            {"name": "fluid", "kind": "fluid_force"},
            {"name": "eta", "kind": "wave_elevation", "at_point": [5.0, 0.0, 0.0]},
        ],
    }


def test_a_short_run_in_a_sea_has_a_finite_fluid_force_that_changes_with_the_seed():
    import rancf

    out = {}
    for seed in (1, 2):
        w = {"spectrum": "jonswap", "hs": 3.0, "tp": 8.0, "depth": 50.0}
        w.update(components=30, seed=seed, direction_deg=20.0)
        _, names, values = rancf.simulate(parse_scenario(_scenario(w, t_end=1.0)))
        out[seed] = np.asarray(values)
        assert np.all(np.isfinite(out[seed]))
    cols = [i for i, n in enumerate(names) if n.startswith("fluid_")]
    f1, f2 = out[1][:, cols], out[2][:, cols]
    assert np.abs(f1 - f2).max() > 1e-3 * np.abs(f1).max()
    eta = out[1][:, names.index("eta")]
    assert np.ptp(eta) > 0.0


@pytest.mark.parametrize(
    ("waves", "words"),
    [
        ({"spectrum": "jonswap", "hs": 3.0, "tp": 8.0}, "depth"),
        ({"spectrum": "pm", "hs": 3.0, "tp": 8.0, "depth": 50.0}, "spectrum"),
        ({"spectrum": "jonswap", "hs": 3.0, "tp": 8.0, "depth": 50.0, "gamma": 9.0}, "gamma"),
        ({"spectrum": "jonswap", "hs": 3.0, "tp": 8.0, "depth": 50.0, "components": 0}, "comp"),
        ({"spectrum": "jonswap", "elevation": [[0, 0]] * 4, "depth": 50.0}, "waves"),
        ({"elevation": [[0.0, 0.1], [1.0, 0.2], [2.5, 0.0], [3.0, 0.1]], "depth": 9.0}, "equal"),
        ({"elevation": [[0.0, 0.1], [1.0, 0.2]], "depth": 9.0}, "4 rows"),
        ({"elevation": "missing.csv", "depth": 9.0}, "does not exist"),
    ],
)
def test_bad_wave_tables_are_refused_in_one_line(waves, words):
    with pytest.raises(ScenarioError) as err:
        parse_scenario(copy.deepcopy(_scenario(waves))).build_system()
    msg = str(err.value)
    assert "\n" not in msg and "fluid.waves" in msg and words in msg, msg
