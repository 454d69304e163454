"""Static mooring lines side by side: MoorPy 1.3 and ``rancf static``, in one run.

    python benchmarks/mooring/compare_statics.py [--peer-python PYTHON]

The two lines of ``moorpy_statics.py`` (the chain on the seabed, the taut buoyant line) in
MoorPy (run by ``--peer-python``: an interpreter with ``moorpy==1.3.*``, default this one) and
through ``rancf static FILE --json`` on ``mooring-chain.toml`` and ``taut-buoyant.toml``.  The
force the line puts on the fairlead is MoorPy's ``Point.getForces(lines_only=True)`` and minus
rancf's reaction at the fairlead support (the support's force on the line); they agree when
|F_rancf - F_MoorPy| <= 0.5 % |F_MoorPy|.  Also MoorPy's fairlead tension next to rancf's
``tension`` sensor at the end (the axial force from the strain there; not compared).  Prints a
table with the forces, the difference, both wall times (rancf: its static solve,
``wall_time_s``, and the whole process), MoorPy's segment count (the points it returns the
profile at; its catenary is exact) and rancf's elements, and the CPU.  A third row checks the
chain's model (geometry, seabed, supports) through keys rancf had before ``[fluid]``: the chain
in air with gravity scaled to w / m (in statics buoyancy is a uniform upward load); it does not
count for the exit status, which is 1 when a case misses the tolerance or rancf fails.  The
chain in space (``mooring-surge-3d.toml``: drawn as a conic, unloaded straight by the default
``stress_free = "auto"``, docs/derivations/cable.md sec. 8) at 40, 80 and 160 elements is held
to the same tolerance.
"""

from __future__ import annotations

import argparse
import json
import math
import shutil
import sys
import tempfile
import tomllib
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))

from common import HERE, failed, peer, rancf, table  # noqa: E402
from provenance import machine, version  # noqa: E402

TOLERANCE = 0.005
FILES = {"chain": "mooring-chain.toml", "taut buoyant": "taut-buoyant.toml"}
#: The check of the chain's model without the fluid tables: in statics buoyancy is a uniform
#: upward load, so the chain in air under g w / (m g) per mass weighs what it weighs in water.
DRY = "chain, g scaled to w/m (no [fluid])"
#: The chain drawn in space, meshed with these element counts.
SPATIAL = (40, 80, 160)


def spatial_chain(n: int, folder: Path) -> Path:
    """``mooring-surge-3d.toml`` (the chain in space, drawn as a conic) on ``n`` elements."""
    text = (HERE / "mooring-surge-3d.toml").read_text().replace("elements = 30", f"elements = {n}")
    path = folder / f"chain-3d-{n}.toml"
    path.write_text(text)
    return path


def dry_chain(wet_weight: float, mass: float, folder: Path) -> Path:
    """``mooring-chain.toml`` without ``[fluid]``, ``[hydro]`` and the ``tension`` sensor, its
    gravity scaled to ``wet_weight / mass``: the same statics through rancf's existing keys."""
    text = (HERE / FILES["chain"]).read_text()
    head, rest = text.split("[fluid]", 1)
    text = head + "[[supports]]" + rest.split("[[supports]]", 1)[1]
    text = text.split('[[sensors]]\nname = "tension"')[0]
    text = text.replace(
        "gravity = [0.0, 0.0, -9.81]", f"gravity = [0.0, 0.0, {-wet_weight / mass!r}]"
    )
    path = folder / "chain-dry.toml"
    path.write_text(text)
    return path


def rancf_force(out: dict) -> list[float] | None:
    """Minus the reaction sensor ``fairlead`` of ``rancf static --json``: the line's force on the
    fairlead."""
    s = out.get("sensors", {})
    keys = [f"fairlead_{c}" for c in "xyz"]
    if not all(k in s for k in keys):
        return None
    return [-float(s[k]) for k in keys]


def main() -> None:
    p = argparse.ArgumentParser()
    p.add_argument("--peer-python", default=sys.executable)
    a = p.parse_args()
    mp, mp_wall = peer(a.peer_python, "moorpy_statics.py")
    rows = [
        [
            "case",
            "MoorPy F [kN]",
            "rancf F [kN]",
            "|dF|/|F|",
            "within 0.5 %",
            "tension: MoorPy / rancf sensor [kN]",
            "MoorPy solve / process [s]",
            "rancf solve / process [s]",
            "MoorPy segments",
            "rancf elements",
        ]
    ]
    ok = True
    tmp = Path(tempfile.mkdtemp())
    chain = mp["cases"]["chain"]
    files = {
        **{k: HERE / v for k, v in FILES.items()},
        DRY: dry_chain(chain["wet_weight_N_per_m"], chain["mass_kg_per_m"], tmp),
        **{f"chain in space, {n} el.": spatial_chain(n, tmp) for n in SPATIAL},
    }
    for name, path in files.items():
        peer_case = mp["cases"]["chain" if name == DRY or name.startswith("chain ") else name]
        ref = peer_case["fairlead_force_N"]
        elements = tomllib.loads(path.read_text())["mesh"]["elements"]
        proc, wall = rancf("static", str(path), "--json")
        got = rancf_force(json.loads(proc.stdout)) if proc.returncode == 0 else None
        kn = lambda f: "(" + ", ".join(f"{v / 1e3:.1f}" for v in f) + ")"  # noqa: E731
        if got is None:
            ok = False
            why = failed(proc) if proc.returncode else "no fairlead reaction in the output"
            rows.append(
                [
                    name,
                    kn(ref),
                    f"rancf failed: {why}",
                    "-",
                    "no",
                    "-",
                    "-",
                    f"- / {wall:.2f}",
                    "40",
                    str(elements),
                ]
            )
            continue
        err = math.dist(got, ref) / math.hypot(*ref)
        ok &= err <= TOLERANCE or name == DRY
        out = json.loads(proc.stdout)
        solve = out.get("wall_time_s", float("nan"))
        sensor = out["sensors"].get("tension")
        tension = f"{peer_case['fairlead_tension_N'] / 1e3:.1f} / " + (
            "-" if sensor is None else f"{sensor / 1e3:.1f}"
        )
        rows.append(
            [
                name,
                kn(ref),
                kn(got),
                f"{err:.2e}",
                "yes" if err <= TOLERANCE else "NO",
                tension,
                f"{peer_case['wall_s']:.3f} / {mp_wall:.2f}",
                f"{solve:.3f} / {wall:.2f}",
                "40",
                str(elements),
            ]
        )
    shutil.rmtree(tmp)
    print(table(rows))
    print(
        f"\nMoorPy {mp['peer_version']}, rancf {version('rancf')}; rho = {mp['rho']} kg/m^3, "
        f"g = {mp['g']} m/s^2; {machine()}"
    )
    sys.exit(0 if ok else 1)


if __name__ == "__main__":
    main()
