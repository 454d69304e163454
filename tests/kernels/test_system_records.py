"""The compiled core's System from one model record (rancf.kernels.records.SystemModel) and its
entry points from two records each (rancf.kernels.call_records): every field read by its name,
and a field of the wrong type, size or value refused in one line that names it."""

from __future__ import annotations

import dataclasses

import numpy as np
import pytest

from rancf.kernels import _core
from rancf.kernels.call_records import ResidualOptions, ResidualPoint, RunBuffers, RunOptions
from rancf.kernels.records import (
    JointRecord,
    LinearTerm,
    LoadRecord,
    PlaceRecord,
    PrescribedRecord,
    RigidRecord,
    SpringRecord,
    SystemModel,
    TimeFunctionRecord,
    WinchRecord,
)


def _parts() -> dict:
    """Two planar point masses (coordinates 0..3), a pin between them, a spring from the second
    to the ground, a load on the first, a ramp."""
    return {
        "rigid": [RigidRecord(2, True, 1.0), RigidRecord(2, True, 2.0)],
        "places": [
            PlaceRecord("mass", 0),
            PlaceRecord("mass", 1),
            PlaceRecord("ground", point=(1.0, 0.0, 0.0)),
        ],
        "joints": [JointRecord("pin", 0, 1)],
        "springs": [SpringRecord(1, 2, 10.0, 0.5, 0.0)],
        "loads": [LoadRecord(0, force=(0.0, -1.0, 0.0), factor=0)],
        "time_functions": [TimeFunctionRecord("ramp", (2.0,), duration=1.0)],
        "prescribed": [],
        "linear": [],
    }


def _system(gravity=(0.0, -9.81, 0.0), dim=2, **parts) -> _core.System:
    kw = _parts() | parts
    y_ref = np.array([1.0, 0.0, 1.0, 0.0])
    return _core.System(SystemModel(dim=dim, models=(), y_ref=y_ref, gravity=gravity, **kw))


def test_a_system_of_records():
    """The records give the sizes, and the load, spring and ramp act as their fields say:
    at t = 0.25 the ramp is 0.5 (load -0.5 on the first mass in y), the spring (k = 10,
    l0 = 0) pulls the second mass, 0.1 from the ground point, back by 1.0."""
    s = _system()
    assert (s.n, s.m, list(s.joint_rows)) == (4, 2, [0])
    y = np.array([1.0, 0.0, 1.1, 0.0])
    r = np.empty(6)
    s.residual(ResidualPoint(y, np.zeros(2), r), ResidualOptions(0.25, dynamic=False))
    weight = np.array([0.0, 9.81, 0.0, 2 * 9.81])
    assert r[:4] == pytest.approx(weight + [0.0, 0.5, 1.0, 0.0], abs=1e-12)
    assert r[4:] == pytest.approx([-0.1, 0.0], abs=1e-12)


def test_the_residual_takes_a_point_and_options_and_names_a_bad_field():
    """A dynamic residual reads the point's velocities and accelerations (at rest with zero
    accelerations it equals the static one); a missing or wrong field is one line naming it."""
    s = _system()
    y, lam = np.array([1.0, 0.0, 1.1, 0.0]), np.zeros(2)
    static, dynamic = np.empty(6), np.empty(6)
    s.residual(ResidualPoint(y, lam, static), ResidualOptions(0.25, dynamic=False))
    z = np.zeros(4)
    s.residual(ResidualPoint(y, lam, dynamic, z, z), ResidualOptions(0.25))
    np.testing.assert_array_equal(dynamic, static)
    a = np.array([0.0, 1.0, 0.0, 0.0])
    s.residual(ResidualPoint(y, lam, dynamic, z, a), ResidualOptions(0.25))
    assert dynamic[1] - static[1] == pytest.approx(1.0)  # the first mass (1 kg) times a
    with pytest.raises(TypeError, match=r"^point.v: expected an array of numbers, got None$"):
        s.residual(ResidualPoint(y, lam, dynamic), ResidualOptions(0.25))
    with pytest.raises(ValueError, match=r"^point.residual: expected 6 values, got 5$"):
        s.residual(ResidualPoint(y, lam, np.empty(5)), ResidualOptions(dynamic=False))
    with pytest.raises(ValueError, match=r"all three or none"):
        s.residual(ResidualPoint(y, lam, dynamic, z, z, contact_yf=y), ResidualOptions())


def _bad(name: str, i: int, **fields) -> dict:
    parts = _parts()
    parts[name] = list(parts[name])
    parts[name][i] = dataclasses.replace(parts[name][i], **fields)
    return parts


