"""How ``rancf simulate`` streams a run to its folder (:class:`DiskStream`, a
:class:`rancf.runs.simulate.Stream`): an earlier run taken up (``--resume``), the rows stored as
they come, checkpoints, a progress bar on a terminal, and the folder's summary at the end."""

from __future__ import annotations

import argparse
import math
import os
import sys
import time
from pathlib import Path
from typing import Any

from rancf.cli.io import OutputDir

__all__ = ["DiskStream", "NothingToDo", "warn", "running", "PROGRESS_AFTER_S"]


def _process_age() -> float:
    """Seconds since this process started (Linux ``/proc``, to its clock tick, 0.01 s: rounded
    to it; else since the CLI was imported)."""
    try:
        with open("/proc/self/stat", encoding="ascii") as fh:
            start_ticks = int(fh.read().rsplit(")", 1)[1].split()[19])
        with open("/proc/uptime", encoding="ascii") as fh:
            uptime = float(fh.read().split()[0])
        ticks = os.sysconf("SC_CLK_TCK")  # 100: 2 decimals
        return max(0.0, round(uptime - start_ticks / ticks, len(str(ticks)) - 1))
    except (OSError, ValueError, IndexError):  # pragma: no cover - not Linux
        return time.monotonic() - _IMPORTED


_IMPORTED = time.monotonic()


def warn(notes: list[str]) -> list[str]:
    """Print each warning as one line on standard error; returns them."""
    for note in notes:
        print(f"rancf: warning: {note}", file=sys.stderr)
    return notes


def running(model: Any, t: float) -> dict[str, Any]:
    from rancf.post.results import run_sizes

    return {
        "status": "running",
        "message": f"running, t = {t:g} s",
        "t_reached": t,
        **run_sizes(model),
    }


class NothingToDo(Exception):
    """A resumed run already reached its end time ``t``."""

    def __init__(self, t: float) -> None:
        super().__init__(t)
        self.t = t


class DiskStream:
    """How ``rancf simulate`` streams a run to its folder (:class:`rancf.runs.simulate.Stream`):
    an earlier run taken up (``--resume``), the rows stored as they come
    (:class:`~rancf.post.history.HistoryStore`), checkpoints every ``every`` seconds, a progress
    bar on a terminal, and the folder's summary at the end; ``beside``: the rows are derived on
    the output worker's thread (:mod:`rancf.post.block_worker`), else between the steps."""

    def __init__(
        self,
        args: argparse.Namespace,
        sc: Any,
        copy: str,
        files: dict[str, str],
        od: OutputDir,
        stop: Any,
        every: float,
        beside: bool = False,
    ) -> None:
        self.args, self.sc, self.copy, self.files = args, sc, copy, files
        self.od, self.stop, self.every, self.beside = od, stop, every, beside
        self.store: Any = None
        self.notes: list[str] = []
        self.state: Any = None
        self._rows: dict[str, Any] = {}
        self._bar: list[Any] = []

    def start(self, plan: Any) -> tuple[Any, dict[str, Any]]:
        from rancf.cli.resume import Resume

        resume = Resume(self.od.path, self.copy, self.files) if self.od.earlier_run else None
        if resume is None or resume.state is None:
            return None, {}
        self._rows = resume.take_up(plan.system, plan.outputs, plan.options)  # all checked
        self.od.keep()  # the earlier run's files stay whatever happens
        self.state = resume.state
        if self.state.t >= plan.options.t_end * (1.0 - 1e-12):
            raise NothingToDo(self.state.t)
        if not self.args.quiet:
            print(
                f"rancf: {resume.killed_note()}; resuming from t = {self.state.t:g} s",
                file=sys.stderr,
            )
        return self.state, resume.start_info()

    def ready(self, plan: Any, start: dict[str, Any]) -> Any:
        from rancf.atomic import atomic_write
        from rancf.post.checks import before_run_warnings, element_notes
        from rancf.post.history import HistoryStore

        if self.state is None:
            self.od.clear()  # --resume of a run killed before its first checkpoint: anew
        self.notes = warn(before_run_warnings(plan.system, plan.options))  # the run goes on
        # defaults the file did not state (a harmonic's build-up), a curved spatial cable's
        notes = self.sc.notes + element_notes(plan.system)
        for note in notes:
            print(f"rancf: {note}", file=sys.stderr)
        info: dict[str, Any] = {
            "scenario": str(Path(self.args.scenario).resolve()),
            "setup_wall_time_s": None,
        }
        info["notes"] = notes
        info["input_files"] = self.files
        from rancf.kernels import _core

        info["threads"] = _core.assembly_threads()  # the element loops' (cli.sim.element_threads)
        info.update(start)
        self.store = HistoryStore(
            self.od.path, plan.outputs, {**info, "warnings": self.notes}, beside=self.beside
        )
        if self.state is not None:
            self.store.seed(self._rows)
        atomic_write(self.od.path / "scenario.toml", self.copy)
        t0 = 0.0 if self.state is None else self.state.t
        self.store.write_summary(running(plan.system, t0))
        self._plan = plan
        return self.store

    def callbacks(self) -> tuple[Any, Any, Any]:
        return _callbacks(self, self._plan)

    def flush(self) -> None:
        self.close_bar()
        self.store.flush()  # every row's derived outputs, the strain among them

    def finish(self, plan: Any, result: Any, warnings: list[str]) -> dict[str, Any]:
        from rancf.post.results import run_summary

        summary = run_summary(plan.system, result)
        self.store.info["warnings"] = warnings
        self.store.finish(summary, result.state)
        return {**summary, **self.store.info}

    def close_bar(self) -> None:
        if self._bar:
            self._bar[0].close()
            self._bar.clear()


