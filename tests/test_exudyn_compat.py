"""Exudyn under its current names (no DeprecationWarning) and under the names before 1.12.258.

The installed Exudyn (extra ``bench``) runs the comparison column with warnings as errors; the
older names are checked on stand-ins for Exudyn's modules, so they run without Exudyn too.
"""

import subprocess
import sys
import types

import pytest

from rancf import exudyn_compat

CHECK = """
import numpy as np
import exudyn as exu
from rancf.exudyn_compat import cable2d, dynamic_settings, straight_cable2d
from rancf.studies import exudyn_cable

nodes = [[[0.0, 0.0], [1.0, 0.0]], [[0.1, -0.02], [0.98, -0.2]], [[0.2, -0.08], [0.9, -0.44]]]
solver = dict(t_end=0.02, step=1e-3, rho_inf=0.9, output_step=0.01)
t, tip = exudyn_cable.curved_pendulum_tip(nodes, [0.102, 0.104], solver, 1e-4, 1e-9, 2e3, 2e8)
assert t.shape == (3,) and tip.shape == (3, 2) and np.all(np.isfinite(tip)), (t, tip)

sc = exu.SystemContainer()
mbs = sc.AddSystem()
cable = cable2d(massPerLength=0.2, bendingStiffness=1e-2, axialStiffness=1e4)
ids = straight_cable2d(mbs, [0, 0, 0], [1, 0, 0], 3, cable, [0, -9.81, 0], [1, 1, 0, 0])
mbs.Assemble()
ss = dynamic_settings(0.01, 1e-3, 0.9, sparse=True)
mbs.SolveDynamic(ss)
assert len(ids) == 4 and mbs.GetNodeOutput(ids[-1], exu.OutputVariableType.Position)[1] < 0
print("ok")
"""


def test_exudyn_runs_without_deprecation_warnings():
    """In a fresh process: Exudyn warns about an old name once per process only."""
    pytest.importorskip("exudyn")
    p = subprocess.run(
        [sys.executable, "-W", "error::DeprecationWarning", "-c", CHECK],
        capture_output=True,
        text=True,
        timeout=300,
    )
    assert p.returncode == 0 and p.stdout.strip() == "ok", p.stderr[-3000:]


def _fake_exudyn(monkeypatch, item_interface, beams, settings):
    exu = types.ModuleType("exudyn")
    exu.SimulationSettings = settings
    exu.LinearSolverType = types.SimpleNamespace(EigenSparse="EigenSparse")
    exu.itemInterface, exu.beams = item_interface, beams
    monkeypatch.setitem(sys.modules, "exudyn", exu)
    monkeypatch.setitem(sys.modules, "exudyn.itemInterface", item_interface)
    monkeypatch.setitem(sys.modules, "exudyn.beams", beams)


def _module(name, **attrs):
    m = types.ModuleType(name)
    m.__dict__.update(attrs)
    return m


def _ns(**kw):
    return types.SimpleNamespace(**kw)


class OldCable2D:
    """Exudyn before 1.12.258: ``physics*`` parameters, anything else is an error."""

    def __init__(self, physicsLength=0.0, physicsMassPerLength=0.0, nodeNumbers=None):
        self.kw = dict(physicsLength=physicsLength, physicsMassPerLength=physicsMassPerLength)


class NewCable2D:
    def __init__(self, length=0.0, massPerLength=0.0, nodeNumbers=None):
        self.kw = dict(length=length, massPerLength=massPerLength)


def old_settings():
    return _ns(
        solutionSettings=_ns(writeSolutionToFile=True, sensorsWritePeriod=0.01),
        displayComputationTime=True,
        displayStatistics=True,
        linearSolverType="EXUdense",
        timeIntegration=_ns(generalizedAlpha=_ns()),
    )


def new_settings():
    return _ns(
        solution=_ns(file=_ns(write=True), sensors=_ns(writePeriod=0.01)),
        show=_ns(computationTime=True, statistics=True),
        linearSolver=_ns(solverType="EXUdense"),
        timeIntegration=_ns(generalizedAlpha=_ns()),
    )


