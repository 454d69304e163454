"""A corpus of bad inputs through the command line.

Every case must end with the expected exit status, exactly one line on standard error that names
the key, option or path, no traceback, and nothing left behind in the working directory.  Cases
run in-process through :func:`rancf.cli.main` (the same code path as the console script); a few
run as real processes in ``test_cli_signals.py``.
"""

from __future__ import annotations

import os
import tomllib
from pathlib import Path

import pytest

from rancf.cli import main
from tests.scenario.test_scenario import BASE

CONIC = ["conic", "--chord", "0.5", "--angles", "30", "40", "--point", "0.315", "0.077"]


def _toml(value) -> str:
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, str):
        return f'"{value}"'
    if isinstance(value, float):
        return repr(value).replace("inf", "inf").replace("nan", "nan")
    if isinstance(value, list):
        return "[" + ", ".join(_toml(v) for v in value) + "]"
    return str(value)


def dump(d: dict) -> str:
    """Minimal TOML writer for the scenario dictionaries of these tests."""
    lines = []
    for table, body in d.items():
        if isinstance(body, list):
            for item in body:
                lines.append(f"[[{table}]]")
                lines += [f"{k} = {_toml(v)}" for k, v in item.items()]
            continue
        lines.append(f"[{table}]")
        nested = {
            k: v for k, v in body.items() if isinstance(v, list) and v and isinstance(v[0], dict)
        }
        lines += [f"{k} = {_toml(v)}" for k, v in body.items() if k not in nested]
        for k, items in nested.items():
            for item in items:
                lines.append(f"[[{table}.{k}]]")
                lines += [f"{kk} = {_toml(vv)}" for kk, vv in item.items()]
    return "\n".join(lines) + "\n"


def mutated(**changes) -> str:
    """BASE with ``table__key=value`` changes (``None`` deletes; ``table=...`` replaces)."""
    return _mutated(BASE, changes)


def rod(**changes) -> str:
    """ROD (a clamped spatial rod arc) with changes, as :func:`mutated`."""
    return _mutated(ROD, changes)


def _mutated(text: str, changes: dict) -> str:
    d = tomllib.loads(text)
    for key, value in changes.items():
        if "__" in key:
            table, sub = key.split("__")
            if value is None:
                d[table].pop(sub)
            else:
                d.setdefault(table, {})[sub] = value
        elif value is None:
            d.pop(key)
        else:
            d[key] = value
    return dump(d)


NURBS = {
    "kind": "nurbs",
    "degree": 2,
    "knots": [0.0, 0.0, 0.0, 1.0, 1.0, 1.0],
    "control_points": [[0.0, 0.0], [0.25, 0.2], [0.5, 0.0]],
}
LINE = {"kind": "line", "start": [0.0, 0.0], "end": [0.5, 0.0]}
ROD = """
[geometry]
kind = "conic"
start = [0.0, 0.0, 0.0]
end = [0.5, 0.0, 0.0]
angles_deg = [30.0, 30.0]
point = [0.25, 0.067, 0.0]
[mesh]
elements = 3
element = "rod"
[section]
radius = 0.03
[material]
density = 6000.0
youngs_modulus = 2.0e7
poisson_ratio = 0.3
[[supports]]
at = "start"
kind = "clamp"
[solver]
t_end = 0.02
step = 1.0e-3
"""


def _without(d: dict, key: str) -> dict:
    return {k: v for k, v in d.items() if k != key}


PRINCIPAL = {"area": 1e-3, "inertia_y": 1e-7, "inertia_z": 2e-7, "orientation": [0.0, 0.0, 1.0]}


def nurbs(**g) -> str:
    return mutated(geometry={**NURBS, **g})


