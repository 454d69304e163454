"""The axial force of a line whose stress-free reference is far more curved than its shape
(rancf.bodies.nodal_forces, docs/derivations/cable.md section 7).

A chain of 288 kg/m and EA = 1.23e9 N hangs between pins at (-300, -100) and (0, 0); its
reference is an elliptic arc of 330 m, horizontal at the anchor and vertical at the fairlead,
so the elements near the fairlead straighten from a reference turning up to 0.6 rad each.  The
pointwise strain oscillates there by more than the tension (EA / T > 1000): the sensor read
248 kN for a fairlead force of 775 kN in the 3D mooring chain.  Read from the nodal forces:

* at each end, the axial force is the support's reaction along the line's tangent (the
  identity, to round-off);
* at the fairlead the ``tension`` sensor is the size of the reaction, as it is for a line whose
  bending stiffness is negligible (here sqrt(EI / T) < 0.1 m): within 2 % with 20 elements and
  0.1 % with 40 (the rest is the end tangent, which the elements next to the strongly curved
  reference end carry less accurately than the force);
* along the line the horizontal component ``N t_x`` of the axial force is the anchor's
  horizontal reaction (the loads are vertical) within 1e-3 over the first 3/4 of its length.
"""

from __future__ import annotations

import contextlib
import io

import numpy as np
import pytest

from rancf.cli import main
from tests.numbers import csv_columns

CHAIN = """
[geometry]
kind = "conic"
start = [-300.0, -100.0]
end = [0.0, 0.0]
angles_deg = [18.43494882292201, 71.56505117707799]
point = [-96.55665347288583, -67.81444884237139]
[mesh]
elements = {n}
[section]
area = 0.03668789808917197
inertia = 1.0e-7
[material]
density = 7850.0
youngs_modulus = 33596909722.222225
[[supports]]
at = "start"
kind = "pin"
[[supports]]
at = "end"
kind = "pin"
[loads]
gravity = [0.0, -9.81]
[[sensors]]
name = "fairlead"
kind = "tension"
at = "end"
[[sensors]]
name = "anchor"
kind = "tension"
at = "start"
"""


@pytest.mark.parametrize(("n", "size_tol"), [(20, 2e-2), (40, 1e-3)])
def test_tension_of_a_straightened_curved_chain(tmp_path, n, size_tol):
    (tmp_path / "c.toml").write_text(CHAIN.format(n=n))
    with contextlib.redirect_stdout(io.StringIO()):
        assert main(["static", str(tmp_path / "c.toml"), "--out", str(tmp_path / "r")]) == 0
    run = tmp_path / "r"
    sensors, reactions = csv_columns(run / "sensors.csv"), csv_columns(run / "reactions.csv")
    (body,) = (run / "bodies").iterdir()  # the one body's section values
    along = csv_columns(body / "along.csv")
    q = np.load(run / "results.npz")["q"][-1].reshape(n + 1, 4)
    tangent = q[:, 2:] / np.linalg.norm(q[:, 2:], axis=1, keepdims=True)
    end = np.array([reactions["end_fx"][-1], reactions["end_fy"][-1]])
    start = np.array([reactions["start_fx"][-1], reactions["start_fy"][-1]])
    per = (along["s"].size - 1) // n
    nodal = along["axial_force"][::per]
    assert nodal.size == n + 1
    # the ends: the reaction along the tangent (outward at the end, inward at the start)
    assert abs(nodal[-1] / (end @ tangent[-1]) - 1) < 1e-9
    assert abs(nodal[0] / -(start @ tangent[0]) - 1) < 1e-9
    assert sensors["fairlead"][-1] == nodal[-1] and sensors["anchor"][-1] == nodal[0]
    # the size of the reaction (negligible bending stiffness)
    assert abs(sensors["fairlead"][-1] / np.linalg.norm(end) - 1) < size_tol
    assert abs(sensors["anchor"][-1] / np.linalg.norm(start) - 1) < 1e-4
    # the horizontal force along the first 3/4 of the line
    h = nodal * tangent[:, 0]
    inner = slice(0, 3 * n // 4 + 1)
    assert np.abs(h[inner] / -start[0] - 1).max() < 1e-3


HANGING = """
[geometry]
kind = "line"
start = [0.0, 0.0]
end = [0.0, -10.0]
[mesh]
elements = 5
[section]
radius = 0.01
[material]
density = 7850.0
youngs_modulus = 2.0e11
[[supports]]
at = "start"
kind = "pin"
[loads]
gravity = [0.0, -9.81]
[[sensors]]
name = "tip"
kind = "tension"
at = "end"
"""


def test_tension_of_a_hanging_cable_is_the_weight_below(tmp_path):
    """A straight cable hanging from a pin: N(s) = w (L - s) at every node (the two elements'
    shares of the uniform weight cancel in the average) and zero at the free end."""
    (tmp_path / "h.toml").write_text(HANGING)
    with contextlib.redirect_stdout(io.StringIO()):
        assert main(["static", str(tmp_path / "h.toml"), "--out", str(tmp_path / "r")]) == 0
    (body,) = (tmp_path / "r" / "bodies").iterdir()
    along = csv_columns(body / "along.csv")
    nodal, s = along["axial_force"][::4], along["s"][::4]
    w = 7850.0 * np.pi * 0.01**2 * 9.81
    assert abs(nodal[0] / (w * 10.0) - 1) < 1e-9
    np.testing.assert_allclose(nodal, w * (10.0 - s), rtol=0, atol=1e-9 * w * 10.0)
    assert csv_columns(tmp_path / "r" / "sensors.csv")["tip"][-1] == nodal[-1]


def test_tension_at_a_moving_end_is_the_reaction_along_the_tangent(tmp_path):
    """In a run the end's axial force is its support's reaction (inertia included) along the
    tangent at every output, here with the fairlead surging 1 m at 0.5 Hz."""
    text = CHAIN.format(n=10).replace(
        'at = "end"\nkind = "pin"\n',
        'at = "end"\nkind = "pin"\nmotion = { harmonic = 0.5, amplitude = [1.0, 0.0], '
        "build_up = 0.0 }\n",
    )
    text += '[solver]\ninitial_state = "static"\nt_end = 0.2\nstep = 0.02\n'
    (tmp_path / "d.toml").write_text(text)
    with contextlib.redirect_stdout(io.StringIO()):
        assert main(["simulate", str(tmp_path / "d.toml"), "--out", str(tmp_path / "r")]) == 0
    run = tmp_path / "r"
    sensors, reactions = csv_columns(run / "sensors.csv"), csv_columns(run / "reactions.csv")
    q = np.load(run / "results.npz")["q"].reshape(len(sensors["t"]), 11, 4)
    tangent = q[:, -1, 2:] / np.linalg.norm(q[:, -1, 2:], axis=1, keepdims=True)
    end = np.column_stack([reactions["end_fx"], reactions["end_fy"]])
    along = np.einsum("ij,ij->i", end, tangent)
    assert np.ptp(along) > 1e3  # the surge changes the tension
    np.testing.assert_allclose(sensors["fairlead"], along, rtol=1e-9, atol=0)
