"""A winch paying out a cable with a 10 kg load side by side: MoorDyn 2.7's variable unstretched
length and rancf's ``[[winches]]``, in one run.

    python benchmarks/mooring/compare_payout.py [--peer-python PYTHON] [--segments N]

rancf runs ``payout.toml`` (``rancf simulate FILE --out DIR --quiet``); the winch tension is the
``drum_tension`` column of its ``winch`` sensor.  MoorDyn runs ``moordyn_payout.py``'s model at
``--segments`` (default 20, step 2e-4 s / N) in the same run (``--peer-python``: an interpreter
with ``moordyn==2.7.*`` and scipy), and its converged answer is the stored
``results/moordyn_payout.csv``.  The issue asks for the end tension within 3 %: compared every
0.1 s over the whole run (0 to 12 s), relative to MoorDyn's converged tension.  Also the length
rancf reports against the law, and the load's position against -L(t) (the static stretch is
below 0.1 mm).  Prints a table (steps, elements / segments, wall times, differences) and the CPU.
Exit status 1 when rancf fails or misses 3 %.
"""

from __future__ import annotations

import argparse
import json
import sys
import tempfile
import tomllib
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))

from common import HERE, RESULTS, failed, peer, rancf, read_series, table  # noqa: E402
from provenance import machine, version  # noqa: E402

TOLERANCE, EVERY = 0.03, 0.1


def on_grid(times: list[float], values: list[float], grid: list[float]) -> list[float]:
    """``values`` linearly interpolated at the times of ``grid``."""
    out, j = [], 0
    for t in grid:
        while j + 2 < len(times) and times[j + 1] < t:
            j += 1
        t0, t1 = times[j], times[j + 1]
        w = min(max((t - t0) / (t1 - t0), 0.0), 1.0)
        out.append(values[j] + w * (values[j + 1] - values[j]))
    return out


def worst(got: list[float], ref: list[float], grid: list[float]) -> tuple[float, float]:
    return max((abs(g - r) / r, t) for g, r, t in zip(got, ref, grid, strict=True))


def main() -> None:
    p = argparse.ArgumentParser()
    p.add_argument("--peer-python", default=sys.executable)
    p.add_argument("--segments", type=int, default=20)
    p.add_argument("--reference", type=Path, default=RESULTS / "moordyn_payout.csv")
    a = p.parse_args()
    ref = read_series(a.reference)
    grid = [round(i * EVERY, 9) for i in range(round(ref["t_s"][-1] / EVERY) + 1)]
    ref_t = on_grid(ref["t_s"], ref["winch_tension_N"], grid)
    scenario = tomllib.loads((HERE / "payout.toml").read_text())
    elements = scenario["bodies"][0]["mesh"]["elements"]
    step = scenario["solver"]["step"]
    rows = [
        [
            "code",
            "step [s]",
            "elements / segments",
            "set-up [s]",
            "solve [s]",
            "process [s]",
            "max |dT|/T",
            "at t [s]",
            "max |z + L| [mm]",
        ]
    ]
    ok = False
    with tempfile.TemporaryDirectory() as tmp:
        out = Path(tmp) / "run"
        proc, wall = rancf("simulate", str(HERE / "payout.toml"), "--out", str(out), "--quiet")
        if proc.returncode == 0:
            summary = json.loads((out / "summary.json").read_text())
            s = read_series(out / "sensors.csv")
            got = on_grid(s["t"], s["drum_tension"], grid)
            err, at = worst(got, ref_t, grid)
            ok = err <= TOLERANCE
            z = [abs(y + ln) for y, ln in zip(s["load_y"], s["drum_length"], strict=True)]
            rows.append(
                [
                    "rancf",
                    f"{step:g}",
                    str(elements),
                    f"{summary['setup_wall_time_s']:.2f}",
                    f"{summary['solve_wall_time_s']:.2f}",
                    f"{wall:.2f}",
                    f"{err:.2e}",
                    f"{at:g}",
                    f"{1e3 * max(z):.3f}",
                ]
            )
        else:
            rows.append(
                [
                    "rancf",
                    f"{step:g}",
                    str(elements),
                    "-",
                    "-",
                    f"{wall:.2f}",
                    f"failed: {failed(proc)}",
                    "-",
                    "-",
                ]
            )
        csv_path = Path(tmp) / "md"
        md, md_wall = peer(
            a.peer_python,
            "moordyn_payout.py",
            "--segments",
            str(a.segments),
            "--single",
            "--out",
            str(csv_path),
        )
        s = read_series(csv_path / "moordyn_payout.csv")
    md_err, md_at = worst(on_grid(s["t_s"], s["winch_tension_N"], grid), ref_t, grid)
    z = [abs(zz + ln) for zz, ln in zip(s["load_z_m"], s["length_m"], strict=True)]
    run = md["runs"][0]
    rows.append(
        [
            f"MoorDyn {md['versions']['moordyn']}",
            f"{run['dt_s']:g}",
            str(a.segments),
            f"{run['setup_s']:.2f}",
            f"{run['solve_s']:.2f}",
            f"{md_wall:.2f}",
            f"{md_err:.2e}",
            f"{md_at:g}",
            f"{1e3 * max(z):.3f}",
        ]
    )
    print(table(rows))
    print(
        f"\nreference: {a.reference.name} (MoorDyn, converged); rancf {version('rancf')}; "
        f"{machine()}"
    )
    sys.exit(0 if ok else 1)


if __name__ == "__main__":
    main()
