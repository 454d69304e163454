"""Where exact geometry pays: the 6.1 pendulum (elliptic arc) from soft to stiff, E = 2e6–2e10 Pa.

The planar pendulum of paper example 6.1 (chord 0.5 m, angles 30°/40°, point (0.315, 0.077) m,
radius 0.02 m, ρ = 6000 kg/m³, pinned at A, gravity, released from rest, h = 1 ms, ρ∞ = 0.9,
1 s) for five Young's moduli.  Every mesh of every element type — RANCF with Kopt, with K = 0.2
and K = 0.6, classical ANCF (node positions and unit tangents of the conic, the Hermite cubic
as reference) and the co-rotational beam — is one run of one sweep (``sweep/`` in the output).

Error measure: ``max_t |r_B(t) - r_B,ref(t)|`` over the output times (every 0.01 s).  The
converged reference, at each E, is the Kopt RANCF mesh of 24 elements with the same time step
(so the time-discretization error cancels); its own convergence is checked against 16 elements
and reported next to the results.  The beam converges to slightly different physics (rotary
inertia) and is measured against the same cable reference.  When Exudyn is installed, its
``ANCFCable2D`` with a curved (Hermite) reference is an extra column, measured against its own
24-element solution (its strain measure differs from ours), for E up to 2e9 Pa: with its
default solver settings its 24-element run at 2e10 Pa took 117 s.
"""

from __future__ import annotations

from concurrent.futures import ThreadPoolExecutor
from pathlib import Path
from typing import Any

import numpy as np

from rancf.post.plots import pyplot
from rancf.studies.common import (
    Comparison,
    StudyResult,
    add_animation,
    begin_study,
    example_path,
    format_error,
    n_elements,
    save_figure,
)
from rancf.studies.figures import kind_style
from rancf.studies.grid import Executor, grid_variant, run_grid

NAME = "exact-geometry"
TITLE = "Where exact geometry pays: the 6.1 pendulum from E = 2e6 to 2e10 Pa"
KINDS: dict[str, dict[str, Any]] = {
    "Kopt": dict(mesh__element="rancf", mesh__k="opt"),
    "K = 0.2": dict(mesh__element="rancf", mesh__k=0.2),
    "K = 0.6": dict(mesh__element="rancf", mesh__k=0.6),
    # K does not enter ANCF or beam meshes (nodes and tangents are the conic's); 0.5 skips Kopt
    "ANCF (Hermite reference)": dict(mesh__element="ancf", mesh__k=0.5),
    "Euler–Bernoulli beam": dict(mesh__element="beam", mesh__k=0.5),
}
EXUDYN = "Exudyn ANCFCable2D (curved reference)"
#: Exudyn's column stops here: with its default solver settings its 24-element run at
#: E = 2e10 Pa took 117 s (0.22 s at 2e9 Pa) on our 2-core machine.
EXUDYN_MAX_E = 2e9
TOLS = (1e-3, 1e-4)


def _plan(quick: bool) -> dict[str, Any]:
    if quick:
        return dict(es=[2e6, 2e9], ns=[1, 2, 3], n_ref=6, n_check=4, t_end=0.2)
    return dict(
        es=[2e6, 2e7, 2e8, 2e9, 2e10],
        ns=[1, 2, 3, 4, 5, 6, 7, 8, 10, 12],
        n_ref=24,
        n_check=16,
        t_end=1.0,
    )


def _needed(errs: dict[int, float], tol: float) -> int | None:
    return next((n for n in sorted(errs) if errs[n] <= tol), None)


def _fmt(n: int | None, ns: list[int], errs: dict[int, float] | None = None) -> str:
    if errs is not None and all(np.isnan(v) for v in errs.values()):
        return "not run"
    return str(n) if n is not None else f"> {max(ns)}"


