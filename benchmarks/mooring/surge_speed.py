"""The surging chain in 3D at equal accuracy: ``rancf simulate`` against MoorDyn 2.7, whole runs.

    python benchmarks/mooring/surge_speed.py [--pairs 3] [--peer-python PYTHON]
        [--scenario mooring-surge-fast.toml] [--iteration-elements 20 80]

Four parts, each printed as a table, the CPU and its load named at the end:

1. **Accuracy.** MoorDyn at 160 segments (its default step, 0.04 s / 160) is the converged
   answer; ``--scenario`` (default ``mooring-surge-fast.toml``: 20 elements, 0.2 s steps, the
   coarsest settings found within 3 %), the same file with the element counts and steps of
   ``--scan`` and MoorDyn at 40 segments and 1e-4 s are compared with it once a second from
   t = 20 s to 60 s (the fairlead force's size, as ``compare_surge.py``).
2. **Whole runs, pairs interleaved.** ``rancf simulate`` of the scenario (static initial state
   included) against ``moordyn_surge.py --segments 40 --dt 1e-4`` (its static solve included),
   A B A B ...; per run the process wall and CPU time (user + system: on a shared machine
   the steadier figure), and apart: rancf's ``setup_wall_time_s``
   (process start to the first step, imports included) and solve time, MoorDyn's
   initialization (its static solve) and solve time.  The ratio is taken pair by pair and its
   median quoted, of the wall and of the CPU times.
3. **Per Newton iteration.** The scenario for 20 s with ``newton = "full"`` (a Jacobian every
   iteration) at each of ``--iteration-elements``, against the same line without fluid and
   seabed (a plain cable hanging between the same points): solve time over Newton iterations,
   pairs interleaved, the ratio's median.
4. **Set-up, phase by phase**, in fresh processes (the median of the runs): the imports of a
   run, reading the scenario (pydantic's first validation builds the validator), building the
   system, the static initial state; wall and CPU times.
"""

from __future__ import annotations

import argparse
import json
import os
import re
import resource
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))

from common import HERE, peer, rancf, read_series, table  # noqa: E402
from compare_surge import per_second, reaction_size, worst  # noqa: E402
from provenance import machine, version  # noqa: E402

PHASES = """
import importlib, json, os, sys, time
os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")
T = [(time.perf_counter(), time.process_time())]
before = set(sys.modules)
for name in json.loads(sys.argv[2]):  # what the run below loads, first (all of it imports)
    importlib.import_module(name)
from rancf.cli.resume import scenario_for_run
from rancf.post.run_plan import plan_run
from rancf.solvers.start import start_state
T.append((time.perf_counter(), time.process_time()))
sc, copy = scenario_for_run(sys.argv[1], None)
T.append((time.perf_counter(), time.process_time()))
system, outputs = plan_run(sc, 10.0)
T.append((time.perf_counter(), time.process_time()))
y0, info = start_state(sc, system)
T.append((time.perf_counter(), time.process_time()))
loaded = [m for m in sys.modules if m not in before and "._" not in m and m[0] != "_"]
out = {"modules": loaded}
for i, k in enumerate(("imports", "read", "build", "static")):
    out[k] = T[i + 1][0] - T[i][0]
    out[k + " cpu"] = T[i + 1][1] - T[i][1]
print(json.dumps(out))
"""


def children_cpu() -> float:
    """User and system CPU time of the finished child processes so far [s]."""
    r = resource.getrusage(resource.RUSAGE_CHILDREN)
    return r.ru_utime + r.ru_stime


def run_rancf(scenario: Path, out: Path) -> dict[str, float]:
    """``rancf simulate`` as a process: its summary's times, the process wall and CPU time."""
    cpu0 = children_cpu()
    proc, wall = rancf("simulate", str(scenario), "--out", str(out), "--quiet", "--overwrite")
    if proc.returncode != 0:
        raise RuntimeError(f"rancf simulate {scenario.name} failed:\n{proc.stderr[-2000:]}")
    s = json.loads((out / "summary.json").read_text())
    return {
        "wall": wall,
        "cpu": children_cpu() - cpu0,
        "setup": s["setup_wall_time_s"],
        "static": s["static"]["wall_time_s"] if "static" in s else float("nan"),
        "solve": s["solve_wall_time_s"],
        "iterations": s["newton_iterations"],
        "steps": s["steps"],
    }


