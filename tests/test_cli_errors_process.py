"""The bad-input corpus, part 2: hostile input through the real ``rancf``
process.

Each case runs ``python -m rancf`` in a folder of its own and must end with the expected exit
status, exactly one line on standard error (``rancf: ...``) that names the key, option or path,
no traceback or warning, and the folder exactly as it was (no run folder, no empty folder, no
temporary file).  The processes run four at a time, so the corpus costs seconds.
"""

from __future__ import annotations

import os
import shutil
import subprocess
import sys
from concurrent.futures import ThreadPoolExecutor
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np
import pytest

from rancf.cli import main
from tests.test_cli_errors import LINE, mutated

RANCF = [sys.executable, "-m", "rancf"]
CONIC = ["conic", "--chord", "0.5", "--angles", "30", "40", "--point", "0.315", "0.077"]
SIM = ["simulate", "s.toml", "--out", "run", "--quiet"]
RUN = "run0"  # a finished run every case folder gets a copy of
CLAMPED = {
    "geometry": LINE,
    "supports": [{"at": 0, "kind": "clamp"}],
    "loads": {"point": [{"at": -1, "force": [0.0, -1e-3]}]},
}
NURBS = {
    "kind": "nurbs",
    "degree": 2,
    "knots": [0.0, 0.0, 0.0, 1.0, 1.0, 1.0],
    "control_points": [[0.0, 0.0], [0.25, 0.2], [0.5, 0.0]],
}


@dataclass
class Case:
    name: str
    argv: list[str]
    needle: str
    files: dict[str, str | bytes] = field(default_factory=dict)
    status: int = 2
    stdout: str = "pipe"  # "pipe" | "closed" | "full"
    damage: str | None = None  # what to do to run0/results.npz


def sim(name: str, needle: str, **changes) -> Case:
    return Case(name, SIM, needle, {"s.toml": mutated(**changes)})


def _sweep(grid: str, base: str = "s.toml") -> str:
    return f'base = "{base}"\nanalysis = "simulate"\n[grid]\n{grid}\n'


DEEP_TOML = "a = " + "[" * 1000 + "]" * 1000 + "\n"
BIG = "1" * 401
CASES = [
    sim("max-newton-1e20", "solver.max_newton", solver__max_newton=10**20),
    sim("step-1e-12", "solver.t_end / solver.step", solver__step=1e-12, solver__output_step=1e-2),
    sim("t-end-1e308", "solver.t_end", solver__t_end=1e308),
    sim("radius-1e100", "section.radius", section__radius=1e100),
    sim("radius-1e-100", "section.radius", section__radius=1e-100),
    sim("radius-401-digits", "[section.radius] must be finite", section__radius=int(BIG)),
    sim("elements-401-digits", "mesh.elements", mesh__elements=int(BIG)),
    sim("end-1e308", "geometry.end[0]", geometry__end=[1e308, 0.0]),
    sim("start-1e308", "geometry.start[0]", geometry__start=[-1e308, 0.0]),
    sim("point-1e308", "geometry.point[1]", geometry__point=[0.315, 1e308]),
    sim(
        "chord-1e-300",
        "geometry.end",
        geometry__end=[1e-300, 0.0],
        geometry__point=[5e-301, 1e-301],
    ),
    sim("angle-1e-300", "geometry.angles_deg[0]", geometry__angles_deg=[1e-300, 40.0]),
    sim("weights-1e300", "geometry.weights", geometry={**NURBS, "weights": [1.0, 1e300, 1.0]}),
    Case("toml-nested-1000", SIM, "nested too deeply", {"s.toml": DEEP_TOML}),
    Case(
        "integer-5000-digits",
        SIM,
        "s.toml",
        {"s.toml": mutated() + "[modes]\ncount = " + "1" * 5000 + "\n"},
    ),
    Case(
        "load-steps-1e9",
        ["static", "s.toml"],
        "solver.load_steps",
        {"s.toml": mutated(**CLAMPED, solver__load_steps=10**9)},
    ),
    Case(
        "conic-chord-1e-300",
        ["conic", "--chord", "1e-300", "--angles", "30", "40", "--point", "1e-301", "1e-302"],
        "--chord",
    ),
    Case("conic-k-1e-300", [*CONIC, "--k", "1e-300"], "--k"),
    Case(
        "conic-angle-1e-300",
        ["conic", "--chord", "0.5", "--angles", "1e-300", "40", "--point", "0.315", "0.077"],
        "--angles T0",
    ),
    Case(
        "conic-angle-near-90",
        ["conic", "--chord", "0.5", "--angles", "30", "89.99999999999999", "--point", "0.3", "0.1"],
        "--angles T1",
    ),
    Case(
        "conic-point-1e308",
        ["conic", "--chord", "0.5", "--angles", "30", "40", "--point", "0.315", "1e308"],
        "--point",
    ),
    Case(
        "sweep-scheduler-garbage",
        ["sweep", "w.toml", "--out", "sw", "--scheduler", "garbage"],
        "--scheduler",
        {"w.toml": _sweep('"mesh.elements" = [2]')},
    ),
    Case(
        "sweep-10000-runs-too-large",
        ["sweep", "w.toml", "--out", "sw"],
        "GB",
        {
            "s.toml": mutated(solver__t_end=2500.0),
            "w.toml": _sweep(
                f'"mesh.elements" = {list(range(1, 101))}\n'
                f'"damping.mass_proportional" = {[i * 0.01 for i in range(100)]}'
            ),
        },
    ),
    Case(
        "sweep-nested-1000",
        ["sweep", "w.toml", "--out", "sw"],
        "nested too deeply",
        {"w.toml": DEEP_TOML},
    ),
    Case(
        "sweep-out-empty",
        ["sweep", "w.toml", "--out", ""],
        "--out",
        {"w.toml": _sweep('"mesh.elements" = [2]')},
    ),
    Case(
        "sweep-out-not-a-sweep",
        ["sweep", "w.toml", "--out", RUN],
        "--out",
        {"w.toml": _sweep('"mesh.elements" = [2]'), "s.toml": mutated()},
    ),
    Case("stdout-closed", CONIC, "standard output is closed", stdout="closed"),
    Case("stdout-full", [*CONIC, "--json"], "standard output: No space left", stdout="full"),
    Case(
        "cad-list-binary-json",
        ["cad", "list", "bin.json"],
        "bin.json",
        {"bin.json": bytes(range(256)) * 64},
    ),
    Case(
        "cad-list-nested-json",
        ["cad", "list", "deep.json"],
        "nested too deeply",
        {"deep.json": "[" * 100_000},
    ),
    Case("out-empty", ["simulate", "s.toml", "--out", ""], "--out", {"s.toml": mutated()}),
    Case(
        "out-earlier-run",
        ["simulate", "s.toml", "--out", RUN],
        "--overwrite",
        {"s.toml": mutated()},
    ),
    Case(
        "out-not-a-run",
        ["simulate", "s.toml", "--out", "."],
        "not a rancf run folder",
        {"s.toml": mutated()},
    ),
    Case(
        "static-out-earlier-run",
        ["static", "s.toml", "--out", RUN],
        "--overwrite",
        {"s.toml": mutated(**CLAMPED)},
    ),
    Case("export-vtk-empty", ["export", RUN, "--vtk", ""], "--vtk"),
    Case("plot-out-empty", ["plot", RUN, "--out", ""], "--out"),
    Case(
        "export-samples-5000000", ["export", RUN, "--vtk", "v", "--samples", "5000000"], "--samples"
    ),
    Case("export-truncated-npz", ["export", RUN, "--vtk", "v"], "results.npz", damage="half"),
    Case("plot-empty-npz", ["plot", RUN], "results.npz", damage="empty"),
    Case(
        "export-garbage-npz", ["export", RUN, "--nurbs", "c.json"], "results.npz", damage="garbage"
    ),
    Case(
        "animate-npz-of-another-run",
        ["animate", RUN, "--out", "a.gif"],
        "a body folder of the run",
        damage="foreign",
    ),
    Case("export-npz-without-q", ["export", RUN, "--vtk", "v"], "results.npz", damage="no-q"),
]