CASES = [
    (
        _bad("places", 0, kind="bar"),
        ValueError,
        "places[0].kind: expected one of ground, cable, rod, beam, rigid2d, rigid3d, mass, "
        "got 'bar'",
    ),
    (_bad("places", 1, body="x"), TypeError, "places[1].body: expected an integer, got 'x'"),
    (
        _bad("places", 1, body=2),
        ValueError,
        "places[1].body: expected a rigid body or point mass in [0, 2), got 2",
    ),
    (_bad("places", 2, point=(1.0, 0.0)), ValueError, "places[2].point: expected 3 numbers, got 2"),
    (
        _bad("places", 2, motion=4),
        ValueError,
        "places[2].motion: expected a time function in [0, 1) or -1, got 4",
    ),
    (
        _bad("joints", 0, kind="hinge"),
        ValueError,
        "joints[0].kind: expected one of pin, fixed, tangent, revolute, slider, sliding, "
        "got 'hinge'",
    ),
    (_bad("joints", 0, b=3), ValueError, "joints[0].b: expected a place in [0, 3), got 3"),
    (_bad("joints", 0, rel=(1.0,) * 4), ValueError, "joints[0].rel: expected 9 numbers, got 4"),
    (
        _bad("joints", 0, driven="yes"),
        TypeError,
        "joints[0].driven: expected True or False, got 'yes'",
    ),
    (
        _bad("joints", 0, driven=True),
        ValueError,
        "joints[0].angle: expected a time function in [0, 1), got -1",
    ),
    (
        _bad("springs", 0, stiffness="stiff"),
        TypeError,
        "springs[0].stiffness: expected a number, got 'stiff'",
    ),
    (
        _bad("springs", 0, damping=None),
        TypeError,
        "springs[0].damping: expected a number, got None",
    ),
    (
        _bad("loads", 0, factor=1),
        ValueError,
        "loads[0].factor: expected a time function in [0, 1) or -1, got 1",
    ),
    (
        _bad("loads", 0, force="down"),
        TypeError,
        "loads[0].force: expected a sequence of numbers, got 'down'",
    ),
    (
        _bad("time_functions", 0, kind="sine"),
        ValueError,
        "time_functions[0].kind: expected one of constant, piecewise, ramp, harmonic, spin_up, "
        "got 'sine'",
    ),
    (
        _bad("time_functions", 0, kind="piecewise", breaks=(0.0, 1.0), coef=(0.0,) * 3),
        ValueError,
        "time_functions[0].coef: expected 4 numbers (breaks - 1, 4, components), got 3",
    ),
    (_bad("rigid", 1, dim=3), ValueError, "rigid[1].dim: expected 2 (the system's), got 3"),
    (_bad("rigid", 0, mass=True), TypeError, "rigid[0].mass: expected a number, got True"),
    (
        _parts() | {"prescribed": [PrescribedRecord(9, 0, 0, 0.0)]},
        ValueError,
        "prescribed[0].coord: expected a coordinate in [0, 4), got 9",
    ),
    (
        _parts() | {"prescribed": [PrescribedRecord(1, 0, 1, 0.0)]},
        ValueError,
        "prescribed[0].comp: expected a component of its time function in [0, 1), got 1",
    ),
    (
        _parts() | {"linear": [LinearTerm(-1, 0, 1.0)]},
        ValueError,
        "linear[0].row: expected a row >= 0, got -1",
    ),
    (
        _parts() | {"linear": [LinearTerm(0, 4, 1.0)]},
        ValueError,
        "linear[0].col: expected a coordinate in [0, 4), got 4",
    ),
    (_parts() | {"springs": [object()]}, TypeError, "springs[0].a: missing"),
    (_parts() | {"loads": "loads"}, TypeError, "loads: expected a list of records, got 'loads'"),
]


@pytest.mark.parametrize(("parts", "error", "message"), CASES)
def test_a_bad_field_is_one_line_naming_it(parts, error, message):
    with pytest.raises(error) as info:
        _system(**parts)
    text = str(info.value)
    assert text.startswith(message)
    assert "\n" not in text


def test_bad_gravity_and_dimension_are_named():
    with pytest.raises(ValueError, match=r"^model.gravity: expected 3 numbers, got 2$"):
        _system(gravity=(0.0, -9.81))
    with pytest.raises(ValueError, match=r"^model.dim: expected 2 or 3, got 4$"):
        _system(dim=4)


def test_a_winch_on_no_flexible_body_is_named():
    band = np.zeros(3)
    winch = WinchRecord(body=0, length=0, length_set=1.0, c1=band, c2=band, d2=band)
    with pytest.raises(ValueError, match=r"^model.winches\[0\].body: expected a flexible body in "):
        _system(winches=(winch,))


def _run_buffers(n: int, m: int, dtype: type = float) -> RunBuffers:
    """The state at zero (y of ``dtype``) and room for one stored row."""
    y, v, a, w = np.zeros(n, dtype=dtype), np.zeros(n), np.zeros(n), np.zeros(n)
    return RunBuffers(y, v, a, w, np.zeros(m), np.zeros((1, n)), np.zeros((1, n)), np.zeros((1, m)))


def test_run_takes_buffers_and_options_and_writes_in_place():
    """One step of the pinned masses from rest: the state and the stored row are written into
    the buffers themselves; an integer array (a copy would be written) is refused by name."""
    s = _system()
    scheme = _core.Scheme(
        alpha_m=0.0,
        alpha_f=0.0,
        gamma=0.5,
        beta=0.25,
        damping=0.0,
        tol=1e-10,
        max_iter=20,
        modified=False,
    )
    integ = _core.SystemIntegrator(s, scheme)
    buffers = _run_buffers(s.n, s.m)
    steps, ok, _, stored, _, _ = integ.run(buffers, RunOptions(t0=0.0, h=1e-3, n_steps=1))
    assert (steps, ok, stored) == (1, True, 1)
    assert buffers.out_y[0] == pytest.approx(buffers.y, abs=0.0)
    assert np.any(buffers.y != np.zeros(s.n))
    with pytest.raises(TypeError, match=r"^buffers.y: expected a C-contiguous float64 array"):
        integ.run(_run_buffers(s.n, s.m, int), RunOptions(t0=0.0, h=1e-3, n_steps=1))