# (id, scenario text, exit status, text that must appear in the one error line)
SCENARIOS = [
    ("unknown-table", mutated(solvr={}), 2, "solvr"),
    ("unknown-key-mesh", mutated(mesh__elemnts=3), 2, "mesh.elemnts"),
    ("unknown-key-geometry", mutated(geometry__pont=[0.3, 0.07]), 2, "geometry.pont"),
    ("unknown-key-solver", mutated(solver__tend=1.0), 2, "solver.tend"),
    ("missing-geometry", mutated(geometry=None), 2, "geometry"),
    ("missing-material", mutated(material=None), 2, "material"),
    ("missing-density", mutated(material__density=None), 2, "material.density"),
    ("missing-elements", mutated(mesh__elements=None), 2, "mesh.elements"),
    ("missing-kind", mutated(geometry__kind=None), 2, "geometry.kind"),
    ("missing-point", mutated(geometry__point=None), 2, "geometry.point"),
    ("bad-kind", mutated(geometry__kind="spline"), 2, "geometry.kind"),
    ("elements-string", mutated(mesh__elements="five"), 2, "mesh.elements"),
    ("elements-zero", mutated(mesh__elements=0), 2, "mesh.elements"),
    ("elements-float", mutated(mesh__elements=2.5), 2, "mesh.elements"),
    ("elements-huge", mutated(mesh__elements=9223372036854775807), 2, "mesh.elements"),
    ("elements-too-many", mutated(mesh__elements=2_000_000), 2, "mesh.elements"),
    ("element-kind", mutated(mesh__element="shell"), 2, "mesh.element"),
    ("k-above-one", mutated(mesh__k=1.5), 2, "mesh.k"),
    ("k-tiny", mutated(mesh__k=1e-9), 2, "mesh.k"),
    ("k-string", mutated(mesh__k="best"), 2, "mesh.k"),
    ("k-nan", mutated(mesh__k=float("nan")), 2, "mesh.k"),
    ("spacing", mutated(mesh__spacing="log"), 2, "mesh.spacing"),
    ("quadrature-1", mutated(mesh__quadrature_points=1), 2, "mesh.quadrature_points"),
    ("quadrature-1000", mutated(mesh__quadrature_points=1000), 2, "mesh.quadrature_points"),
    (
        "beam-3d",
        mutated(
            mesh__element="beam",
            geometry={**LINE, "end": [0.5, 0, 0], "start": [0.0, 0, 0]},
            loads={"gravity": [0, 0, -9.81]},
        ),
        2,
        "mesh.element",
    ),
    ("radius-zero", mutated(section__radius=0.0), 2, "section.radius"),
    ("radius-negative", mutated(section__radius=-0.02), 2, "section.radius"),
    ("radius-inf", mutated(section__radius=float("inf")), 2, "section.radius"),
    ("section-both", mutated(section__area=1e-3), 2, "section"),
    ("section-area-only", mutated(section={"area": 1e-3}), 2, "section"),
    ("density-negative", mutated(material__density=-1.0), 2, "material.density"),
    ("density-bool", mutated(material__density=True), 2, "material.density"),
    ("youngs-zero", mutated(material__youngs_modulus=0.0), 2, "material.youngs_modulus"),
    ("youngs-nan", mutated(material__youngs_modulus=float("nan")), 2, "material.youngs_modulus"),
    ("angle-95", mutated(geometry__angles_deg=[30.0, 95.0]), 2, "geometry.angles_deg[1]"),
    ("angle-0", mutated(geometry__angles_deg=[0.0, 40.0]), 2, "geometry.angles_deg[0]"),
    ("angle-negative", mutated(geometry__angles_deg=[-30.0, 40.0]), 2, "geometry.angles_deg[0]"),
    ("angles-three", mutated(geometry__angles_deg=[30.0, 40.0, 50.0]), 2, "geometry.angles_deg"),
    ("angle-string", mutated(geometry__angles_deg=["30", 40.0]), 2, "geometry.angles_deg[0]"),
    ("point-outside", mutated(geometry__point=[0.3, 0.5]), 2, "geometry.point"),
    ("point-on-chord", mutated(geometry__point=[0.3, 0.0]), 2, "geometry.point"),
    ("point-3d-in-2d", mutated(geometry__point=[0.3, 0.07, 0.0]), 2, "geometry.point"),
    ("chord-zero", mutated(geometry__end=[0.0, 0.0]), 2, "geometry.end"),
    ("start-1d", mutated(geometry__start=[0.0]), 2, "geometry.start"),
    ("end-nan", mutated(geometry__end=[float("nan"), 0.0]), 2, "geometry.end[0]"),
    (
        "angles-on-line",
        mutated(geometry={**LINE, "angles_deg": [30.0, 40.0]}),
        2,
        "geometry.angles_deg",
    ),
    ("degree-on-conic", mutated(geometry__degree=3), 2, "geometry.degree"),
    ("line-zero-length", mutated(geometry={**LINE, "end": [0.0, 0.0]}), 2, "geometry.end"),
    ("knots-on-line", mutated(geometry={**LINE, "knots": [0.0, 1.0]}), 2, "geometry.knots"),
    ("nurbs-degree-5", nurbs(degree=5), 2, "geometry.degree"),
    ("nurbs-degree-1", nurbs(degree=1), 2, "geometry.degree"),
    (
        "nurbs-few-points",
        nurbs(degree=3, knots=[0.0] * 4 + [1.0] * 4),
        2,
        "geometry.control_points",
    ),
    ("nurbs-knots-length", nurbs(knots=[0.0, 0.0, 1.0, 1.0]), 2, "geometry.knots"),
    ("nurbs-knots-decreasing", nurbs(knots=[0.0, 0.0, 0.0, 1.0, 0.5, 1.0]), 2, "geometry.knots"),
    (
        "nurbs-knots-missing",
        mutated(geometry={k: v for k, v in NURBS.items() if k != "knots"}),
        2,
        "geometry.knots",
    ),
    ("nurbs-weight-negative", nurbs(weights=[1.0, -1.0, 1.0]), 2, "geometry.weights"),
    ("nurbs-weights-count", nurbs(weights=[1.0, 1.0]), 2, "geometry.weights"),
    (
        "nurbs-coincident-points",
        nurbs(control_points=[[0.0, 0.0], [0.0, 0.0], [0.5, 0.0]]),
        2,
        "geometry.control_points",
    ),
    ("nurbs-all-coincident", nurbs(control_points=[[0.1, 0.1]] * 3), 2, "geometry"),
    ("nurbs-point-on-conic-key", nurbs(point=[0.3, 0.07]), 2, "geometry.point"),
    (
        "nurbs-kink",
        nurbs(
            degree=2,
            knots=[0, 0, 0, 0.5, 0.5, 1, 1, 1],
            control_points=[[0, 0], [0.1, 0.2], [0.2, 0.0], [0.3, 0.2], [0.5, 0.0]],
        ),
        2,
        "geometry.control_points",
    ),
    ("support-node-7", mutated(supports=[{"at": 7, "kind": "pin"}]), 2, "supports[0].at"),
    ("support-kind", mutated(supports=[{"at": "start", "kind": "weld"}]), 2, "supports[0].kind"),
    ("support-at-middle", mutated(supports=[{"at": "middle"}]), 2, "supports[0].at"),
    ("support-not-array", mutated(supports={"at": "start"}), 2, "supports"),
    ("gravity-3d-in-2d", mutated(loads={"gravity": [0.0, -9.81, 0.0]}), 2, "loads.gravity"),
    (
        "point-load-force",
        mutated(loads={"point": [{"at": "end", "force": [1.0]}]}),
        2,
        "loads.point[0].force",
    ),
    (
        "point-load-frequency",
        mutated(loads={"point": [{"at": "end", "force": [0.0, 1.0], "frequency_hz": -2.0}]}),
        2,
        "loads.point[0].frequency_hz",
    ),
    (
        "point-load-node",
        mutated(loads={"point": [{"at": 99, "force": [0.0, 1.0]}]}),
        2,
        "loads.point[0].at",
    ),
    (
        "damping-negative",
        mutated(damping={"mass_proportional": -0.1}),
        2,
        "damping.mass_proportional",
    ),
    (
        "velocity-on-pin",
        mutated(initial_velocity=[{"at": "start", "value": [0.0, 1.0]}]),
        2,
        "initial_velocity[0].at",
    ),
    (
        "velocity-dims",
        mutated(initial_velocity=[{"at": "end", "value": [1.0]}]),
        2,
        "initial_velocity[0].value",
    ),
    ("step-negative", mutated(solver__step=-1e-3), 2, "solver.step"),
    ("step-above-t-end", mutated(solver__step=0.5), 2, "solver.step"),
    ("t-end-bool", mutated(solver__t_end=True), 2, "solver.t_end"),
    ("t-end-inf", mutated(solver__t_end=float("inf")), 2, "solver.t_end"),
    ("min-step-above-step", mutated(solver__min_step=1e-2), 2, "solver.min_step"),
    ("output-step-above-t-end", mutated(solver__output_step=1.0), 2, "solver.output_step"),
    ("rho-inf-2", mutated(solver__rho_inf=2.0), 2, "solver.rho_inf"),
    ("max-newton-0", mutated(solver__max_newton=0), 2, "solver.max_newton"),
    ("newton-kind", mutated(solver__newton="half"), 2, "solver.newton"),
    ("adaptive-string", mutated(solver__adaptive="yes"), 2, "solver.adaptive"),
    ("rtol-zero", mutated(solver__rtol=0.0), 2, "solver.rtol"),
    ("load-steps-0", mutated(solver__load_steps=0), 2, "solver.load_steps"),
    (
        "sensor-name-twice",
        mutated(
            sensors=[
                {"name": "a", "kind": "position", "at": "end"},
                {"name": "a", "kind": "position", "at": "start"},
            ]
        ),
        2,
        "sensors[1].name",
    ),
    (
        "sensor-name-t",
        mutated(sensors=[{"name": "t", "kind": "position", "at": "end"}]),
        2,
        "sensors[0].name",
    ),
    (
        "sensor-kind",
        mutated(sensors=[{"name": "a", "kind": "speed", "at": "end"}]),
        2,
        "sensors[0].kind",
    ),
    (
        "sensor-between-one",
        mutated(sensors=[{"name": "a", "kind": "distance", "between": ["start"]}]),
        2,
        "sensors[0].between",
    ),
    ("sensor-node", mutated(sensors=[{"name": "a", "kind": "position", "at": 42}]), 2, "sensors.a"),
    ("modes-count-0", mutated(modes={"count": 0}), 2, "modes.count"),
    ("modes-about", mutated(modes={"about": "dynamic"}), 2, "modes.about"),
    ("rod-2d", mutated(mesh__element="rod", material__shear_modulus=1e6), 2, "mesh.element"),
    ("rod-no-shear", rod(material__poisson_ratio=None), 2, "material.shear_modulus"),
    ("rod-shear-and-nu", rod(material__shear_modulus=8e6), 2, "material.poisson_ratio"),
    ("rod-nu-0.5", rod(material__poisson_ratio=0.5), 2, "material.poisson_ratio"),
    ("rod-nu-string", rod(material__poisson_ratio="0.3"), 2, "material.poisson_ratio"),
    (
        "rod-shear-zero",
        rod(material__poisson_ratio=None, material__shear_modulus=0.0),
        2,
        "material.shear_modulus",
    ),
    ("cable-shear", mutated(material__shear_modulus=1e6), 2, "material.shear_modulus"),
    ("cable-nu", mutated(material__poisson_ratio=0.3), 2, "material.poisson_ratio"),
    ("cable-inertia-y", mutated(section={**PRINCIPAL}), 2, "section.inertia_y"),
    ("cable-torsion", mutated(section__torsion_constant=1e-8), 2, "section.torsion_constant"),
    ("rod-torsion-negative", rod(section__torsion_constant=-1e-8), 2, "section.torsion_constant"),
    (
        "rod-no-orientation",
        rod(section=_without(PRINCIPAL, "orientation")),
        2,
        "section.orientation",
    ),
    ("rod-no-inertia-z", rod(section=_without(PRINCIPAL, "inertia_z")), 2, "section.inertia_z"),
    ("rod-inertia-and-y", rod(section={**PRINCIPAL, "inertia": 1e-7}), 2, "section.inertia"),
    ("rod-radius-and-y", rod(section__inertia_y=1e-7), 2, "section"),
    (
        "rod-orientation-2",
        rod(section={**PRINCIPAL, "orientation": [1.0, 0.0]}),
        2,
        "section.orientation",
    ),
    (
        "rod-orientation-zero",
        rod(section={**PRINCIPAL, "orientation": [0.0, 0.0, 0.0]}),
        2,
        "section.orientation",
    ),
    (
        "rod-orientation-tangent",
        rod(section={**PRINCIPAL, "orientation": [3**0.5 / 2, 0.5, 0.0]}),
        2,
        "section.orientation",
    ),
    (
        "rod-moment-2",
        rod(loads={"point": [{"at": "end", "moment": [0.0, 1.0]}]}),
        2,
        "loads.point[0].moment",
    ),
    (
        "rod-moment-nan",
        rod(loads={"point": [{"at": "end", "moment": [0.0, float("nan"), 1.0]}]}),
        2,
        "loads.point[0].moment[1]",
    ),
    ("load-neither", rod(loads={"point": [{"at": "end"}]}), 2, "loads.point[0].force"),
    (
        "cable-moment",
        mutated(loads={"point": [{"at": "end", "moment": [0.0, 0.0, 1.0]}]}),
        2,
        "loads.point[0].moment",
    ),
    (
        "cable-fix-twist",
        mutated(supports=[{"at": "start", "fix_twist": True}]),
        2,
        "supports[0].fix_twist",
    ),
    (
        "rod-fix-twist-string",
        rod(supports=[{"at": "start", "fix_twist": "yes"}]),
        2,
        "supports[0].fix_twist",
    ),
    (
        "cable-twist-sensor",
        mutated(sensors=[{"name": "a", "kind": "twist", "at": "end"}]),
        2,
        "sensors[0].kind",
    ),
    (
        "rod-twist-between",
        rod(sensors=[{"name": "a", "kind": "twist", "between": [0, 1]}]),
        2,
        "sensors[0].at",
    ),
    ("rod-twist-node", rod(sensors=[{"name": "a", "kind": "twist", "at": 9}]), 2, "sensors.a"),
    ("rotary-on-cable", mutated(section__rotary_inertia="full"), 2, "section.rotary_inertia"),
    ("rotary-bad", rod(section__rotary_inertia="bending"), 2, "section.rotary_inertia"),
    (
        "rotary-full-unequal",
        rod(section={**PRINCIPAL, "rotary_inertia": "full"}),
        2,
        "section.rotary_inertia",
    ),
    ("motion-empty", rod(initial_motion={}), 2, "initial_motion"),
    (
        "motion-unknown-key",
        rod(initial_motion={"omega": [0.0, 0.0, 1.0]}),
        2,
        "initial_motion.omega",
    ),
    (
        "motion-2d-vector",
        mutated(initial_motion={"angular_velocity": [0.0, 0.0, 1.0]}),
        2,
        "initial_motion.angular_velocity",
    ),
    (
        "motion-3d-number",
        rod(initial_motion={"angular_velocity": 1.0}),
        2,
        "initial_motion.angular_velocity",
    ),
    (
        "motion-about-2",
        rod(initial_motion={"angular_velocity": [0.0, 0.0, 1.0], "about": [0.0, 0.0]}),
        2,
        "initial_motion.about",
    ),
    ("motion-moves-clamp", rod(initial_motion={"velocity": [0.0, 1.0, 0.0]}), 2, "initial_motion"),
    (
        "motion-turns-clamp",
        rod(initial_motion={"angular_velocity": [0.0, 0.0, 1.0]}),
        2,
        "initial_motion",
    ),
    (
        "motion-and-velocity",
        mutated(
            initial_motion={"angular_velocity": 1.0},
            initial_velocity=[{"at": "end", "value": [0.0, 0.1]}],
        ),
        2,
        "initial_motion",
    ),
    (
        "momentum-at",
        rod(sensors=[{"name": "L", "kind": "angular_momentum", "at": "end"}]),
        2,
        "sensors[0].at",
    ),
    (
        "about-on-position",
        rod(sensors=[{"name": "p", "kind": "position", "at": "end", "about": [0.0, 0.0, 0.0]}]),
        2,
        "sensors[0].about",
    ),
    (
        "momentum-about-2",
        rod(sensors=[{"name": "L", "kind": "angular_momentum", "about": [0.0, 0.0]}]),
        2,
        "sensors[0].about",
    ),
    ("t-end-1e6", mutated(solver__t_end=1e6), 2, "GB"),
    ("t-end-1e12", mutated(solver__t_end=1e12, solver__output_step=1.0), 2, "solver.t_end"),
]


