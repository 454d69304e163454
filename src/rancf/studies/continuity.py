"""What C² buys: error against unknowns for C¹ and C² meshes.

Two problems, each meshed with ``n`` elements as C¹ (shared nodes: ``[r, r_x]`` per node) and as
C² (``mesh.continuity = "C2"``: the control points of the cubic B-spline through the mesh,
:mod:`rancf.mesh.continuity`); the unknowns are the free coordinates of each model.

* **Cantilever** (the shipped ``cantilever``: L = 0.5 m, radius 0.03 m, ρ = 6000 kg/m³,
  E = 2e7 Pa, clamped): relative error of the first five bending frequencies against the
  Euler–Bernoulli values ``f_i = (β_i² / 2π) sqrt(EI / ρA L⁴)`` (the axial modes are told apart
  by their shapes and left out), and the highest frequency of the mesh: the stiffest mode an
  explicit integrator must resolve, the step-size limit a user meets.
* **6.1 pendulum** (the shipped ``planar-pendulum``, Kopt RANCF, h = 1 ms, ρ∞ = 0.9): the tip
  error ``max_t |r_B(t) - r_B,ref(t)|`` over the output times (every 0.01 s) against the C¹ mesh
  of :data:`N_REF` elements with the same time step, as in the exact-geometry study.

:func:`continuity_study` returns the rows; ``benchmarks/continuity_study.py`` writes them
(``benchmarks/results/continuity_study.json``) and prints the table of the user guide
(``docs/guide/closed-curves.md``).
"""

from __future__ import annotations

from typing import Any

import numpy as np

from rancf.studies.common import load_example, modes, run, variant

__all__ = ["BETA", "N_REF", "cantilever_rows", "pendulum_rows", "continuity_study"]

#: ``β_i L`` of the clamped-free Euler–Bernoulli beam, first five modes.
BETA = np.array(
    [1.875104068711961, 4.694091132974175, 7.854757438237613, 10.99554073487547, 14.13716839104647]
)
#: Elements of the pendulum's reference (C¹, Kopt).
N_REF = 24


def _bending(model: Any, modes: Any) -> tuple[np.ndarray, float]:
    """The bending frequencies (transverse shapes) and the highest frequency of all modes."""
    shapes = modes.modes.reshape(modes.frequencies_hz.size, model.n_nodes, model.dpn)
    transverse = np.abs(shapes[:, :, 1]).max(axis=1) > np.abs(shapes[:, :, 0]).max(axis=1)
    return modes.frequencies_hz[transverse], float(modes.frequencies_hz.max())


def cantilever_rows(ns: list[int]) -> list[dict[str, Any]]:
    """One row per continuity and mesh: unknowns, relative errors of the first five bending
    frequencies (NaN where the mesh has fewer), the highest frequency [Hz]."""
    raw = load_example("cantilever")
    sec, mat = raw["section"], raw["material"]
    ei_rho_a = mat["youngs_modulus"] * sec["radius"] ** 2 / 4 / mat["density"]
    length = float(np.linalg.norm(np.subtract(raw["geometry"]["end"], raw["geometry"]["start"])))
    exact = BETA**2 / (2 * np.pi) * np.sqrt(ei_rho_a / length**4)
    rows = []
    for c in ("C1", "C2"):
        for n in ns:
            sc, model = variant(raw, f"cantilever {c} n={n}", mesh__elements=n, mesh__continuity=c)
            f, top = _bending(model, modes(sc))
            err = np.full(5, np.nan)
            k = min(5, f.size)
            err[:k] = f[:k] / exact[:k] - 1.0
            rows.append(
                dict(
                    continuity=c,
                    elements=n,
                    unknowns=int(np.sum(~model.fixed)),
                    errors=err.tolist(),
                    highest_hz=top,
                )
            )
    return rows


def pendulum_rows(ns: list[int], t_end: float = 1.0) -> tuple[list[dict[str, Any]], float]:
    """One row per continuity and mesh: unknowns and the tip error [m] against the reference;
    and the reference's own error against C¹ with ``2 N_REF / 3`` elements (its check)."""
    raw = load_example("planar-pendulum")

    def tip(n: int, c: str) -> tuple[int, np.ndarray]:
        sc, model = variant(
            raw,
            f"pendulum {c} n={n}",
            mesh__elements=n,
            mesh__continuity=c,
            solver__t_end=t_end,
        )
        res = run(sc)
        return int(np.sum(~model.fixed)), model.node_positions(res.q)[:, -1]

    _, ref = tip(N_REF, "C1")

    def error(r: np.ndarray) -> float:
        return float(np.max(np.linalg.norm(r - ref, axis=1)))

    rows = []
    for c in ("C1", "C2"):
        for n in ns:
            dofs, r = tip(n, c)
            rows.append(dict(continuity=c, elements=n, unknowns=dofs, tip_error=error(r)))
    return rows, error(tip(2 * N_REF // 3, "C1")[1])


def continuity_study(quick: bool = False) -> dict[str, Any]:
    """Both problems (module docstring); ``quick``: fewer meshes and 0.2 s of the pendulum."""
    ns = [2, 4, 8] if quick else [2, 3, 4, 6, 8, 12, 16, 24]
    pn = [6, 12] if quick else [2, 3, 4, 6, 8, 12]
    pend, check = pendulum_rows(pn, 0.2 if quick else 1.0)
    return dict(cantilever=cantilever_rows(ns), pendulum=pend, pendulum_reference_check=check)
