"""Benchmark runner: rancf against Exudyn, side by side in one run.

    python benchmarks/run.py [--out DIR] [--repeats N] [--quick] [--install]

Prints a table and writes ``bench.csv`` and ``bench.json`` to ``--out`` (default
``benchmarks/results``).  Without Exudyn installed (``pip install .[bench]``) only rancf's own
cases are timed.  A ratio is rancf / Exudyn, the median of per-pair ratios (A B A B ...);
below 1 means rancf is faster.

* ``simulate pendulum N el``: the straight pendulum through ``rancf simulate`` as a whole process
  (see ``cli_cases.py``) against ``exudyn_pendulum.py``: per-step solve time from each side's own
  report, set-up time (process start to the first step), whole-process wall time.
* ``static cantilever`` and ``time to 1e-3 m``: the Python API (``solve_static``/``integrate``)
  in this process against Exudyn's ``SolveStatic``/``SolveDynamic``.
* ``static ... catenary``: the static catenaries through ``rancf static --json`` as whole
  processes (``catenary_cases.py``): solve time, Newton iterations, process wall time.
* ``contact: ...``: the contact cases through ``rancf simulate`` (``contact_cost.py``):
  a cable lying on the ground against the same cable hanging free, and a cable falling onto a
  circle against Exudyn's ``ObjectContactFrictionCircleCable2D``.
* ``--install``: the wall time of ``pip wheel`` of this checkout (the C++ core's build).
"""

from __future__ import annotations

import argparse
import csv
import datetime
import json
import platform
import statistics
import sys
import time
from pathlib import Path
from typing import Any

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent))

import catenary_cases  # noqa: E402
import cli_cases  # noqa: E402
import contact_cost  # noqa: E402
import exudyn_cases as ex  # noqa: E402
import rod_cost  # noqa: E402

import rancf  # noqa: E402
from rancf.bodies.flexible import Material, Model, PointLoad, Section, Support  # noqa: E402
from rancf.geometry.conic import conic_arc  # noqa: E402
from rancf.mesh.factories import (
    mesh_conic,
    mesh_line,
    to_ancf,  # noqa: E402
)
from rancf.solvers.dynamic import DynamicOptions, integrate  # noqa: E402
from rancf.solvers.static import solve_static  # noqa: E402

PEND = dict(length=1.2, area=0.0018, inertia=1.215e-8, density=5540.0, youngs=0.7e6)


def _median_time(fn: Any, repeats: int) -> tuple[float, Any]:
    """Median solve time of ``fn() -> (solve wall time, result)`` after one warm-up call."""
    fn()  # warm-up
    times, out = [], None
    for _ in range(repeats):
        wall, out = fn()
        times.append(wall)
    return statistics.median(times), out


def _paired(fa: Any, fb: Any, repeats: int) -> tuple[float, float, float, Any, Any]:
    """A and B in turn (A B A B ...), after one warm-up each.

    Returns median A time, median B time, median of the per-pair ratios A/B, and the results.
    """
    fa()
    fb()
    ta, tb, ratios = [], [], []
    ra = rb = None
    for _ in range(repeats):
        wa, ra = fa()
        wb, rb = fb()
        ta.append(wa)
        tb.append(wb)
        ratios.append(wa / wb)
    return statistics.median(ta), statistics.median(tb), statistics.median(ratios), ra, rb


def _timed(fn: Any, *args: Any, **kw: Any) -> tuple[float, Any]:
    t0 = time.perf_counter()
    out = fn(*args, **kw)
    return time.perf_counter() - t0, out


