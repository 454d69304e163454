"""MoorDyn's convergence for the surging chain (``moordyn_surge.py``): segments and time step.

    python benchmarks/mooring/moordyn_convergence.py [--segments 20 40 80 160 320]
        [--step-check 160] [--t-end 60]

Runs MoorDyn at each segment count N with its step 0.04 s / N, and N = ``--step-check`` again
with half that step (its difference to the full step is the time-step error); compares every
fairlead tension series with the finest N's after the first period
(t >= 20 s, once a second) and reports the largest relative difference, MoorDyn's set-up and
solve wall time.  Writes ``results/moordyn_surge.csv`` (the finest run's series) and
``results/moordyn_surge.json`` (the study, the command, versions and CPU).
"""

from __future__ import annotations

import argparse
import json
import sys
from pathlib import Path

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE))

from moordyn_surge import PERIOD, T_END, default_step, simulate, write_csv  # noqa: E402
from provenance import provenance  # noqa: E402

RESULTS = HERE / "results"


def seconds(r, t_from: float) -> dict[float, float]:
    """The fairlead tension once a second from ``t_from`` on."""
    out = {}
    for t, v in zip(r.times, r.columns["tension_N"], strict=True):
        if t >= t_from - 1e-9 and abs(t - round(t)) < 1e-6:
            out[round(t)] = v
    return out


def main() -> None:
    p = argparse.ArgumentParser()
    p.add_argument("--segments", type=int, nargs="+", default=[20, 40, 80, 160, 320])
    p.add_argument("--step-check", type=int, default=160, help="N run again at half the step")
    p.add_argument("--t-end", type=float, default=T_END)
    p.add_argument("--out", type=Path, default=RESULTS)
    a = p.parse_args()
    plan = [(n, default_step(n)) for n in sorted(a.segments)]
    plan.append((a.step_check, default_step(a.step_check) / 2))
    runs = []
    for n, dt in plan:
        r = simulate(n, dt, a.t_end)
        runs.append((n, dt, r))
        print(
            f"MoorDyn {n:4d} segments, dt {dt:.3g} s: set-up {r.init_s:.2f} s, solve "
            f"{r.solve_s:.2f} s",
            file=sys.stderr,
            flush=True,
        )
    ref_n, ref_dt, ref = next(r for r in runs if r[0] == max(a.segments))
    half = seconds(runs[-1][2], PERIOD)
    full = seconds(next(r for r in runs if r[0] == a.step_check)[2], PERIOD)
    step_error = max(abs(full[t] - half[t]) / half[t] for t in half)
    ref_s = seconds(ref, PERIOD)
    rows = []
    for n, dt, r in runs:
        s = seconds(r, PERIOD)
        err = max(abs(s[t] - ref_s[t]) / ref_s[t] for t in ref_s)
        rows.append(
            {
                "segments": n,
                "dt_s": dt,
                "setup_s": r.init_s,
                "solve_s": r.solve_s,
                "max_rel_diff_to_reference": err,
                "tension_max_N": max(r.columns["tension_N"]),
                "tension_min_N": min(r.columns["tension_N"]),
            }
        )
    a.out.mkdir(parents=True, exist_ok=True)
    write_csv(a.out / "moordyn_surge.csv", ref)
    study = {
        **provenance("moordyn", "moorpy", "numpy"),
        "reference": {"segments": ref_n, "dt_s": ref_dt},
        "compared": f"fairlead tension once a second for t >= {PERIOD} s",
        "step_check": {"segments": a.step_check, "max_rel_diff_full_to_half_step": step_error},
        "runs": rows,
    }
    (a.out / "moordyn_surge.json").write_text(json.dumps(study, indent=1) + "\n")
    print(f"{'segments':>8} {'dt [s]':>9} {'set-up [s]':>10} {'solve [s]':>9} {'max diff':>9}")
    for r in rows:
        print(
            f"{r['segments']:8d} {r['dt_s']:9.3g} {r['setup_s']:10.2f} {r['solve_s']:9.2f} "
            f"{r['max_rel_diff_to_reference']:9.2e}"
        )
    print(
        f"time step: {a.step_check} segments, step {default_step(a.step_check):.3g} s against "
        f"half of it: {step_error:.2e}"
    )


if __name__ == "__main__":
    main()
