"""A winch paying out a steel cable with a 10 kg load, in MoorDyn 2.7 (the peer of
``rancf simulate payout.toml``).

    python benchmarks/mooring/moordyn_payout.py [--segments 5 10 20] [--t-end 12] [--single]

A steel cable (radius 5 mm: A = 7.854e-5 m^2, E = 2e11 Pa, 7850 kg/m^3, so EA = 1.571e7 N and
0.6165 kg/m) hangs from a winch at (0, 0, 0) with a 10 kg point load at its lower end, in air
(MoorDyn's water density set to 0, no drag, no added mass), g = 9.81.  The unstretched length
follows the cycloidal law L(t) = 5 + 10 (t/T - sin(2 pi t/T) / (2 pi)), T = 10 s (velocity and
acceleration zero at both ends), sampled every 0.25 s and interpolated by the not-a-knot cubic
spline (the same table the rancf scenario gives its winch), held at 15 m after 10 s.

MoorDyn 2.7 changes a line's unstretched length through ``SetLineUnstretchedLength`` and
``SetLineUnstretchedLengthVel``: every segment keeps the length L/N, the node masses follow (the
material's mass A rho L changes with L), the nodes keep their velocities.  Before each coupling
step (1e-3 s) the length is set to L(t) and its rate to (L(t + h) - L(t)) / h, so it ends the step
at L(t + h).  The cable starts from MoorDyn's static solution at 5 m, without internal damping
(BA = 0), integrated by MoorDyn's RK4: MoorDyn's usual BA = -1 (critical damping of one segment)
makes the paid-out cable a dashpot (the load lags the law by 4.4 m at 5 segments, 1.2 m at 20:
the segments' damping resists the nodes' separation as they lengthen), and its default RK2 is
unstable without damping (undamped oscillations grow by (w dt)^4 / 8 a step; RK4 is stable for
w dt < 2.8).  ``--ba`` and ``--scheme`` choose others.

Runs each segment count with the step 5e-4 s / N and the finest again at half the step; writes
``results/moordyn_payout.csv`` (the finest run: t, L, load z, the winch tension: the size of the
force the cable puts on the winch point, the tension at the load) and
``results/moordyn_payout.json`` (the study, the command, versions and CPU) to ``--out``.  With
``--single`` only the runs at ``--segments`` (no half step), and the study printed as JSON.
"""

from __future__ import annotations

import argparse
import csv
import ctypes
import json
import math
import sys
from pathlib import Path

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE))

import moordyn  # noqa: E402
from moordyn_case import Case, LineType, Point, run  # noqa: E402
from provenance import provenance  # noqa: E402
from scipy.interpolate import CubicSpline  # noqa: E402

RADIUS, YOUNGS, DENSITY, LOAD, G = 0.005, 2.0e11, 7850.0, 10.0, 9.81
AREA = math.pi * RADIUS**2
L0, L1, T_PAY, T_END, SAMPLE = 5.0, 15.0, 10.0, 12.0, 0.25
COUPLING = 1e-3


def length_table() -> list[tuple[float, float]]:
    """The pay-out law as the table both codes interpolate: (t, L) every ``SAMPLE`` s to T."""
    n = round(T_PAY / SAMPLE)
    rows = []
    for i in range(n + 1):
        s = i / n
        law = L0 + (L1 - L0) * (s - math.sin(2 * math.pi * s) / (2 * math.pi))
        rows.append((i * SAMPLE, round(law, 12)))  # as written in payout.toml
    return rows


_TABLE = length_table()
_SPLINE = CubicSpline([t for t, _ in _TABLE], [v for _, v in _TABLE], bc_type="not-a-knot")


def length(t: float) -> float:
    """L(t): the not-a-knot cubic spline of :func:`length_table`, held after its last time."""
    return float(_SPLINE(min(max(t, 0.0), T_PAY)))


def _set_length(line: object, value: float, rate: float) -> None:
    """``SetLineUnstretchedLength`` and ``...Vel``, each giving back the reference to ``None``
    that moordyn 2.7.2's binding takes from it: it returns ``None`` without a new reference
    (``sys.getrefcount(None)`` falls by one a call), and after some 10^4 calls Python stops with
    "deallocating None"."""
    none = ctypes.py_object(None)
    moordyn.SetLineUnstretchedLength(line, value)
    ctypes.pythonapi.Py_IncRef(none)
    moordyn.SetLineUnstretchedLengthVel(line, rate)
    ctypes.pythonapi.Py_IncRef(none)


def case(segments: int, dt: float, ba: float = 0.0, scheme: str = "RK4") -> Case:
    options = {
        "g": G,
        "rho": 0.0,
        "WtrDpth": 1000.0,
        "dtM": dt,
        "threshIC": 1e-6,
        "TmaxIC": 100.0,
        "disableOutput": 1,
        "disableOutTime": 1,
        "tScheme": scheme,
    }
    return Case(
        LineType("steel", diameter=2 * RADIUS, mass=DENSITY * AREA, ea=YOUNGS * AREA, ba=ba),
        [Point("Coupled", (0.0, 0.0, 0.0)), Point("Free", (0.0, 0.0, -L0), mass=LOAD)],
        L0,
        segments,
        options=options,
    )