@pytest.fixture
def workdir(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    return tmp_path


def _tree(root: Path) -> set[str]:
    return {str(p.relative_to(root)) for p in root.rglob("*")}


def check_one_line(capsys, argv, status, needle, root):
    before = _tree(root)
    code = main(argv)
    out, err = capsys.readouterr()
    lines = err.strip().splitlines()
    assert code == status, err
    assert len(lines) == 1, err
    assert lines[0].startswith("rancf: "), err
    assert needle in lines[0], err
    assert "Traceback" not in err
    assert _tree(root) == before, "output left behind"
    return lines[0]


@pytest.mark.parametrize(
    ("text", "status", "needle"), [c[1:] for c in SCENARIOS], ids=[c[0] for c in SCENARIOS]
)
def test_bad_scenario_through_simulate(workdir, capsys, text, status, needle):
    (workdir / "s.toml").write_text(text)
    line = check_one_line(
        capsys, ["simulate", "s.toml", "--out", "run", "--quiet"], status, needle, workdir
    )
    assert "s.toml" in line


BAD_FILES = [
    ("missing-file", None, "nope.toml"),
    ("binary-garbage", bytes(range(256)) * 4, "s.toml"),
    ("latin-1-comment", "# café\n".encode("latin-1") + BASE.encode(), "s.toml"),
    ("not-toml", b"[geometry\nkind = ", "s.toml"),
    ("empty-file", b"", "s.toml"),
    ("nul-bytes", b"\x00" * 64, "s.toml"),
]


@pytest.mark.parametrize(
    ("content", "name"), [c[1:] for c in BAD_FILES], ids=[c[0] for c in BAD_FILES]
)
@pytest.mark.parametrize("command", ["simulate", "static", "modes"])
def test_bad_scenario_files(workdir, capsys, content, name, command):
    if content is not None:
        (workdir / name).write_bytes(content)
    argv = [command, name] + (["--out", "run"] if command == "simulate" else [])
    check_one_line(capsys, argv, 2, name, workdir)


def _setup_paths(root: Path) -> None:
    (root / "s.toml").write_text(BASE)
    (root / "c.toml").write_text(
        mutated(
            geometry=LINE,
            supports=[{"at": 0, "kind": "clamp"}],
            loads={"point": [{"at": -1, "force": [0.0, -1e-3]}]},
        )
    )
    (root / "afile").write_text("x")
    (root / "adir").mkdir()


BAD_ARGS = [
    ("out-under-file", ["simulate", "s.toml", "--out", "afile/run"], 2, "--out"),
    ("out-is-file", ["simulate", "s.toml", "--out", "afile"], 2, "--out"),
    ("out-under-proc", ["simulate", "s.toml", "--out", "/proc/rancf-run"], 2, "--out"),
    (
        "checkpoint-0",
        ["simulate", "s.toml", "--out", "run", "--checkpoint-every", "0"],
        2,
        "--checkpoint-every",
    ),
    (
        "checkpoint-negative",
        ["simulate", "s.toml", "--out", "r", "--checkpoint-every", "-5"],
        2,
        "--checkpoint-every",
    ),
    (
        "checkpoint-nan",
        ["simulate", "s.toml", "--out", "run", "--checkpoint-every", "nan"],
        2,
        "--checkpoint-every",
    ),
    (
        "checkpoint-text",
        ["simulate", "s.toml", "--out", "run", "--checkpoint-every", "x"],
        2,
        "--checkpoint-every",
    ),
    (
        "max-output-0",
        ["simulate", "s.toml", "--out", "run", "--max-output-gb", "0"],
        2,
        "--max-output-gb",
    ),
    ("simulate-no-out", ["simulate", "s.toml"], 2, "--out"),
    ("threads-0", ["simulate", "s.toml", "--out", "run", "--threads", "0"], 2, "--threads = 0"),
    ("modes-count-0", ["modes", "c.toml", "--count", "0"], 2, "--count"),
    ("modes-count-10000", ["modes", "c.toml", "--count", "10000"], 2, "--count"),
    ("modes-about", ["modes", "c.toml", "--about", "dynamic"], 2, "--about"),
    ("modes-plot-ext", ["modes", "c.toml", "--plot", "modes.xyz"], 2, "--plot"),
    ("modes-plot-missing-dir", ["modes", "c.toml", "--plot", "nodir/m.png"], 2, "--plot"),
    ("modes-plot-dir", ["modes", "c.toml", "--plot", "adir"], 2, "--plot"),
    ("conic-plot-ext", [*CONIC, "--plot", "c.txt"], 2, "--plot"),
    ("conic-plot-missing-dir", [*CONIC, "--plot", "nodir/c.png"], 2, "--plot"),
    ("conic-plot-under-file", [*CONIC, "--plot", "afile/c.png"], 2, "--plot"),
    ("conic-elements-0", [*CONIC, "--elements", "0"], 2, "--elements"),
    ("conic-elements-many", [*CONIC, "--elements", "100000"], 2, "--elements"),
    ("conic-k-1.5", [*CONIC, "--k", "1.5"], 2, "--k"),
    ("conic-k-nan", [*CONIC, "--k", "nan"], 2, "--k"),
    (
        "conic-chord-negative",
        ["conic", "--chord", "-1", "--angles", "30", "40", "--point", "0.3", "0.07"],
        2,
        "--chord = -1",
    ),
    (
        "conic-chord-text",
        ["conic", "--chord", "abc", "--angles", "30", "40", "--point", "0.3", "0.07"],
        2,
        "--chord",
    ),
    (
        "conic-angle-95",
        ["conic", "--chord", "0.5", "--angles", "30", "95", "--point", "0.3", "0.07"],
        2,
        "--angles T1 = 95",
    ),
    (
        "conic-point-outside",
        ["conic", "--chord", "0.5", "--angles", "30", "40", "--point", "0.3", "0.5"],
        2,
        "--point = ",
    ),
    ("conic-missing-point", ["conic", "--chord", "0.5", "--angles", "30", "40"], 2, "--point"),
    ("conic-spacing", [*CONIC, "--spacing", "log"], 2, "--spacing"),
    ("unknown-command", ["simulat", "s.toml"], 2, "simulat"),
    ("no-command", [], 2, "command"),
    ("example-unknown-action", ["example", "fly"], 2, "fly"),
    ("example-run-unknown", ["example", "run", "nope", "--out", "x"], 2, "nope"),
    ("example-run-out-file", ["example", "run", "planar-pendulum", "--out", "afile"], 2, "--out"),
    ("example-run-no-out", ["example", "run", "planar-pendulum"], 2, "--out"),
    ("example-copy-unknown", ["example", "copy", "nope", "adir"], 2, "nope"),
    ("example-copy-to-file", ["example", "copy", "cantilever", "afile"], 2, "afile"),
    ("report-out-file", ["report", "--out", "afile"], 2, "--out"),
    ("report-out-under-file", ["report", "--out", "afile/rep"], 2, "--out"),
    ("static-missing", ["static", "missing.toml"], 2, "missing.toml"),
    ("static-directory", ["static", "adir"], 2, "adir"),
    ("static-out-file", ["static", "s.toml", "--out", "afile"], 2, "--out"),
    ("static-out-under-file", ["static", "s.toml", "--out", "afile/st"], 2, "--out"),
]


@pytest.mark.parametrize(
    ("argv", "status", "needle"), [c[1:] for c in BAD_ARGS], ids=[c[0] for c in BAD_ARGS]
)
def test_bad_arguments(workdir, capsys, argv, status, needle):
    _setup_paths(workdir)
    check_one_line(capsys, argv, status, needle, workdir)


def test_example_copy_refuses_to_overwrite(workdir, capsys):
    assert main(["example", "copy", "cantilever", "here"]) == 0
    capsys.readouterr()
    check_one_line(capsys, ["example", "copy", "cantilever", "here"], 2, "--force", workdir)


def test_corpus_is_large():
    n = len(SCENARIOS) + 3 * len(BAD_FILES) + len(BAD_ARGS) + 1
    assert n >= 100


@pytest.mark.skipif(os.geteuid() == 0, reason="root may write into a read-only directory")
def test_out_in_read_only_directory(workdir, capsys):
    _setup_paths(workdir)
    (workdir / "ro").mkdir(mode=0o555)
    check_one_line(capsys, ["simulate", "s.toml", "--out", "ro/run"], 2, "--out", workdir)
