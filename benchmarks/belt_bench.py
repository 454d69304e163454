"""Belt drives and a coiling rope: contact through `rancf simulate`, side by side with Exudyn.

    python benchmarks/belt_bench.py [--repeats N] [--coil-repeats N] [--out DIR] [--no-coil]

* ``shipped belt vs Exudyn``: the shipped example ``belt-drive.toml`` as it is (96 elements,
  h = 2 ms, 4 s) against Exudyn's belt drive test ``ANCFgeneralContactCircle``
  (``exudyn_belt.py``: 32 ANCF cable elements, general contact with friction, h = 1 ms,
  modified Newton, its test length of 0.1 s).
* ``matched belt vs Exudyn``: ``scenarios/belt-exudyn.toml``, the test's belt in rancf (32
  elements, h = 1 ms, the same materials, contact stiffness, damping and friction; 0.1 s)
  against the same Exudyn run; the wheels' angles at the end of both are recorded.
* ``rope coil``: ``scenarios/rope-coil.toml`` (a 40-element rope collapsing onto itself, with
  self-contact) against the same rope without ``body_contacts``, per step.

Every run is a whole process; solve time from each side's own clock (rancf: ``summary.json``;
Exudyn: ``SolveDynamic``), set-up (process start to the first step) quoted apart, and the
whole process's CPU time (user + system, from the children's resource usage: less sensitive
to other jobs on the machine than the wall clock).  For the coil the start-up's CPU time (the
same rope run for one step, ``--coil-repeats`` times, median) is taken off both processes'
CPU times, giving ``cpu_per_step_ratio``: the solves' CPU time per step, coil over free rope.
The belts
are compared per simulated second (solve time / simulated time), the coil per step.  Runs
alternate (A B A B ...) after one warm-up pair (the coil: no warm-up, ``--coil-repeats``
pairs, 5 by default); ratios are taken pair by pair and their median is
quoted.  Writes ``belt_bench.json`` to ``--out`` (default ``benchmarks/results``) with the CPU's
name and prints a table.
"""

from __future__ import annotations

import argparse
import json
import resource
import statistics
import sys
import tempfile
from importlib import resources
from pathlib import Path
from typing import Any

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE))
sys.path.insert(0, str(HERE / "mooring"))

import exudyn_cases as ex  # noqa: E402
from provenance import cpu_model  # noqa: E402
from system_cases import run_exudyn, run_rancf  # noqa: E402

EXUDYN_T_END = 0.1  # the test's own length


def _sim_time(scenario: Path) -> float:
    import tomllib

    return float(tomllib.loads(scenario.read_text())["solver"]["t_end"])


def _cpu() -> float:
    """User + system CPU time of the finished child processes so far."""
    ru = resource.getrusage(resource.RUSAGE_CHILDREN)
    return ru.ru_utime + ru.ru_stime


def _rancf(scenario: Path, out: Path) -> dict[str, Any]:
    c0 = _cpu()
    got = run_rancf(scenario, out)
    got["cpu_s"] = _cpu() - c0
    got["t_end"] = _sim_time(scenario)
    got["sensors"] = (out / "sensors.csv").read_text().splitlines()[-1]
    return got


def _exudyn(output_step: float) -> dict[str, Any]:
    c0 = _cpu()
    got = run_exudyn(
        "exudyn_belt.py", ["--t-end", str(EXUDYN_T_END), "--output-step", str(output_step)]
    )
    got["cpu_s"] = _cpu() - c0
    got["t_end"] = EXUDYN_T_END
    return got


def _pairs(fa: Any, fb: Any, repeats: int, per: str, warm: bool = True) -> dict[str, Any]:
    """Interleaved runs; ``per`` "second" (solve / simulated time) or "step"."""
    if warm:
        fa(), fb()
    a, b = [], []
    for _ in range(repeats):
        a.append(fa())
        b.append(fb())

    def cost(x: dict[str, Any]) -> float:
        return x["solve_s"] / (x["t_end"] if per == "second" else x["steps"])

    med = statistics.median
    return {
        f"a_s_per_{per}": med([cost(x) for x in a]),
        f"b_s_per_{per}": med([cost(y) for y in b]),
        "a_cpu_s": med([x["cpu_s"] for x in a]),
        "b_cpu_s": med([y["cpu_s"] for y in b]),
        "a_setup_s": med([x["setup_s"] for x in a]),
        "b_setup_s": med([y["setup_s"] for y in b]),
        "a_steps": a[-1]["steps"],
        "b_steps": b[-1]["steps"],
        "a_newton": a[-1].get("newton"),
        "b_newton": b[-1].get("newton"),
        "ratio": med([cost(x) / cost(y) for x, y in zip(a, b, strict=True)]),
        "ratios": [cost(x) / cost(y) for x, y in zip(a, b, strict=True)],
        "a_last": {k: a[-1][k] for k in ("sensors", "angles", "rates") if k in a[-1]},
        "b_last": {
            k: b[-1][k] for k in ("sensors", "angles", "rates", "node0_x_plus_y") if k in b[-1]
        },
    }


