"""MoorPy's catenary test suite (``tests/test_catenary.py``) through ``rancf static --json``,
side by side with MoorPy's ``catenary`` on the same inputs.

    python benchmarks/mooring/moorpy_catenary_suite.py [--elements 40 80 160]
        [--moorpy-python PATH] [--repeats N] [--out FILE]

The cases, their scenarios and expected values are those of the tests
(:mod:`tests.solvers.moorpy_catenary_cases`; the hardest near-taut case against the exact elastic
catenary, see :mod:`tests.solvers.test_moorpy_catenary`).  Per case and mesh: the end forces'
largest error relative to the fairlead tension, the method, Newton iterations, relaxation
steps, the elements it was solved on (``rancf static`` refines a line whose touchdown its mesh
does not resolve), the solve time ``rancf static`` reports (``wall_time_s``, median over
the repeats) and the solve's CPU time (:func:`solve_cpu`); MoorPy's time is that of its
``catenary`` call (median over the repeats) in the interpreter given by ``--moorpy-python`` (a
venv with ``moorpy==1.3.*``: a benchmark dependency, not one of rancf's), run in the same
session, case by case after rancf's.  Writes ``benchmarks/results/moorpy_catenary_suite.json``.
Run it under ``flock /tmp/rancf-bench.lock`` on a shared machine.
"""

from __future__ import annotations

import argparse
import json
import statistics
import subprocess
import sys
import tempfile
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[2]
sys.path.insert(0, str(ROOT))

from tests.solvers.moorpy_catenary_cases import CASES, scenario_text  # noqa: E402
from tests.solvers.test_moorpy_catenary import expected  # noqa: E402

#: MoorPy's side: one case's forces and the median time of ``repeats`` calls.
MOORPY = """
import json, statistics, sys, time
from moorpy.Catenary import catenary
x, z, L, ea, w, cb, alpha, repeats = json.loads(sys.argv[1])
times = []
for _ in range(repeats):
    t = time.perf_counter()
    out = catenary(x, z, L, ea, w, CB=cb, alpha=alpha, Tol=1e-5, MaxIter=50)
    times.append(time.perf_counter() - t)
print(json.dumps({"forces": [float(f) for f in out[:4]], "time_s": statistics.median(times)}))
"""


def run_rancf(case, elements: int, repeats: int, folder: Path) -> dict:
    """``rancf static --json`` of the case: forces (MoorPy's signs), error, method, times."""
    path = folder / f"{case.name}-{elements}.toml"
    path.write_text(scenario_text(case, elements))
    times, out = [], None
    for _ in range(repeats):
        p = subprocess.run(
            [sys.executable, "-m", "rancf", "static", str(path), "--json"],
            capture_output=True,
            text=True,
        )
        if p.returncode:
            return {
                "converged": False,
                "exit": p.returncode,
                "message": p.stderr.strip().splitlines()[-1],
            }
        out = json.loads(p.stdout)
        times.append(out["wall_time_s"])
    ends = out["reactions"]
    got = -np.r_[ends[0]["force"][:2], ends[-1]["force"][:2]]
    want = expected(case)
    return {
        "converged": True,
        "forces": got.tolist(),
        "error": float(np.abs(got - want).max() / np.hypot(*want[2:])),
        "method": out["method"],
        "elements_solved": len(next(iter(out["positions"].values()))) - 1,
        "warnings": out["warnings"],
        "newton_iterations": out["newton_iterations"],
        "relaxation_steps": out["relaxation_steps"],
        "time_s": statistics.median(times),
        "cpu_s": solve_cpu(path, repeats),
    }


def solve_cpu(path: Path, repeats: int) -> float:
    """The CPU time [s] of the static solve alone (every call of
    :func:`rancf.solvers.static.solve_static` of one ``run_static``: a re-solve on a refined
    mesh counted too), in this process, median over ``repeats`` runs after a warm-up: on a
    shared machine the wall time also counts the other jobs' share of the cores."""
    import time

    import rancf.solvers.static as static
    from rancf.runs.static import run_static
    from rancf.scenario.scenario import load_scenario

    solve, spent = static.solve_static, [0.0]

    def timed(*args, **kwargs):
        t0 = time.process_time()
        try:
            return solve(*args, **kwargs)
        finally:
            spent[0] += time.process_time() - t0

    static.solve_static = timed
    try:
        times = []
        for k in range(repeats + 1):
            spent[0] = 0.0
            run_static(load_scenario(path))
            if k:
                times.append(spent[0])
    finally:
        static.solve_static = solve
    return statistics.median(times)