def static_case(repeats: int) -> dict[str, Any]:
    length, r, e = 0.5, 0.03, 2.0e7
    sec = Section.circular(r)
    force = 3.0 * e * sec.inertia / length**2  # large deflection (tip drops ~60 % of L)

    def ours() -> tuple[float, np.ndarray]:
        m = Model(
            mesh_line([0, 0], [length, 0], 32),
            "ancf",
            sec,
            Material(1.0, e),
            [Support(0, "clamp")],
            point_loads=[PointLoad(-1, (0.0, -force))],
        )
        wall, res = _timed(solve_static, m, 20)
        return wall, m.node_positions(res.q)[-1]

    row: dict[str, Any] = {
        "case": "static cantilever 32 el, 20 load steps",
        "elements": 32,
        "steps": 20,
    }
    if ex.AVAILABLE:
        t_ours, t_ex, ratio, tip, tip_ex = _paired(
            ours,
            lambda: ex.static_cantilever(32, force, 20, length, sec.area, sec.inertia, e),
            repeats,
        )
        row.update(
            exudyn_s=t_ex,
            ratio=ratio,
            exudyn_tip=tip_ex.tolist(),
            tip_difference_m=float(np.linalg.norm(tip - tip_ex)),
        )
    else:
        t_ours, tip = _median_time(ours, repeats)
    row.update(
        rancf_s=t_ours, rancf_tip=tip.tolist(), analytic_small_deflection_note="large deflection"
    )
    return row


def time_to_accuracy(repeats: int, tol: float = 1e-3, t_end: float = 0.5) -> list[dict[str, Any]]:
    """Elliptic-arc pendulum (paper example 1): elements and time to reach ``tol`` at t = 0.5 s.

    Each tool is measured against its own converged reference (64 elements, same time step), so
    only the spatial discretization is compared; the two references are reported too.
    """
    arc = conic_arc(0.5, [30, 40], [0.315, 0.077])
    sec, mat = Section.circular(0.02), Material(6000.0, 2e6)
    step = 1e-3

    def ours(n: int, element: str) -> tuple[float, np.ndarray]:
        mesh = mesh_conic(arc, n)
        m = Model(mesh, element, sec, mat, [Support(0, "pin")], gravity=[0, -9.81])
        opts = DynamicOptions(t_end=t_end, step=step, rho_inf=0.9, output_step=t_end)
        wall, r = _timed(integrate, m, opts)
        return wall, m.node_positions(r.q[-1])[-1]

    def exu_run(n: int) -> tuple[float, np.ndarray]:
        a = to_ancf(mesh_conic(arc, n))
        return ex.curved_pendulum(
            a.nodes[:, 0],
            a.nodes[:, 1],
            a.scales,
            t_end,
            step,
            0.9,
            sec.area,
            sec.inertia,
            mat.density,
            mat.youngs_modulus,
        )

    tools = {
        "rancf RANCF Kopt": lambda n: ours(n, "rancf"),
        "rancf ANCF": lambda n: ours(n, "ancf"),
    }
    if ex.AVAILABLE:
        tools["Exudyn ANCFCable2D (curved reference)"] = exu_run
    rows = []
    refs = {}
    for name, fn in tools.items():
        ref = fn(64)[1]
        refs[name] = ref
        found = None
        for n in range(1, 33):
            if np.linalg.norm(fn(n)[1] - ref) <= tol:
                found = n
                break
        row: dict[str, Any] = {
            "case": f"time to 1e-3 m: {name}",
            "elements": found,
            "reference_tip": ref.tolist(),
        }
        if found is not None:
            t, _ = _median_time(lambda fn=fn, n=found: fn(n), repeats)
            row["wall_s"] = t
        rows.append(row)
    if len(refs) > 1:
        base = refs["rancf RANCF Kopt"]
        for row, (_, ref) in zip(rows, refs.items(), strict=True):
            row["reference_difference_to_rancf_m"] = float(np.linalg.norm(ref - base))
    return rows


def install_case() -> dict[str, Any]:
    """Wall time of building this checkout's wheel (C++ core included) with pip."""
    import subprocess
    import tempfile

    root = Path(__file__).resolve().parents[1]
    with tempfile.TemporaryDirectory() as tmp:
        t0 = time.perf_counter()
        cmd = [sys.executable, "-m", "pip", "wheel", "--no-deps", "-q", "-w", tmp, str(root)]
        subprocess.run(cmd, check=True, capture_output=True)
        wall = time.perf_counter() - t0
    return {"case": "install: pip wheel (build of the core)", "rancf_s": wall}


