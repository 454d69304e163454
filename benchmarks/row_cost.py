"""What a stored row costs, part by part, against what a step costs: the straight pendulum of
`cli_cases.py` stored every step, its rows derived again in one process as a run derives them.

    python benchmarks/row_cost.py [--elements 8 32 128 512] [--repeats 5]

For each size: `rancf simulate` with output every 10 ms gives the loop's time a step
(``solve_wall_time_s / steps``, the best of ``--repeats`` runs: a step with next to nothing
stored; wall time, which on a shared core counts the other processes' turns too:
`step_cpu.py` has the CPU time a step); one with the default output
(every step) gives the stored states.  Those states are then handed, in blocks of the size the run
folder uses (:data:`rancf.post.history.WORKER_BLOCK_ROWS`, fewer for a large model), to what a
run derives from them: the energies (``energies_rows``), and
:meth:`rancf.system.outputs.SystemOutputs.rows`, whose parts are timed on their own (CPU time of
this process, the best of ``--repeats`` passes over all the rows): the consistent accelerations,
multipliers and reactions (:func:`rancf.system.output_block.block_derived`: a force pass and a
band solve a row), the section strains and curvatures (``SectionSampler.raw``), the nodal axial
forces, the section forces and moments (``SectionSampler.from_raw``), the bodies' energies
(``body_energies_rows``, where the system has more than one body: in the rest), the sensors,
and the rest of ``rows`` (NumPy around the calls).  The
files' writing at the end of a run is not included.  Prints one row a size (µs a stored row)
and the JSON of all of them.
"""

from __future__ import annotations

import argparse
import contextlib
import importlib
import json
import shutil
import subprocess
import sys
import tempfile
import time
from collections.abc import Callable, Iterator
from pathlib import Path
from typing import Any

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent))
from cli_cases import SCENARIO  # noqa: E402

#: (label, module, class or "", attribute): the parts of a block's derivation, each timed
#: where it is called.
PARTS = (
    ("accelerations, reactions", "rancf.system.outputs", "", "block_derived"),
    ("section strains", "rancf.bodies.section_outputs", "SectionSampler", "raw"),
    ("nodal axial forces", "rancf.system.output_block", "", "nodal_axial_forces"),
    ("section forces", "rancf.bodies.section_outputs", "SectionSampler", "from_raw"),
    ("sensors", "rancf.system.sensors", "SensorReader", "values"),
)


def _simulate(scenario: Path, out: Path) -> dict[str, Any]:
    shutil.rmtree(out, ignore_errors=True)
    cmd = [sys.executable, "-m", "rancf", "simulate", str(scenario), "--out", str(out)]
    subprocess.run([*cmd, "--quiet", "--threads", "1"], check=True, capture_output=True)
    return json.loads((out / "summary.json").read_text())


@contextlib.contextmanager
def _timed(spent: dict[str, float]) -> Iterator[None]:
    """Wrap every part of :data:`PARTS` to add its CPU time to ``spent``."""
    saved = []
    for label, module, cls, name in PARTS:
        owner = importlib.import_module(module)
        owner = getattr(owner, cls) if cls else owner
        fn = getattr(owner, name)

        def wrap(*a: Any, _fn: Callable = fn, _label: str = label, **k: Any) -> Any:
            t0 = time.process_time()
            try:
                return _fn(*a, **k)
            finally:
                spent[_label] = spent.get(_label, 0.0) + time.process_time() - t0

        saved.append((owner, name, fn))
        setattr(owner, name, wrap)
    try:
        yield
    finally:
        for owner, name, fn in saved:
            setattr(owner, name, fn)


def _derive(plan: Any, rows: dict[str, Any], block: int) -> dict[str, float]:
    """One pass over the stored rows in blocks, as a run folder derives them: CPU time of each
    part [s]."""
    outputs = plan.outputs
    s = outputs.system
    t, q, v = rows["t"], rows["q"], rows["v"]
    spent: dict[str, float] = {}
    with _timed(spent):
        t_all = time.process_time()
        for i in range(0, t.size, block):
            sl = slice(i, min(t.size, i + block))
            k = sl.stop - sl.start
            t0 = time.process_time()
            e = np.empty((k, 3))
            ys, vs = s.y_from_q(q[sl]), s.y_from_q(v[sl])
            s.core.energies_rows(t[sl], np.ascontiguousarray(ys), np.ascontiguousarray(vs), e)
            spent["energies"] = spent.get("energies", 0.0) + time.process_time() - t0
            outputs.rows(t[sl], q[sl], v[sl], None, e, per_body=True)
        total = time.process_time() - t_all
    spent["rest of rows"] = total - sum(spent.values())
    spent["total"] = total
    return spent


def measure(n: int, t_end: float, repeats: int, tmp: Path) -> dict[str, Any]:
    """The figures of one size: µs a step (output every 10 ms) and µs a stored row by part."""
    from rancf.post.history import WORKER_BLOCK_BYTES, WORKER_BLOCK_ROWS
    from rancf.runs.simulate import plan_simulate
    from rancf.scenario.scenario import load_scenario

    files = {}
    for key, out in (("ten", "output_step = 0.01\n"), ("every", "")):
        files[key] = tmp / f"{key}{n}.toml"
        files[key].write_text(SCENARIO.format(n=n, t_end=t_end, out=out, newton=""))
    ten = [_simulate(files["ten"], tmp / "run") for _ in range(repeats)]
    step_us = min(1e6 * r["solve_wall_time_s"] / r["steps"] for r in ten)
    _simulate(files["every"], tmp / "run")
    with np.load(tmp / "run" / "results.npz") as z:
        rows = {k: np.ascontiguousarray(z[k]) for k in ("t", "q", "v")}
    plan = plan_simulate(load_scenario(files["every"]))
    n_q = plan.outputs.n_q
    block = max(1, min(WORKER_BLOCK_ROWS, WORKER_BLOCK_BYTES // (16 * n_q + 32)))
    best: dict[str, float] = {}
    for _ in range(repeats):
        spent = _derive(plan, rows, block)
        if not best or spent["total"] < best["total"]:
            best = spent
    k = rows["t"].size
    per_row = {label: 1e6 * sec / k for label, sec in best.items()}
    return {
        "elements": n,
        "step wall µs (every 10 ms)": step_us,
        "rows": k,
        "block": block,
        **per_row,
    }


def main(argv: list[str] | None = None) -> list[dict[str, Any]]:
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--elements", type=int, nargs="+", default=[8, 32, 128, 512])
    p.add_argument("--t-end", type=float, default=0.3)
    p.add_argument("--repeats", type=int, default=5)
    a = p.parse_args(argv)
    report = []
    with tempfile.TemporaryDirectory() as tmp:
        for n in a.elements:
            r = measure(n, a.t_end, a.repeats, Path(tmp))
            report.append(r)
            parts = "  ".join(
                f"{k} {v:.1f}" for k, v in r.items() if k not in ("elements", "rows", "block")
            )
            print(f"{n:4d} elements, µs: {parts}")
    print(json.dumps(report))
    return report


if __name__ == "__main__":
    main()