def cases(repeats: int, coil_repeats: int, coil: bool) -> dict[str, Any]:
    """The three comparisons (module docstring), keyed by their names."""
    rows: dict[str, Any] = {}
    shipped = Path(str(resources.files("rancf.examples") / "belt-drive.toml"))
    matched = HERE / "scenarios" / "belt-exudyn.toml"
    with tempfile.TemporaryDirectory() as tmp:
        tmpd = Path(tmp)
        if ex.AVAILABLE:
            rows["shipped belt vs Exudyn"] = _pairs(
                lambda: _rancf(shipped, tmpd / "shipped"),
                lambda: _exudyn(0.02),
                repeats,
                "second",
            )
            rows["matched belt vs Exudyn"] = _pairs(
                lambda: _rancf(matched, tmpd / "matched"),
                lambda: _exudyn(0.01),
                repeats,
                "second",
            )
        if coil:
            with_self = HERE / "scenarios" / "rope-coil.toml"
            without = tmpd / "rope-fall.toml"
            text = with_self.read_text()
            without.write_text(text.replace('body_contacts = [["body", "body"]]\n', ""))
            row = _pairs(
                lambda: _rancf(with_self, tmpd / "coil"),
                lambda: _rancf(without, tmpd / "fall"),
                coil_repeats,
                "step",
                warm=False,
            )
            # the start-up's CPU time: the same rope for one step; the rest is the solve's
            start = tmpd / "rope-start.toml"
            one = text.replace("t_end = 0.6\n", "t_end = 0.001\n")
            start.write_text(one.replace("output_step = 0.01\n", "output_step = 0.001\n"))
            s0 = statistics.median(
                _rancf(start, tmpd / f"start{k}")["cpu_s"] for k in range(coil_repeats)
            )
            row["startup_cpu_s"] = s0
            row["cpu_per_step_ratio"] = ((row["a_cpu_s"] - s0) / row["a_steps"]) / (
                (row["b_cpu_s"] - s0) / row["b_steps"]
            )
            rows["rope coil: self-contact vs none"] = row
    return rows


def main() -> None:
    p = argparse.ArgumentParser()
    p.add_argument("--repeats", type=int, default=5)
    p.add_argument("--coil-repeats", type=int, default=5)
    p.add_argument("--out", default=str(HERE / "results"))
    p.add_argument("--no-coil", action="store_true")
    a = p.parse_args()
    out = Path(a.out)
    out.mkdir(parents=True, exist_ok=True)
    rows: dict[str, Any] = {"cpu": cpu_model(), "exudyn_version": ex.VERSION}
    rows.update(cases(a.repeats, a.coil_repeats, not a.no_coil))
    (out / "belt_bench.json").write_text(json.dumps(rows, indent=2, allow_nan=False) + "\n")
    print(f"CPU: {rows['cpu']}")
    print(
        f"{'case':34s} {'A':>10s} {'B':>10s} {'ratio':>7s} {'setup A/B s':>14s} {'CPU A/B s':>14s}"
    )
    for name, r in rows.items():
        if not isinstance(r, dict):
            continue
        if "cpu_per_step_ratio" in r:
            print(f"{name}: CPU per step (start-up taken off) ratio {r['cpu_per_step_ratio']:.3f}")
        per = "second" if "a_s_per_second" in r else "step"
        unit = "s/sim-s" if per == "second" else "ms/step"
        scale = 1.0 if per == "second" else 1e3
        ca, cb = scale * r[f"a_s_per_{per}"], scale * r[f"b_s_per_{per}"]
        print(
            f"{name:34s} {ca:10.4g} {cb:10.4g} {r['ratio']:7.3f} "
            f"{r['a_setup_s']:7.3f}/{r['b_setup_s']:.3f} {r['a_cpu_s']:7.3f}/{r['b_cpu_s']:.3f}"
            f"  ({unit})"
        )


if __name__ == "__main__":
    main()