def main(argv: list[str] | None = None) -> int:
    p = argparse.ArgumentParser(
        description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter
    )
    p.add_argument("--out", default=str(Path(__file__).resolve().parent / "results"))
    p.add_argument("--repeats", type=int, default=5)
    p.add_argument("--quick", action="store_true", help="small sizes, for a smoke test")
    p.add_argument("--install", action="store_true", help="also time the build of the core")
    args = p.parse_args(argv)
    quick = args.quick
    meta = {
        "date": datetime.date.today().isoformat(),
        "machine": f"{platform.processor() or platform.machine()}, {platform.system()}",
        "python": platform.python_version(),
        "rancf": rancf.__version__,
        "numpy": np.__version__,
        "exudyn": ex.VERSION,
    }
    ns = [8] if quick else [8, 32, 128, 512]
    # the default Newton (chord) at the default output (every step) and every 10 ms; full Newton
    rows = cli_cases.simulate_cases(
        ns, [None], args.repeats, 0.05 if quick else 1.0, ex.AVAILABLE, (None, 0.01)
    )
    rows += cli_cases.simulate_cases(
        ns, ["full"], args.repeats, 0.05 if quick else 1.0, ex.AVAILABLE, (0.01,)
    )
    if not quick:  # linear in n: full Newton up to 4096 elements, rancf alone, 0.1 s
        rows += cli_cases.simulate_cases([1024, 2048, 4096], [None], 1, 0.1, False, (0.01,))
    rows.append(static_case(args.repeats))
    rows += catenary_cases.measure(1 if quick else args.repeats)
    rows += rod_cost.measure(8, 5, 5) if quick else rod_cost.measure(64, 300, 500)
    rows += contact_cost.measure(1 if quick else args.repeats, quick, ex.AVAILABLE)
    if not quick:
        rows += time_to_accuracy(args.repeats)
    if args.install:
        rows.append(install_case())
    out = Path(args.out)
    out.mkdir(parents=True, exist_ok=True)
    keys = sorted({k for r in rows for k in r}, key=lambda k: (k != "case", k))
    with open(out / "bench.csv", "w", newline="") as fh:
        w = csv.DictWriter(fh, fieldnames=keys)
        w.writeheader()
        for r in rows:
            w.writerow({k: json.dumps(v) if isinstance(v, list) else v for k, v in r.items()})
    (out / "bench.json").write_text(json.dumps({"meta": meta, "rows": rows}, indent=2) + "\n")
    print(f"# {meta}")
    print(f"{'case':50s} {'rancf':>12s} {'Exudyn':>12s} {'ratio':>7s} {'process':>8s}")
    for r in rows:
        a = r.get("rancf_us_per_step")
        b = r.get("exudyn_us_per_step")
        if a is not None:
            sa, sb = f"{a:9.1f} us", (f"{b:9.1f} us" if b is not None else "-")
        else:
            sa = f"{r.get('rancf_s', r.get('wall_s', float('nan'))):9.4f} s"
            sb = f"{r['exudyn_s']:9.4f} s" if "exudyn_s" in r else "-"
        if "rod_us" in r:
            sa, sb = f"{r['rod_us']:9.3f} us", f"cable {r['cable_us']:.3f}"
        if "exudyn_failed" in r:
            sb = f"failed {r['exudyn_wall_s']:.0f} s"
        ratio = f"{r['ratio']:7.3f}" if "ratio" in r else "-"
        diff = f"{r['process_ratio']:8.3f}" if "process_ratio" in r else ""
        if "elements" in r and r["case"].startswith("time to"):
            sb = f"{r['elements']} el"
        if "newton_iterations" in r:
            sb = f"{r['newton_iterations']} Newton"
        print(f"{r['case']:50s} {sa:>12s} {sb:>12s} {ratio:>7s} {diff}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