@pytest.mark.parametrize("old", [True, False])
def test_names_follow_the_installed_exudyn(monkeypatch, old):
    calls = []

    def along_line(mbs, start, end, n, template, **kw):
        calls.append(("along_line", kw))
        return {"nodes": [0, 1]}

    def straight_line(mbs, start, end, n, template, **kw):
        calls.append(("straight_line", kw))
        return [[0, 1], [], [], [], []]

    beams = _module("exudyn.beams", GenerateStraightLineANCFCable2D=straight_line)
    if not old:
        beams.GenerateBeamElementsAlongLine = along_line
    items = _module("exudyn.itemInterface", Cable2D=OldCable2D if old else NewCable2D)
    _fake_exudyn(monkeypatch, items, beams, old_settings if old else new_settings)

    cable = exudyn_compat.cable2d(length=0.5, massPerLength=2.0, nodeNumbers=[0, 1])
    if old:
        assert cable.kw == {"physicsLength": 0.5, "physicsMassPerLength": 2.0}
    else:
        assert cable.kw == {"length": 0.5, "massPerLength": 2.0}

    ss = exudyn_compat.dynamic_settings(1.0, 0.1, 0.8, sparse=True, sensors_write_period=0.05)
    assert ss.timeIntegration.numberOfSteps == 10 and ss.timeIntegration.endTime == 1.0
    assert ss.timeIntegration.generalizedAlpha.spectralRadius == 0.8
    if old:
        assert ss.solutionSettings.writeSolutionToFile is False
        assert ss.solutionSettings.sensorsWritePeriod == 0.05
        assert ss.displayComputationTime is False and ss.displayStatistics is False
        assert ss.linearSolverType == "EigenSparse"
    else:
        assert ss.solution.file.write is False and ss.solution.sensors.writePeriod == 0.05
        assert ss.show.computationTime is False and ss.show.statistics is False
        assert ss.linearSolver.solverType == "EigenSparse"

    fixed = [1, 1, 0, 0]
    nodes = exudyn_compat.straight_cable2d(None, [0, 0, 0], [1, 0, 0], 1, cable, [0, -1, 0], fixed)
    assert nodes == [0, 1]
    name, kw = calls[0]
    if old:
        assert name == "straight_line"
        assert kw["massProportionalLoad"] == [0, -1, 0] and kw["fixedConstraintsNode0"] == fixed
    else:
        assert name == "along_line"
        assert kw["gravity"] == [0, -1, 0] and kw["groundConstraintsStart"] == fixed


def test_a_setting_missing_under_both_names_is_an_error():
    with pytest.raises(AttributeError, match="neither show.statistics nor displayStatistics"):
        exudyn_compat._assign(_ns(), "show.statistics", "displayStatistics", False)


class OldMassPoint2D:
    def __init__(self, nodeNumber=None, physicsMass=0.0):
        self.kw = dict(nodeNumber=nodeNumber, physicsMass=physicsMass)


class NewMassPoint2D:
    def __init__(self, nodeNumber=None, mass=0.0, physicsMass=None):
        self.kw = dict(nodeNumber=nodeNumber, mass=mass, physicsMass=physicsMass)


@pytest.mark.parametrize("old", [True, False])
def test_any_item_under_its_current_names(monkeypatch, old):
    """``item`` passes ``mass`` as ``physicsMass`` only where the item has no ``mass``."""
    items = _module("exudyn.itemInterface", MassPoint2D=OldMassPoint2D if old else NewMassPoint2D)
    _fake_exudyn(monkeypatch, items, _module("exudyn.beams"), new_settings)
    point = exudyn_compat.item("MassPoint2D", nodeNumber=3, mass=0.5)
    if old:
        assert point.kw == {"nodeNumber": 3, "physicsMass": 0.5}
    else:
        assert point.kw == {"nodeNumber": 3, "mass": 0.5, "physicsMass": None}
