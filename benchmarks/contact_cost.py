"""Contact benchmarks: contact through `rancf simulate`, side by side with Exudyn.

    python benchmarks/contact_cost.py [--repeats N] [--out DIR] [--no-exudyn]

* ``ground``: a 1000-element steel cable (10 m, radius 2 mm) lying on the ground (a plane
  obstacle, no support) against the same cable hanging free from a pin (no obstacle), 200 steps
  of 1 ms, rho_inf = 0.5, both through ``rancf simulate`` as whole processes: per-step solve
  time from each run's ``summary.json``, Newton iterations per step, their ratio pair by pair
  (the issue asks for at most 1.5).
* ``circle``: a 2 m steel cable of 40 elements pinned at one end falls onto a fixed circle
  (frictionless, penalty 1e7 N/m^2 in both codes, no damping), 1 s in 1 ms steps, rho_inf =
  0.6: rancf's contact along the curve (8 Gauss points per element) through ``rancf simulate``
  against Exudyn's ``ObjectContactFrictionCircleCable2D`` (8 contact segments per element,
  ``exudyn_contact_circle.py``, its faster linear solver for the case) as whole processes;
  per-step solve time and set-up time (process start to the first step) of each, and the
  tips' final positions.

* ``broad phase``: self-contact detection (broad and narrow phase, ``Contact.body_outputs``) of
  a straight cable of 500 to 4000 elements (1 cm each): time per evaluation, to show it grows
  near linearly with the elements (Python API, median of 5).

Pairs run in turn (A B A B ...), ratios taken pair by pair, medians quoted.  Writes
``contact_bench.json`` to ``--out`` (default ``benchmarks/results``) and prints a table.
"""

from __future__ import annotations

import argparse
import json
import sys
import tempfile
from pathlib import Path
from typing import Any

import numpy as np

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE))

import exudyn_cases as ex  # noqa: E402
from system_cases import _pairs, run_exudyn, run_rancf  # noqa: E402

CABLE = """
[geometry]
kind = "line"
start = [{x0}, {y0}]
end = [{x1}, {y1}]
[mesh]
elements = {n}
[section]
radius = 0.002
[material]
density = 7850.0
youngs_modulus = 2.0e11
[loads]
gravity = [0.0, -9.81]
[solver]
t_end = {t_end}
step = 1.0e-3
output_step = {t_end}
rho_inf = {rho}
max_newton = 25
"""

GROUND = """
[[obstacles]]
name = "ground"
kind = "plane"
point = [0.0, 0.0]
normal = [0.0, 1.0]
"""

PIN = """
[[supports]]
at = "start"
kind = "pin"
"""

CIRCLE = """
[[obstacles]]
name = "disc"
kind = "cylinder"
center = [1.0, -0.3]
radius = 0.2
stiffness = 1.0e7
"""


def ground_files(tmp: Path, n: int) -> tuple[Path, Path]:
    """The cable lying on the ground and the same cable hanging from a pin."""
    lying, hanging = tmp / "lying.toml", tmp / "hanging.toml"
    lying.write_text(
        CABLE.format(x0=0, y0=0.002, x1=10.0, y1=0.002, n=n, t_end=0.2, rho=0.5) + GROUND
    )
    hanging.write_text(CABLE.format(x0=0, y0=0, x1=0, y1=-10.0, n=n, t_end=0.2, rho=0.5) + PIN)
    return lying, hanging


def circle_file(tmp: Path, n: int, t_end: float = 1.0) -> Path:
    f = tmp / "circle.toml"
    f.write_text(CABLE.format(x0=0, y0=0, x1=2.0, y1=0, n=n, t_end=t_end, rho=0.6) + PIN + CIRCLE)
    return f


def _tip(run: Path) -> list[float]:
    with np.load(run / "results.npz") as z:
        q = z["q"][-1]
    dpn = 4
    return [float(q[-dpn]), float(q[-dpn + 1])]


def broad_phase() -> dict[str, float]:
    """Milliseconds per self-contact evaluation of a straight cable by its element count."""
    import statistics
    import time

    from rancf.bodies.flexible import Material, Model, Section
    from rancf.mesh.factories import mesh_line
    from rancf.system import System

    out: dict[str, float] = {}
    for n in (500, 1000, 2000, 4000):
        m = Model(
            mesh_line([0, 0], [0.01 * n, 0], n),
            "rancf",
            Section.circular(0.002),
            Material(7850.0, 2e11),
        )
        s = System({"c": m}, body_contacts=[("c", "c")])
        vals = np.empty(3)
        times = []
        for _ in range(5):
            t0 = time.perf_counter()
            s.contact.body_outputs(s.y0, vals)
            times.append(time.perf_counter() - t0)
        out[str(n)] = 1e3 * statistics.median(times)
    return out


