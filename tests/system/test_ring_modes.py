"""Free rings: the natural frequencies of a free circular ring against the thin-ring
formulas, with exactly 3 (planar) or 6 (spatial) rigid-body modes removed, from the Python API and
from ``rancf modes`` on a closed scenario.

Ring: radius R = 1 m, circular section of radius 0.01 m, E = 2e11 Pa, ρ = 7850 kg/m³,
ν = 0.3 (G = E / 2.6, J = 2I).  Inextensible thin ring (Love; Blevins, Formulas for natural
frequency and mode shape, table 12-1):

* in-plane flexure:      ω_n² = (EI / ρA R⁴) n² (n² - 1)² / (n² + 1)
* out-of-plane flexure:  ω_n² = (EI / ρA R⁴) n² (n² - 1)² / (n² + EI / GJ)

Each frequency is a double one (the mode and the mode turned by a quarter wave).
"""

from __future__ import annotations

import json
import subprocess
import sys

import numpy as np
import pytest

from rancf.bodies.flexible import Material, Model, Section
from rancf.geometry.ellipse import Ellipse, ellipse_axes
from rancf.mesh.ellipse_mesh import mesh_ellipse
from rancf.solvers.modal import natural_modes

E, RHO, NU, R, RS = 2e11, 7850.0, 0.3, 1.0, 0.01
AREA, INERTIA = np.pi * RS**2, np.pi * RS**4 / 4
EI_GJ = E / (E / (2 * (1 + NU)) * 2)  # EI / GJ with J = 2 I: 1 + ν
N = np.array([2, 3, 4])
SCALE = E * INERTIA / (RHO * AREA * R**4)
IN_PLANE = np.sqrt(SCALE * N**2 * (N**2 - 1) ** 2 / (N**2 + 1)) / (2 * np.pi)
OUT_OF_PLANE = np.sqrt(SCALE * N**2 * (N**2 - 1) ** 2 / (N**2 + EI_GJ)) / (2 * np.pi)
TOL = 3e-3  # 0.3 % of the thin-ring closed forms (which neglect shear and rotary inertia)


def _ring(element: str, n: int = 48) -> Model:
    dim = 3 if element == "rod" else 2
    mesh = mesh_ellipse(Ellipse(np.zeros(dim), R, R, *ellipse_axes(dim)), n, start_deg=37.0)
    return Model(mesh, element, Section.circular(RS), Material(RHO, E, poisson_ratio=NU))


def test_planar_cable_ring_in_plane_frequencies():
    res = natural_modes(_ring("rancf"), count=6)
    assert res.n_rigid == 3
    f = res.frequencies_hz
    assert np.allclose(f[0::2], f[1::2], rtol=1e-8)  # double frequencies
    assert np.abs(f[0::2] / IN_PLANE - 1).max() < TOL
    # above the inextensible values by a mesh error that a finer mesh shrinks
    fine = natural_modes(_ring("rancf", 96), count=6).frequencies_hz[0::2]
    assert np.all(np.abs(fine / IN_PLANE - 1) < np.abs(f[0::2] / IN_PLANE - 1))


def test_rod_ring_in_and_out_of_plane_frequencies():
    mod = _ring("rod")
    res = natural_modes(mod, count=12)
    assert res.n_rigid == 6
    shapes = res.modes.reshape(res.frequencies_hz.size, mod.n_nodes, mod.dpn)
    out = np.abs(shapes[:, :, 2]).max(axis=1) > np.abs(shapes[:, :, :2]).max(axis=(1, 2))
    f_out, f_in = res.frequencies_hz[out], res.frequencies_hz[~out]
    assert f_out.size == f_in.size == 6
    assert np.abs(f_out[0::2] / OUT_OF_PLANE - 1).max() < TOL
    assert np.abs(f_in[0::2] / IN_PLANE - 1).max() < TOL
    assert np.allclose(f_out[0::2], f_out[1::2], rtol=1e-8)


RING = """
[geometry]
kind = "ellipse"
center = {center}
semi_axes = [1.0, 1.0]
start_deg = 90.0

[mesh]
elements = 48
element = "{element}"

[section]
radius = 0.01

[material]
density = 7850.0
youngs_modulus = 2.0e11
{extra}
[modes]
count = {count}
"""


@pytest.mark.parametrize(
    ("element", "center", "count", "rigid"),
    [("rancf", "[0.0, 0.0]", 6, 3), ("rod", "[0.0, 0.0, 0.0]", 12, 6)],
)
def test_rancf_modes_on_a_closed_scenario(tmp_path, element, center, count, rigid):
    """`rancf modes` of a closed scenario gives a ring's frequencies, not an open arc's."""
    f = tmp_path / "ring.toml"
    f.write_text(
        RING.format(
            center=center,
            element=element,
            count=count,
            extra="poisson_ratio = 0.3\n" if element == "rod" else "",
        )
    )
    p = subprocess.run(
        [sys.executable, "-m", "rancf", "modes", str(f), "--json"], capture_output=True, text=True
    )
    assert p.returncode == 0, p.stderr
    doc = json.loads(p.stdout)
    assert doc["rigid_body_modes_removed"] == rigid
    got = np.array(doc["frequencies_hz"])
    want = np.sort(np.r_[IN_PLANE, OUT_OF_PLANE]) if element == "rod" else IN_PLANE
    assert np.abs(got[0::2] / want[: got.size // 2] - 1).max() < TOL