def simulate(segments: int, dt: float, t_end: float = T_END, ba: float = 0.0, scheme: str = "RK4"):
    def winch(t: float) -> tuple[list[float], list[float]]:
        return [0.0, 0.0, 0.0], [0.0, 0.0, 0.0]

    def before_step(line: object, t: float) -> None:
        _set_length(line, length(t), (length(t + COUPLING) - length(t)) / COUPLING)

    def record(system: object, line: object, forces: list[float]) -> dict[str, float]:
        load = moordyn.GetPoint(system, 2)
        n = moordyn.GetLineN(line)
        return {
            "length_m": moordyn.GetLineUnstretchedLength(line),
            "load_z_m": moordyn.GetPointPos(load)[2],
            "winch_tension_N": math.sqrt(sum(f * f for f in forces)),
            "load_tension_N": math.sqrt(sum(v * v for v in moordyn.GetLineNodeTen(line, n))),
        }

    return run(case(segments, dt, ba, scheme), winch, record, t_end, COUPLING, before_step)


def write_csv(path: Path, r, every: int = 10) -> None:
    keys = list(r.columns)
    with path.open("w", newline="") as f:
        w = csv.writer(f)
        w.writerow(["t_s", *keys])
        for i in range(0, len(r.times), every):
            w.writerow([f"{r.times[i]:.4f}", *(f"{r.columns[k][i]:.9g}" for k in keys)])


def default_step(segments: int) -> float:
    """5e-4 s / N: 2.5e-5 s at 20 segments, where the highest axial frequency of the 5 m line
    (about 2 c / (L/N), c = sqrt(E / rho)) times the step is 1.0 (RK4 holds to 2.8)."""
    return 5e-4 / segments


def main() -> None:
    p = argparse.ArgumentParser()
    p.add_argument("--segments", type=int, nargs="+", default=[5, 10, 20])
    p.add_argument("--t-end", type=float, default=T_END)
    p.add_argument("--out", type=Path, default=HERE / "results")
    p.add_argument("--single", action="store_true", help="one run per N, no half-step check")
    p.add_argument("--ba", type=float, default=0.0, help="MoorDyn's BA/-zeta (default 0)")
    p.add_argument("--scheme", default="RK4", help="MoorDyn's tScheme (default RK4)")
    a = p.parse_args()
    finest = max(a.segments)
    plan = [(n, default_step(n)) for n in sorted(a.segments)]
    if not a.single:
        plan.append((finest, default_step(finest) / 2))
    runs = []
    for n, dt in plan:
        r = simulate(n, dt, a.t_end, a.ba, a.scheme)
        runs.append((n, dt, r))
        print(
            f"MoorDyn {n:3d} segments, dt {dt:.3g} s: set-up {r.init_s:.2f} s, solve "
            f"{r.solve_s:.2f} s",
            file=sys.stderr,
            flush=True,
        )
    ref = runs[-1][2]
    every = round(0.1 / COUPLING)
    rows = []
    for n, dt, r in runs:
        diff = max(
            abs(a_ - b_) / b_
            for a_, b_ in zip(
                r.columns["winch_tension_N"][::every],
                ref.columns["winch_tension_N"][::every],
                strict=True,
            )
        )
        rows.append(
            {
                "segments": n,
                "dt_s": dt,
                "setup_s": r.init_s,
                "solve_s": r.solve_s,
                "max_rel_diff_to_reference": diff,
                "winch_tension_0_N": r.columns["winch_tension_N"][0],
                "winch_tension_end_N": r.columns["winch_tension_N"][-1],
            }
        )
    a.out.mkdir(parents=True, exist_ok=True)
    write_csv(a.out / "moordyn_payout.csv", ref, every)
    study = {
        **provenance("moordyn", "scipy", "numpy"),
        "reference": {"segments": runs[-1][0], "dt_s": runs[-1][1]},
        "BA": a.ba,
        "tScheme": a.scheme,
        "compared": "winch tension every 0.1 s",
        "length_table": _TABLE,
        "runs": rows,
    }
    (a.out / "moordyn_payout.json").write_text(json.dumps(study, indent=1) + "\n")
    if a.single:
        print(json.dumps(study))
        return
    print(
        f"{'segments':>8} {'dt [s]':>9} {'set-up [s]':>10} {'solve [s]':>9} {'max diff':>9} "
        f"{'T(0) [N]':>9} {'T(end) [N]':>10}"
    )
    for r in rows:
        print(
            f"{r['segments']:8d} {r['dt_s']:9.3g} {r['setup_s']:10.2f} {r['solve_s']:9.2f} "
            f"{r['max_rel_diff_to_reference']:9.2e} {r['winch_tension_0_N']:9.2f} "
            f"{r['winch_tension_end_N']:10.2f}"
        )


if __name__ == "__main__":
    main()