def differences(rows: list, ref: dict[int, float], series: dict, label: str) -> None:
    err, at = worst(per_second(series["t"], series["f"]), ref)
    rows.append([label, f"{100 * err:.2f} %", str(at)])


def variant(text: str, **keys: str) -> str:
    """``text`` with the values of ``keys`` replaced (each the first ``key = ...`` line)."""
    for k, v in keys.items():
        text = re.sub(rf"(?m)^{k} = .*$", f"{k} = {v}", text, count=1)
    return text


def plain(text: str) -> str:
    """The scenario without fluid, hydrodynamics and obstacles: a plain cable."""
    for head in (r"\[fluid\]", r"\[hydro\]", r"\[\[obstacles\]\]"):
        text = re.sub(rf"(?ms)^{head}\n.*?(?=^\[)", "", text)
    return text


def accuracy(a: argparse.Namespace, tmp: Path) -> list[list[str]]:
    """Part 1: the scenario and MoorDyn 40 / 1e-4 s against MoorDyn 160 segments."""
    csv160, csv40 = tmp / "md160.csv", tmp / "md40.csv"
    peer(a.peer_python, "moordyn_surge.py", "--segments", "160", "--csv", str(csv160))
    peer(a.peer_python, "moordyn_surge.py", "--segments", "40", "--dt", "1e-4", "--csv", str(csv40))
    r160 = read_series(csv160)
    ref = per_second(r160["t_s"], r160["tension_N"])
    rows = [["run", "max |dF|/F, t >= 20 s", "at t [s]"]]
    run_rancf(HERE / a.scenario, tmp / "acc")
    s = read_series(tmp / "acc" / "sensors.csv")
    differences(rows, ref, {"t": s["t"], "f": reaction_size(s)}, f"rancf {a.scenario}")
    base = (HERE / a.scenario).read_text()
    for spec in a.scan:  # the file with other element counts and steps
        n, h = spec.split(":")
        f = tmp / f"scan-{n}-{h}.toml"
        f.write_text(variant(base, elements=n, step=h))
        try:
            run_rancf(f, tmp / "scan")
        except RuntimeError as exc:
            rows.append([f"rancf {n} elements, {h} s", "failed", str(exc).splitlines()[-1][:60]])
            continue
        s = read_series(tmp / "scan" / "sensors.csv")
        differences(rows, ref, {"t": s["t"], "f": reaction_size(s)}, f"rancf {n} elements, {h} s")
    s40 = read_series(csv40)
    differences(rows, ref, {"t": s40["t_s"], "f": s40["tension_N"]}, "MoorDyn 40 segments, 1e-4 s")
    return rows


def whole_runs(a: argparse.Namespace, tmp: Path) -> tuple[list[list[str]], tuple[float, float]]:
    """Part 2: rancf and MoorDyn (40 segments, 1e-4 s) in turn; the median process ratio."""
    ra, md, ratios = [], [], []
    for _ in range(a.pairs):
        ra.append(run_rancf(HERE / a.scenario, tmp / "run"))
        t0, cpu0 = time.perf_counter(), children_cpu()
        out, _ = peer(a.peer_python, "moordyn_surge.py", "--segments", "40", "--dt", "1e-4")
        out["wall"], out["cpu"] = time.perf_counter() - t0, children_cpu() - cpu0
        md.append(out)
        ratios.append((ra[-1]["wall"] / md[-1]["wall"], ra[-1]["cpu"] / md[-1]["cpu"]))

    def med(runs: list[dict], key: str) -> float:
        return statistics.median(r[key] for r in runs)

    rows = [
        [
            "code",
            "set-up [s]",
            "of it the static state [s]",
            "solve [s]",
            "process [s]",
            "process CPU [s]",
        ]
    ]
    rows.append(
        [
            f"rancf {a.scenario}",
            f"{med(ra, 'setup'):.3f}",
            f"{med(ra, 'static'):.3f}",
            f"{med(ra, 'solve'):.3f}",
            f"{med(ra, 'wall'):.3f}",
            f"{med(ra, 'cpu'):.3f}",
        ]
    )
    rows.append(
        [
            "MoorDyn 40 segments, 1e-4 s",
            f"{med(md, 'init_s'):.3f}",
            f"{med(md, 'init_s'):.3f}",
            f"{med(md, 'solve_s'):.3f}",
            f"{med(md, 'wall'):.3f}",
            f"{med(md, 'cpu'):.3f}",
        ]
    )
    return rows, (statistics.median(r[0] for r in ratios), statistics.median(r[1] for r in ratios))