def _damage(run: Path, how: str, other: Path) -> None:
    npz = run / "results.npz"
    data = npz.read_bytes()
    if how == "half":
        npz.write_bytes(data[: len(data) // 2])
    elif how == "empty":
        npz.write_bytes(b"")
    elif how == "garbage":
        npz.write_bytes(np.random.default_rng(1).bytes(len(data)))
    elif how == "foreign":
        shutil.copy(other / "results.npz", npz)
    elif how == "no-q":
        with np.load(npz) as z:
            arrays = {k: z[k] for k in z.files if k != "q"}
        with open(npz, "wb") as fh:
            np.savez(fh, **arrays)


def _tree(root: Path) -> dict[str, int]:
    return {str(p.relative_to(root)): p.stat().st_size for p in sorted(root.rglob("*"))}


def _run(case: Case, root: Path) -> tuple[int, str, dict, dict]:
    for name, content in case.files.items():
        path = root / name
        path.write_bytes(content) if isinstance(content, bytes) else path.write_text(content)
    before = _tree(root)
    kw: dict = {"stdout": subprocess.DEVNULL}
    if case.stdout == "closed":
        kw = {"stdout": None, "preexec_fn": lambda: os.close(1)}
    elif case.stdout == "full":
        kw = {"stdout": open("/dev/full", "wb")}  # noqa: SIM115 - closed with the process
    try:
        p = subprocess.run([*RANCF, *case.argv], cwd=root, stderr=subprocess.PIPE, timeout=60, **kw)
    except subprocess.TimeoutExpired:  # refused too late, or not at all
        return -1, "timed out after 60 s", before, _tree(root)
    return p.returncode, p.stderr.decode(errors="replace"), before, _tree(root)


@pytest.fixture(scope="module")
def results(tmp_path_factory):
    base = tmp_path_factory.mktemp("hostile")
    cwd = os.getcwd()
    os.chdir(base)
    try:
        (base / "s.toml").write_text(mutated())
        (base / "t.toml").write_text(mutated(mesh__elements=5))
        assert main(["simulate", "s.toml", "--out", RUN, "--quiet"]) == 0
        assert main(["simulate", "t.toml", "--out", "other", "--quiet"]) == 0
    finally:
        os.chdir(cwd)
    roots = {}
    for case in CASES:
        roots[case.name] = root = base / case.name
        shutil.copytree(base / RUN, root / RUN)
        if case.damage:
            _damage(root / RUN, case.damage, base / "other")
    with ThreadPoolExecutor(4) as pool:
        done = {c.name: pool.submit(_run, c, roots[c.name]) for c in CASES}
        return {name: f.result() for name, f in done.items()}


@pytest.mark.parametrize("case", CASES, ids=[c.name for c in CASES])
def test_hostile_input_in_a_real_process(results, case):
    status, err, before, after = results[case.name]
    lines = err.strip().splitlines()
    assert status == case.status, err
    assert len(lines) == 1 and lines[0].startswith("rancf: "), err
    assert case.needle in lines[0], err
    assert len(lines[0]) < 400, f"{len(lines[0])} characters"
    assert "Traceback" not in err and "Warning" not in err
    assert after == before, "output left behind"


def test_corpus_grew():
    assert len(CASES) >= 40