#: A progress bar appears once a run has been stepping this long [s] (short runs stay silent).
PROGRESS_AFTER_S = 0.5


def _terminal(stream: Any) -> bool:
    """Whether ``stream`` is a terminal (a progress bar's carriage returns belong only there)."""
    try:
        return bool(stream.isatty())
    except (AttributeError, ValueError):  # closed or not a file
        return False


def _progress_bar(t_end: float, t: float) -> Any:
    from tqdm import tqdm  # imported only for runs long enough to show a bar

    return tqdm(
        total=t_end,
        initial=t,
        unit="s",
        file=sys.stderr,
        leave=False,
        bar_format="{l_bar}{bar}| t = {n:.4g}/{total:.4g} s [{elapsed}<{remaining}]",
    )


def _callbacks(disk: DiskStream, plan: Any) -> tuple[Any, Any, Any]:
    """``on_output``, ``should_stop`` and ``on_start`` of a streamed run: checkpoints every
    ``disk.every`` seconds (``disk.od.keep`` once the first is on disk) and a progress bar on a
    terminal."""
    from rancf.post.results import run_summary

    model, store, opts, state = plan.system, disk.store, plan.options, disk.state
    bar = disk._bar
    pace = {"next": time.monotonic() + disk.every, "every": disk.every, "bar": math.inf}

    def on_start() -> None:
        store.info["setup_wall_time_s"] = _process_age()
        t0 = 0.0 if state is None else state.t  # every file exists before the first step
        store.checkpoint(running(model, t0), state)
        disk.od.keep()
        if not disk.args.quiet and _terminal(sys.stderr):  # no carriage returns in logs
            pace["bar"] = time.monotonic() + PROGRESS_AFTER_S

    def on_output(t: float, snapshot: Any) -> None:
        if bar:
            bar[0].update(t - bar[0].n)
        elif time.monotonic() >= pace["bar"]:
            bar.append(_progress_bar(opts.t_end, t))
        now = time.monotonic()
        if now >= pace["next"]:
            now_at = snapshot()
            summary = {**run_summary(model, now_at), **running(model, t)}
            store.checkpoint(summary, now_at.state)
            took = time.monotonic() - now
            pace["next"] = time.monotonic() + max(pace["every"], 4.0 * took)

    return on_output, disk.stop, on_start