def run_study(
    out: str | Path, quick: bool = False, executor: Executor | None = None
) -> StudyResult:
    """Run the study; figures and CSV tables go to ``out``; the grid runs on ``executor``
    (default: this process)."""
    out, res, raw = begin_study(out, NAME, TITLE, __doc__)
    p = _plan(quick)
    es, ns = p["es"], p["ns"]
    plan: list[tuple[float, str, int, dict[str, Any]]] = []
    for e in es:
        plan.append((e, "reference", p["n_ref"], KINDS["Kopt"]))
        plan.append((e, "check", p["n_check"], KINDS["Kopt"]))
    for n in ns:
        for e in es:
            plan += [(e, kind, n, opts) for kind, opts in KINDS.items()]
    variants = [
        grid_variant(
            raw,
            i,
            f"E={e:g}_{kind}_n={n}",
            material__youngs_modulus=e,
            mesh__elements=n,
            solver__t_end=p["t_end"],
            **opts,
        )
        for i, (e, kind, n, opts) in enumerate(plan)
    ]
    soft_ref = variants[0].name  # the reference at the softest E: animated as soon as it ran

    def on_run(name: str, run: Any) -> tuple[str, ...]:
        if name == soft_ref:  # drawn while the grid runs, not after it
            caption = f"E = {es[0]:g} Pa, reference run"
            add_animation(res, run["folder"], out / "animation.gif", caption)
        return ()

    with ThreadPoolExecutor(1) as pool:  # Exudyn's column here while the grid runs elsewhere
        exudyn_future = pool.submit(_exudyn_errors, raw, es, ns, p)
        done = run_grid(executor, variants, example_path(NAME), out / "sweep", on_run)
        exudyn = exudyn_future.result()
    runs = {(e, kind, n): done[v.name] for v, (e, kind, n, _) in zip(variants, plan, strict=True)}

    def error(run: Any, ref: Any) -> float:
        if run["status"] != "completed":
            return float("inf")
        k = run["tip"].shape[0]
        return float(np.max(np.linalg.norm(run["tip"] - ref["tip"][:k], axis=1)))

    errs: dict[float, dict[str, dict[int, float]]] = {}
    ref_check: dict[float, float] = {}
    for e in es:
        ref = runs[(e, "reference", p["n_ref"])]
        ref_check[e] = error(runs[(e, "check", p["n_check"])], ref)
        errs[e] = {kind: {n: error(runs[(e, kind, n)], ref) for n in ns} for kind in KINDS}
    kinds = list(KINDS)
    if exudyn is not None:
        kinds.append(EXUDYN)
        for e in es:
            errs[e][EXUDYN] = exudyn.get(e, dict.fromkeys(ns, float("nan")))

    needed = {e: {k: [_needed(errs[e][k], tol) for tol in TOLS] for k in kinds} for e in es}
    res.add_table(
        out,
        "Elements needed for a tip error of 1e-3 m / 1e-4 m",
        ["E [Pa]", "reference check [m]", *kinds],
        [
            [f"{e:g}", format_error(ref_check[e], ".1e")]
            + [" / ".join(_fmt(n, ns, errs[e][k]) for n in needed[e][k]) for k in kinds]
            for e in es
        ],
        "elements_needed.csv",
    )
    res.add_table(
        out,
        "Tip error against elements",
        ["E [Pa]", "element", "elements", "max tip error [m]"],
        [[f"{e:g}", k, n, format_error(errs[e][k][n])] for e in es for k in kinds for n in ns],
        "error_vs_elements.csv",
    )
    _figures(out, res, errs, needed, es, ns, kinds, p)
    _explain(res, errs, needed, ref_check, es, ns, p["n_ref"], p["n_check"])
    res.data.update(errors=errs, needed=needed, ref_check=ref_check, exudyn=exudyn is not None)
    return res.finish()


def _exudyn_errors(
    raw: dict[str, Any], es: list[float], ns: list[int], p: dict[str, Any]
) -> dict[float, dict[int, float]] | None:
    """Exudyn's errors against its own ``n_ref``-element solution (None without Exudyn)."""
    from rancf.studies import exudyn_cable

    if not exudyn_cable.AVAILABLE:
        return None
    from rancf.scenario import parse_scenario

    sc = parse_scenario(raw, NAME)
    body, s = sc.data["bodies"][0], sc.data["solver"]
    g = body["geometry"]
    from rancf.geometry.conic import conic_arc_through
    from rancf.mesh.factories import mesh_conic, to_ancf

    arc = conic_arc_through(g["start"], g["end"], g["angles_deg"], g["point"])
    meshes = {n: to_ancf(mesh_conic(arc, n, 0.5)) for n in [*ns, p["n_ref"]]}
    model = sc.build_model()
    area, inertia = model.section.area, model.section.inertia
    solver = {**s, "t_end": p["t_end"]}
    out = {}
    for e in (e for e in es if e <= EXUDYN_MAX_E):
        tips = {
            n: exudyn_cable.curved_pendulum_tip(
                m.nodes, m.scales, solver, area, inertia, body["material"]["density"], e
            )[1]
            for n, m in meshes.items()
        }
        ref = tips[p["n_ref"]]
        out[e] = {n: float(np.max(np.linalg.norm(tips[n] - ref, axis=1))) for n in ns}
    return out