def run_moorpy(case, python: str, repeats: int) -> dict:
    args = [case.x, case.z, case.length, case.ea, case.w, case.cb, case.alpha, repeats]
    p = subprocess.run([python, "-c", MOORPY, json.dumps(args)], capture_output=True, text=True)
    if p.returncode:
        return {"error": p.stderr.strip().splitlines()[-1]}
    return json.loads(p.stdout)


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--elements", type=int, nargs="+", default=[40, 80, 160])
    ap.add_argument("--moorpy-python", default="/work/venv-moorpy/bin/python")
    ap.add_argument("--repeats", type=int, default=3)
    ap.add_argument("--out", default=str(ROOT / "benchmarks/results/moorpy_catenary_suite.json"))
    a = ap.parse_args()
    rows = []
    with tempfile.TemporaryDirectory() as tmp:
        for case in CASES:
            row = {
                "case": case.name,
                "expected": expected(case).tolist(),
                "moorpy": run_moorpy(case, a.moorpy_python, a.repeats),
            }
            for n in a.elements:
                row[f"rancf_{n}"] = r = run_rancf(case, n, a.repeats, Path(tmp))
                err = f"{100 * r['error']:.3f} %" if r["converged"] else f"exit {r['exit']}"
                how = (
                    f"{r['method']}, {r['newton_iterations']} it, {1e3 * r['time_s']:.1f} ms wall, "
                    f"{1e3 * r['cpu_s']:.1f} ms CPU"
                    if r["converged"]
                    else ""
                )
                print(f"{case.name:16s} {n:4d}  {err:>10s}  {how}", flush=True)
            rows.append(row)
    Path(a.out).write_text(json.dumps({"cases": rows}, indent=1) + "\n")
    print(f"wrote {a.out}")
    print(markdown(rows, a.elements))


def markdown(rows: list[dict], elements: list[int]) -> str:
    """The docs' table: per case the expected fairlead force, rancf's at the first mesh, the
    largest error per mesh and the solve times (rancf's at the first mesh, MoorPy's)."""
    meshes = " / ".join(str(n) for n in elements)
    out = [
        f"| case | expected fairlead (H, V) | rancf, {elements[0]} el. | error, {meshes} el. "
        f"| rancf solve (wall / CPU), {meshes} el. | MoorPy time |",
        "|---|---|---|---|---|---|",
    ]
    for row in rows:
        first = row[f"rancf_{elements[0]}"]
        runs = [row[f"rancf_{n}"] for n in elements]
        errs = " / ".join(_error(r, n) for r, n in zip(runs, elements, strict=True))
        want = row["expected"]
        got = (
            f"{-first['forces'][2]:.1f}, {-first['forces'][3]:.1f} N"
            if first["converged"]
            else "exit 3"
        )
        rt = " / ".join(_times(r) for r in runs)
        mt = f"{1e3 * row['moorpy']['time_s']:.2f} ms" if "time_s" in row["moorpy"] else ""
        out.append(
            f"| {row['case']} | {-want[2]:.1f}, {-want[3]:.1f} N | {got} | {errs} | {rt} | {mt} |"
        )
    return "\n".join(out)


def _times(run: dict) -> str:
    """A run's solve times for the table: wall / CPU [ms]."""
    if not run["converged"]:
        return "-"
    return f"{1e3 * run['time_s']:.0f}/{1e3 * run['cpu_s']:.0f}"


def _error(run: dict, elements: int) -> str:
    """A run's error for the table, with the elements it was solved on where ``rancf static``
    refined the mesh (a touchdown: docs/guide/statics.md)."""
    if not run["converged"]:
        return "exit 3"
    solved = run.get("elements_solved", elements)
    return f"{100 * run['error']:.2f} %" + (f" ({solved} el.)" if solved != elements else "")


if __name__ == "__main__":
    main()