def cases(
    repeats: int, n_ground: int, n_circle: int, t_circle: float, exudyn: bool
) -> dict[str, Any]:
    """The ground and circle cases (module docstring), keyed by their names."""
    rows: dict[str, Any] = {}
    with tempfile.TemporaryDirectory() as tmp:
        tmpd = Path(tmp)
        lying, hanging = ground_files(tmpd, n_ground)
        key = f"ground {n_ground} el: lying vs hanging"
        rows[key] = _pairs(
            lambda: run_rancf(lying, tmpd / "lying"),
            lambda: run_rancf(hanging, tmpd / "hang"),
            repeats,
        )
        for side, run in (("lying", "lying"), ("hanging", "hang")):
            s = json.loads((tmpd / run / "summary.json").read_text())
            rows[key][f"{side}_newton_per_step"] = s["newton_iterations"] / s["steps"]
        if exudyn:
            circle = circle_file(tmpd, n_circle, t_circle)
            args = ["--elements", str(n_circle), "--t-end", str(t_circle)]
            trial = {
                v: run_exudyn(
                    "exudyn_contact_circle.py", [*args[:2], "--t-end", "0.2", "--solver", v]
                )["solve_s"]
                for v in ("dense", "sparse")
            }
            solver = min(trial, key=trial.get)  # Exudyn's faster linear solver for the case
            last: dict[str, Any] = {}

            def exu_run() -> dict[str, Any]:
                last.update(run_exudyn("exudyn_contact_circle.py", [*args, "--solver", solver]))
                return last

            row = _pairs(lambda: run_rancf(circle, tmpd / "circle"), exu_run, repeats)
            row.update(
                {
                    "exudyn_solver": solver,
                    "exudyn_version": ex.VERSION,
                    "rancf_tip": _tip(tmpd / "circle"),
                    "exudyn_tip": last["tip"],
                }
            )
            rows[f"circle {n_circle} el vs Exudyn"] = row
    return rows


def measure(repeats: int, quick: bool, exudyn: bool) -> list[dict[str, Any]]:
    """Rows of benchmarks/run.py: the ground case (A lying, B hanging) and the circle case
    (A rancf, B Exudyn), per-step times through whole processes."""
    got = cases(repeats, 100 if quick else 1000, 10 if quick else 40, 0.1 if quick else 1.0, exudyn)
    rows = []
    for name, r in got.items():
        ground = name.startswith("ground")
        row = {
            "case": f"contact: {name}" + (" (B: hanging)" if ground else ""),
            "rancf_us_per_step": r["a_us_per_step"],
            "ratio": r["ratio"],
            "rancf_setup_s": r["a_setup_s"],
            "steps": r["steps"][0],
        }
        row["hanging_us_per_step" if ground else "exudyn_us_per_step"] = r["b_us_per_step"]
        if not ground:
            row.update(
                {
                    "exudyn_setup_s": r["b_setup_s"],
                    "rancf_tip": r["rancf_tip"],
                    "exudyn_tip": r["exudyn_tip"],
                }
            )
        rows.append(row)
    return rows


def main() -> None:
    p = argparse.ArgumentParser()
    p.add_argument("--repeats", type=int, default=5)
    p.add_argument("--out", default=str(HERE / "results"))
    p.add_argument("--no-exudyn", action="store_true")
    p.add_argument("--broad-only", action="store_true", help="only the broad phase's scaling")
    a = p.parse_args()
    out = Path(a.out)
    out.mkdir(parents=True, exist_ok=True)
    broad = broad_phase()
    print("self-contact evaluation, ms by elements:", broad)
    if a.broad_only:
        old = out / "contact_bench.json"
        rows0 = json.loads(old.read_text()) if old.is_file() else {}
        rows0["broad phase ms by elements"] = broad
        old.write_text(json.dumps(rows0, indent=2, allow_nan=False) + "\n")
        return
    rows: dict[str, Any] = {"broad phase ms by elements": broad}
    rows.update(cases(a.repeats, 1000, 40, 1.0, ex.AVAILABLE and not a.no_exudyn))
    (out / "contact_bench.json").write_text(json.dumps(rows, indent=2, allow_nan=False) + "\n")
    print(f"{'case':34s} {'A us/step':>10s} {'B us/step':>10s} {'ratio':>7s} {'setup A/B s':>14s}")
    for name, r in rows.items():
        if "a_us_per_step" not in r:
            continue
        print(
            f"{name:34s} {r['a_us_per_step']:10.1f} {r['b_us_per_step']:10.1f} "
            f"{r['ratio']:7.3f} {r['a_setup_s']:7.3f}/{r['b_setup_s']:.3f}"
        )


if __name__ == "__main__":
    main()
