"""``rancf simulate --resume`` and ``--t-end``: the scenario a run goes on with, and the run
folder's checkpoint made ready for it (docs/guide/outputs.md, *Continuing a run*)."""

from __future__ import annotations

import os
import tomllib
from pathlib import Path
from typing import Any

from rancf.errors import InputError

__all__ = ["scenario_for_run", "Resume"]


def scenario_for_run(path: str, t_end: float | None) -> tuple[Any, str]:
    """The scenario of file ``path`` (``solver.t_end`` replaced by ``t_end`` if given) and the
    text the run folder keeps as ``scenario.toml``."""
    from rancf.scenario import load_scenario
    from rancf.scenario.scenario import Scenario
    from rancf.sweep.toml_out import dumps, scenario_copy, with_absolute_paths

    sc = load_scenario(path)  # the file's own errors first
    text = Path(path).read_text(encoding="utf-8")
    raw = tomllib.loads(text)
    if t_end is None:
        return sc, scenario_copy(text, raw, path)
    raw.setdefault("solver", {})["t_end"] = t_end
    return Scenario.from_dict(raw, str(path)), dumps(with_absolute_paths(raw, path))


def _first_difference(a: Any, b: Any, where: str = "") -> str | None:
    if isinstance(a, dict) and isinstance(b, dict):
        for key in sorted(set(a) | set(b)):
            at = f"{where}.{key}" if where else str(key)
            if key not in a or key not in b:
                return at
            found = _first_difference(a[key], b[key], at)
            if found:
                return found
        return None
    if isinstance(a, list) and isinstance(b, list) and len(a) == len(b):
        for i, (x, y) in enumerate(zip(a, b, strict=True)):
            found = _first_difference(x, y, f"{where}[{i}]")
            if found:
                return found
        return None
    return None if a == b else where


def _without_t_end(text: str) -> dict[str, Any]:
    raw = tomllib.loads(text)
    if isinstance(raw.get("solver"), dict):
        raw["solver"].pop("t_end", None)
    return raw


def _alive(pid: int) -> bool:
    try:
        os.kill(pid, 0)
    except ProcessLookupError:
        return False
    except OSError:  # exists, owned by another user
        return True
    return True


def _check_memory(state: Any, system: Any, options: Any) -> None:
    """Refuse a state whose integrator memory does not fit ``system`` and ``options``' Newton
    method (restored into an integrator of its own, as the run will)."""
    from rancf.solvers.generalized_alpha import GeneralizedAlpha

    o = options
    try:
        integ = GeneralizedAlpha(
            system, o.rho_inf, o.newton_tol, o.max_newton, o.newton, o.rtol, o.strain_error
        )
        integ.restore(state.memory, int(state.counters.get("n_factorizations", 0)))
    except (ValueError, TypeError):
        raise InputError(
            "state",
            f"memory of {state.memory.size} numbers",
            "an integrator memory of this system and its Newton method",
        ) from None


class Resume:
    """The run of a run folder, to go on with (``rancf simulate --resume``).

    Parameters
    ----------
    out : Path
        The run folder (locked by the caller).
    copy : str
        The ``scenario.toml`` text of the scenario the run goes on with.
    files : dict
        The digests of the files it reads (:func:`rancf.scenario.read_files.file_digests`).

    Raises
    ------
    InputError
        If the folder's run is of another scenario (anything but ``solver.t_end`` differs, or
        a file it reads changed since the run started).
    """

    def __init__(self, out: Path, copy: str, files: dict[str, str]) -> None:
        from rancf.post.resume import read_checkpoint, summary_of

        self.out = Path(out)
        self.summary = summary_of(out)
        try:
            earlier = (self.out / "scenario.toml").read_text(encoding="utf-8")
        except OSError:
            earlier = None
        if earlier is not None:
            key = _first_difference(_without_t_end(earlier), _without_t_end(copy))
            if key is not None:
                raise InputError(
                    "--resume",
                    str(out),
                    f"a run of the same scenario ({key} differs from "
                    f"the run's scenario.toml; only solver.t_end may change)",
                )
        self._check_files(files)
        self.state = read_checkpoint(self.out)
        if self.state is None and self.summary.get("status") != "running":
            raise InputError(
                "--resume",
                str(out),
                "a run folder with a checkpoint to go on from (it holds "
                "none: a static solution or a run of an older version; replace it with "
                "--overwrite instead of --resume)",
            )
        self.removed: list[str] = []

    def _check_files(self, files: dict[str, str]) -> None:
        """Refuse if a file the scenario reads (a CSV table, a CAD file) changed since the run
        started (``summary.json``'s ``input_files``; a run of an older version has none)."""
        from rancf.scenario.read_files import changed_file

        earlier = self.summary.get("input_files")
        if not isinstance(earlier, dict):
            return
        changed = changed_file(earlier, files)
        if changed is not None:
            raise InputError(
                "--resume",
                str(self.out),
                f"a run whose input files are as they were ({changed} "
                "changed since the run started; the run would mix the two; start it again with "
                "--overwrite)",
            )

    def take_up(self, system: Any, outputs: Any, options: Any) -> dict[str, Any]:
        """Check that the checkpoint fits ``system`` (and the integrator of ``options``) and
        read the rows up to it, then remove what the earlier run left besides (nothing in the
        folder changes before all is read).

        Returns
        -------
        dict
            The rows up to the checkpoint (:func:`rancf.post.resume.stored_rows`).

        Raises
        ------
        InputError
            Naming the checkpoint (or the results file) if it is damaged or of another system.
        """
        from rancf.post.resume import CHECKPOINT, remove_leftovers, stored_rows

        state = self.state
        assert state is not None
        rods = [b for b in system.flex if b.family.has_triads]
        sizes = [x.size for b in rods for x in (b.kernel.tref, b.kernel.m1ref)]
        try:
            state.check_finite()
            state.check_fits(system.n, system.m, sizes)
            _check_memory(state, system, options)
        except InputError as exc:
            raise InputError(
                "--resume",
                str(self.out / CHECKPOINT),
                f"a checkpoint this run can go on from "
                f"(it holds a state with {exc.value}; needed: {exc.allowed}); start the run "
                "again with --overwrite",
            ) from None
        rows = stored_rows(self.out, outputs, int(state.counters.get("n_outputs", 0)))
        self.removed = remove_leftovers(self.out)
        return rows

    def killed_note(self) -> str:
        """Why the earlier run stopped, as one clause."""
        s = self.summary
        pid = s.get("pid")
        if s.get("status") == "running" and isinstance(pid, int) and not _alive(pid):
            return f"the run was killed (process {pid} no longer runs)"
        return f"the run {s.get('status', 'stopped')}"

    def start_info(self) -> dict[str, Any]:
        """How the run started (``summary.json``'s ``initial_state`` and ``static``) and the
        times it was resumed at, this one last."""
        s = self.summary
        info = {k: s[k] for k in ("initial_state", "static") if k in s}
        assert self.state is not None
        info["resumed_at"] = [*s.get("resumed_at", []), self.state.t]
        return info