def per_iteration(a: argparse.Namespace, tmp: Path) -> list[list[str]]:
    """Part 3: a full-Newton iteration with fluid and seabed against a plain cable's."""
    rows = [["elements", "plain cable [us/it.]", "fluid + seabed [us/it.]", "ratio (median)"]]
    base = (HERE / a.scenario).read_text()
    for n in a.iteration_elements:
        full = variant(base, elements=str(n), newton='"full"', t_end="20.0", step="0.1")
        files = {"plain": tmp / f"plain{n}.toml", "fluid": tmp / f"fluid{n}.toml"}
        files["plain"].write_text(plain(full))
        files["fluid"].write_text(full)
        per: dict[str, list[float]] = {"plain": [], "fluid": []}
        for _ in range(a.pairs):
            for k, f in files.items():
                r = run_rancf(f, tmp / f"it-{k}")
                per[k].append(r["solve"] / r["iterations"])
        ratio = statistics.median(f / p for f, p in zip(per["fluid"], per["plain"], strict=True))
        rows.append(
            [
                str(n),
                f"{1e6 * statistics.median(per['plain']):.1f}",
                f"{1e6 * statistics.median(per['fluid']):.1f}",
                f"{ratio:.2f}",
            ]
        )
    return rows


def phases(a: argparse.Namespace) -> list[list[str]]:
    """Part 4: the set-up's phases in fresh processes (medians)."""
    env = {**os.environ, "OPENBLAS_NUM_THREADS": "1"}
    modules: list[str] = []
    runs = []
    for i in range(a.pairs + 3):  # the first run finds the modules the others import first
        out = subprocess.run(
            [sys.executable, "-c", PHASES, str(HERE / a.scenario), json.dumps(modules)],
            env=env,
            check=True,
            capture_output=True,
            text=True,
        ).stdout
        got = json.loads(out.strip().splitlines()[-1])
        if i == 0:
            modules = got["modules"]
        else:
            runs.append(got)
    keys = ("imports", "read", "build", "static")
    rows = [
        ["", "imports [s]", "read [s]", "build [s]", "static state [s]", "set-up but imports [s]"]
    ]
    for label, suffix in (("wall", ""), ("CPU", " cpu")):
        med = {k: statistics.median(r[k + suffix] for r in runs) for k in keys}
        rest = med["read"] + med["build"] + med["static"]
        rows.append([label] + [f"{med[k]:.4f}" for k in keys] + [f"{rest:.4f}"])
    return rows


def main() -> None:
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--pairs", type=int, default=3)
    p.add_argument("--peer-python", default=sys.executable)
    p.add_argument("--scenario", default="mooring-surge-fast.toml")
    p.add_argument("--iteration-elements", type=int, nargs="*", default=[20, 80])
    p.add_argument("--skip-accuracy", action="store_true")
    p.add_argument(
        "--scan",
        nargs="*",
        default=["20:0.1", "20:0.25", "16:0.2", "12:0.1", "12:0.2", "10:0.1"],
        metavar="ELEMENTS:STEP",
        help="the scenario also with these element counts and steps (accuracy only)",
    )
    a = p.parse_args()
    load0 = os.getloadavg()[0]
    with tempfile.TemporaryDirectory() as tmp:
        tmpd = Path(tmp)
        if not a.skip_accuracy:
            print(table(accuracy(a, tmpd)), "\n", flush=True)
        rows, ratio = whole_runs(a, tmpd)
        print(table(rows))
        print(
            f"whole run rancf / MoorDyn, medians of {a.pairs} pairs: wall {ratio[0]:.3f}, "
            f"CPU {ratio[1]:.3f}\n"
        )
        print(table(per_iteration(a, tmpd)), "\n", flush=True)
    print(table(phases(a)))
    print(f"\nrancf {version('rancf')}; {machine()}, {load0:.1f} at the start")


if __name__ == "__main__":
    main()