def _figures(
    out: Path,
    res: StudyResult,
    errs: dict[float, dict[str, dict[int, float]]],
    needed: dict[float, dict[str, list[int | None]]],
    es: list[float],
    ns: list[int],
    kinds: list[str],
    p: dict[str, Any],
) -> None:
    from matplotlib.ticker import MaxNLocator

    plt = pyplot()
    fig, axes = plt.subplots(
        1, len(es), figsize=(3.4 * len(es), 3.8), sharey=True, constrained_layout=True
    )
    for ax, e in zip(np.atleast_1d(axes), es, strict=True):
        for i, k in enumerate(kinds):
            ok = [n for n in ns if np.isfinite(errs[e][k][n])]
            style = kind_style(i, k)
            style["ms"] = 0.7 * style["ms"]
            ax.semilogy(ok, [errs[e][k][n] for n in ok], label=k, **style)
        for tol in TOLS:
            ax.axhline(tol, color="k", ls=":", lw=0.8)
        ax.set_title(f"E = {e:g} Pa")
        ax.set_xlabel("elements")
        ax.xaxis.set_major_locator(MaxNLocator(integer=True))
    np.atleast_1d(axes)[0].set_ylabel(f"max over t ∈ [0, {p['t_end']:g}] s of |tip − ref| [m]")
    np.atleast_1d(axes)[-1].legend(fontsize=7)
    save_figure(
        fig,
        out / "error_vs_elements.png",
        res,
        f"Tip error against elements for each E (reference: {p['n_ref']} Kopt elements)",
    )
    fig, axes = plt.subplots(1, 2, figsize=(12, 4.3), constrained_layout=True)
    n_fixed = 3 if 3 in ns else ns[-1]
    for i, k in enumerate(kinds):
        need = [needed[e][k][1] for e in es]
        axes[0].semilogx(
            [e for e, n in zip(es, need, strict=True) if n is not None],
            [n for n in need if n is not None],
            label=k,
            **kind_style(i, k),
        )
        axes[1].loglog(es, [errs[e][k][n_fixed] for e in es], label=k, **kind_style(i, k))
    axes[0].set_ylabel("elements for tip error ≤ 1e-4 m\n(no point: more than tried)")
    axes[0].yaxis.set_major_locator(MaxNLocator(integer=True))
    axes[1].set_ylabel(f"tip error with {n_elements(n_fixed)} [m]")
    for ax in axes:
        ax.set_xlabel("Young's modulus E [Pa]")
        ax.legend(fontsize=7)
    axes[0].set_title("Elements needed: the transition")
    axes[1].set_title("Soft: deformation error; stiff: reference-shape error")
    save_figure(
        fig, out / "transition.png", res, "Elements needed and error at a fixed mesh against E"
    )


def _explain(
    res: StudyResult,
    errs: dict[float, dict[str, dict[int, float]]],
    needed: dict[float, dict[str, list[int | None]]],
    ref_check: dict[float, float],
    es: list[float],
    ns: list[int],
    n_ref: int,
    n_check: int,
) -> None:
    soft, stiff = es[0], (2e9 if 2e9 in es else es[-1])
    ancf = "ANCF (Hermite reference)"
    for e, j, earlier in ((stiff, 1, "3 / 6"), (soft, 0, "7 / 7")):
        tol = TOLS[j]
        k_n, a_n = needed[e]["Kopt"][j], needed[e][ancf][j]
        res.comparison.append(
            Comparison(
                f"E = {e:g} Pa: elements for tip error ≤ {tol:g} m, Kopt / ANCF",
                "not given",
                f"{_fmt(k_n, ns)} / {_fmt(a_n, ns)}",
                "",
                f"our earlier measurement: {earlier}",
            )
        )
    n3 = 3 if 3 in ns else ns[-1]
    ratio = {e: errs[e][ancf][n3] / max(errs[e]["Kopt"][n3], 1e-300) for e in es}
    res.notes.append(
        "Why the transition: a soft cable (E = "
        f"{soft:g} Pa) sags and bends a lot, and the error of any mesh is that of interpolating "
        "the deformation; RANCF and ANCF elements are both cubic in the deformation, so they "
        f"need about as many elements (with {n3} elements ANCF's error is {ratio[soft]:.1f}× "
        "Kopt's). A stiff cable hardly deforms and swings like a rigid curved body whose motion "
        "is set by its shape and mass distribution; the RANCF mesh has the exact elliptic arc "
        "as its reference, so its error falls with the deformation, while the ANCF mesh's "
        "reference is the Hermite cubic through the nodes — a slightly different body, an error "
        "that does not shrink as E grows and only refinement removes (the beam's is larger "
        f"still). With {n3} elements ANCF's error is {ratio[stiff]:.1f}× Kopt's at E = "
        f"{stiff:g} Pa. Reference check: the {n_ref}- and {n_check}-element Kopt solutions "
        f"differ by at most {max(ref_check.values()):.1e} m over all E"
        + (
            ", so the 1e-4 m counts are resolved."
            if max(ref_check.values()) < 0.5 * TOLS[1]
            else "; errors below that are not resolved by this reference."
        )
    )
