"""MoorDyn 2.7 input files and runs shared by the mooring benchmarks (the peer side).

:func:`input_file` writes a MoorDyn v2 input file (line types, points, lines, options) and
:func:`run` steps it through MoorDyn's Python API (``moordyn.Create``/``Init``/``Step``) with the
coupled points driven by Python functions of time.  Within one coupling step MoorDyn moves a
coupled point as ``r + v (t - t0)`` (``Point::updateFairlead``), so the coupling step is kept
short (1e-2 s) and MoorDyn's own step ``dtM`` (or its CFL limit) is the integration step.
Needs ``pip install moordyn==2.7.*`` (a benchmark dependency, not one of rancf's).
"""

from __future__ import annotations

import os
import tempfile
import time
from collections.abc import Callable
from dataclasses import dataclass, field
from pathlib import Path

import moordyn


@dataclass
class LineType:
    """One row of MoorDyn's LINE TYPES table (BA < 0: a damping ratio, MoorDyn's convention)."""

    name: str
    diameter: float
    mass: float
    ea: float
    ba: float = -1.0
    ei: float = 0.0
    cd: float = 0.0
    ca: float = 0.0
    cd_ax: float = 0.0
    ca_ax: float = 0.0


@dataclass
class Point:
    """One row of MoorDyn's POINTS table: ``Fixed``, ``Coupled`` or ``Free``."""

    kind: str
    position: tuple[float, float, float]
    mass: float = 0.0
    volume: float = 0.0


@dataclass
class Case:
    """A MoorDyn model: one line type, points and one line between points ``a`` and ``b``."""

    line_type: LineType
    points: list[Point]
    length: float
    segments: int
    a: int = 1
    b: int = 2
    options: dict[str, float | str] = field(default_factory=dict)


def input_file(case: Case) -> str:
    """The text of the MoorDyn v2 input file of ``case``."""
    lt = case.line_type
    rows = [
        "--------------------- MoorDyn Input File ------------------------------------",
        "rancf benchmark peer model",
        "----------------------- LINE TYPES ------------------------------------------",
        "TypeName Diam Mass/m EA BA/-zeta EI Cd Ca CdAx CaAx",
        "(name) (m) (kg/m) (N) (N-s/-) (N-m^2) (-) (-) (-) (-)",
        f"{lt.name} {lt.diameter!r} {lt.mass!r} {lt.ea!r} {lt.ba!r} {lt.ei!r} {lt.cd!r} "
        f"{lt.ca!r} {lt.cd_ax!r} {lt.ca_ax!r}",
        "---------------------- POINTS --------------------------------",
        "ID Attachment X Y Z Mass Volume CdA Ca",
        "(#) (-) (m) (m) (m) (kg) (m^3) (m^2) (-)",
    ]
    for i, p in enumerate(case.points, 1):
        x, y, z = p.position
        rows.append(f"{i} {p.kind} {x!r} {y!r} {z!r} {p.mass!r} {p.volume!r} 0 0")
    rows += [
        "---------------------- LINES --------------------------------------",
        "ID LineType AttachA AttachB UnstrLen NumSegs LineOutputs",
        "(#) (name) (#) (#) (m) (-) (-)",
        f"1 {lt.name} {case.a} {case.b} {case.length!r} {case.segments} -",
        "---------------------- OPTIONS -----------------------------------------",
    ]
    rows += [f"{v if isinstance(v, str) else repr(v)} {k}" for k, v in case.options.items()]
    rows += [
        "------------------------- OUTPUTS --------------------------------",
        "END",
        "--------------------- need this line ------------------",
    ]
    return "\n".join(rows) + "\n"


@dataclass
class Run:
    """What :func:`run` measured: times, the recorded columns, MoorDyn's step and wall times."""

    times: list[float]
    columns: dict[str, list[float]]
    dt: float
    init_s: float
    solve_s: float


def run(
    case: Case,
    coupled: Callable[[float], tuple[list[float], list[float]]],
    record: Callable[[object, object, list[float]], dict[str, float]],
    t_end: float,
    coupling_step: float = 1e-2,
    before_step: Callable[[object, float], None] | None = None,
) -> Run:
    """Step ``case`` in MoorDyn to ``t_end``.

    ``coupled(t)`` gives the coupled points' positions and velocities (flat lists); ``record(
    system, line, forces)`` the values stored at every coupling time (``forces``: MoorDyn's
    forces on the coupled points); ``before_step(line, t)`` is called before each step (a
    variable length is set there).  MoorDyn's console output and files go to a temporary folder.
    """
    with tempfile.TemporaryDirectory() as tmp:
        path = Path(tmp) / "line.txt"
        path.write_text(input_file(case))
        cwd = os.getcwd()
        os.chdir(tmp)
        try:
            t0 = time.perf_counter()
            system = moordyn.Create(str(path))
            moordyn.SetVerbosity(system, 0)
            x, v = coupled(0.0)
            # at rest while MoorDyn finds its initial state: its solvers move a coupled point
            # with the velocity given here
            moordyn.Init(system, x, [0.0] * len(v))
            t1 = time.perf_counter()
            line = moordyn.GetLine(system, 1)
            forces = list(moordyn.Step(system, x, v, 0.0, 0.0)) if x else []
            times, columns = [0.0], {k: [val] for k, val in record(system, line, forces).items()}
            n = round(t_end / coupling_step)
            for i in range(n):
                t = i * coupling_step
                if before_step is not None:
                    before_step(line, t)
                x, v = coupled(t)
                forces = list(moordyn.Step(system, x, v, t, coupling_step))
                times.append((i + 1) * coupling_step)
                for k, val in record(system, line, forces).items():
                    columns[k].append(val)
            t2 = time.perf_counter()
            moordyn.Close(system)
        finally:
            os.chdir(cwd)
    return Run(times, columns, float(case.options.get("dtM", float("nan"))), t1 - t0, t2 - t1)
