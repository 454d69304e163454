"""A shipped scenario that is not a paper study, run as ``rancf example run NAME``.

:data:`rancf.studies.common.SCENARIO_ANALYSES` says what each such scenario is for
(``"simulate"``, ``"static"``, ``"modes"``); each analysis writes the files its own command
would and adds its figures and a table to a small report:

* ``static`` — the load path as a run directory ``static/`` (as ``rancf static --out``) with
  its plots, and the sensors at the full load;
* ``modes`` — ``modes.json`` and ``modes.png`` (as ``rancf modes --json --plot``), the
  frequencies as a table;
* ``simulate`` — the run directory ``run/`` (as ``rancf simulate``) with its plots, and the
  sensors at the end.

The scenario file itself is copied into the output folder first, so the run can be repeated
and edited.  Warnings for likely unit mistakes (:mod:`rancf.post.checks`) become notes of the
report.
"""

from __future__ import annotations

from pathlib import Path

from rancf.atomic import atomic_write
from rancf.post.results import sensor_table, strict_json
from rancf.scenario import load_scenario
from rancf.studies.common import SCENARIO_ANALYSES, StudyResult, example_path

__all__ = ["run_scenario"]

#: The disk an example's dynamic run may take [GB].
MAX_EXAMPLE_GB = 2.0


def _describe(text: str) -> str:
    """The scenario's opening comment (its description), as one paragraph."""
    lines = []
    for line in text.splitlines():
        if not line.startswith("#"):
            break
        lines.append(line.lstrip("# ").strip())
    return " ".join(lines)


def _figures(res: StudyResult, out: Path, run_dir: Path, what: str, skip: str = "") -> None:
    from rancf.post.system_run import load_run, plot_system_run

    paths = plot_system_run(load_run(run_dir), run_dir / "plots")
    for path in paths:
        if path.stem != skip:
            res.figures.append((f"{what}: {path.stem}", str(path.relative_to(out))))


def _notes(res: StudyResult, summary: dict) -> None:
    for w in summary.get("warnings", []):
        if f"Warning: {w}" not in res.notes:
            res.notes.append(f"Warning: {w}")


def run_scenario(name: str, out: str | Path, quick: bool = False) -> StudyResult:
    """Run the analyses of the shipped scenario ``name`` into ``out``.

    ``quick`` changes nothing: these scenarios are small.  A static solve that does not converge
    raises :class:`~rancf.errors.ConvergenceError` after writing the converged load steps.
    """
    out = Path(out)
    out.mkdir(parents=True, exist_ok=True)
    text = example_path(name).read_text(encoding="utf-8")
    scenario = out / f"{name}.toml"
    atomic_write(scenario, text)
    res = StudyResult(name, f"Shipped scenario: {name}")
    res.notes.append(
        f"{_describe(text)} The scenario file is `{scenario.name}` in this folder; "
        f"`rancf example run {name}` runs: {', '.join(SCENARIO_ANALYSES[name])}."
    )
    sc = load_scenario(scenario)
    analyses = SCENARIO_ANALYSES[name]
    for analysis in analyses:
        if analysis == "static":
            from rancf.runs.static import run_static

            info = {"scenario": str(scenario.resolve())}
            static = run_static(sc, out / "static", info, lambda doc: _notes(res, doc))
            st = static.result
            _figures(res, out, out / "static", "static load path", skip="energy")
            res.add_table(
                out,
                f"Static equilibrium: {len(st.load_factors) - 1} load steps, "
                f"{st.n_newton} Newton iterations",
                ["sensor", "value"],
                [[n, f"{v:.9g}"] for n, v in static.sensors.items()],
                "static.csv",
            )
        elif analysis == "modes":
            from rancf.post.plots import plot_modes
            from rancf.runs.modes import run_modes

            modal_run = run_modes(sc, at_least=1)
            system, modal = modal_run.system, modal_run.result
            doc = {
                "frequencies_hz": modal.frequencies_hz.tolist(),
                "rigid_body_modes_removed": modal.n_rigid,
            }
            atomic_write(out / "modes.json", strict_json(doc))
            plot_modes(system, modal, out / "modes.png")
            res.figures.append(("mode shapes", "modes.png"))
            res.add_table(
                out,
                f"Natural frequencies about the reference configuration ({modal.n_rigid} "
                "rigid-body mode(s) removed)",
                ["mode", "frequency [Hz]"],
                [[i + 1, f"{f:.6f}"] for i, f in enumerate(modal.frequencies_hz)],
                "modes.csv",
            )
        elif analysis == "buckling":
            from rancf.post.plots import plot_buckling
            from rancf.runs.buckling import run_buckling

            brun = run_buckling(sc, 2)
            system, buck = brun.system, brun.result
            atomic_write(
                out / "buckling.json",
                strict_json({"load_factors": buck.load_factors.tolist(), "about": buck.about}),
            )
            plot_buckling(system, buck, out / "buckling.png")
            res.figures.append(("buckling mode shapes", "buckling.png"))
            res.add_table(
                out,
                "Buckling about the reference configuration (critical load factors)",
                ["mode", "load factor"],
                [[i + 1, f"{f:.6g}"] for i, f in enumerate(buck.load_factors)],
                "buckling.csv",
            )
        else:  # simulate
            from rancf.runs.simulate import run_simulate

            info = {"scenario": str(scenario.resolve())}
            dynamic = run_simulate(
                sc, out / "run", info, MAX_EXAMPLE_GB, "the limit of an example run (GB)"
            )
            result, outputs, summary = dynamic.result, dynamic.outputs, dynamic.summary
            assert summary is not None  # a folder was given
            _notes(res, summary)
            _figures(res, out, out / "run", "simulation")
            names, vals = sensor_table(
                outputs, sc.sensors, result.q[-1:], result.v[-1:], t=result.t[-1:]
            )
            res.add_table(
                out,
                f"Simulation: {summary['status']}, t = {result.t_reached:g} s, "
                f"{result.n_steps} steps",
                ["sensor", "value at the end"],
                [[n, f"{v:.9g}"] for n, v in zip(names, vals[0], strict=True)],
                "simulate.csv",
            )
    return res.finish()
