"""A finished command ends its process without the interpreter's teardown, losing nothing: the
output reaches a pipe whole, at-exit handlers run once, the exit status is the command's, and a
thread still running keeps the usual exit (which waits for it)."""

from __future__ import annotations

import json
import subprocess
import sys

#: Runs ``rancf ARGS`` as the console script does; a module-level object reports the teardown
#: (its finalizer runs only when the interpreter frees the module), a handler the at-exit run.
SCRIPT = """
import atexit, sys, threading, time
from pathlib import Path

class Witness:
    def __del__(self):
        sys.stderr.write("teardown\\n")

witness = Witness()
atexit.register(lambda: sys.stderr.write("at-exit handler\\n"))
if sys.argv[1] == "thread":  # a thread started as the command ends, still running at exit
    import rancf.cli
    marker, command = Path(sys.argv[2]), rancf.cli.main

    def main():
        status = command()
        threading.Thread(target=lambda: (time.sleep(0.3), marker.write_text("done"))).start()
        return status

    rancf.cli.main = main
sys.argv = ["rancf", *sys.argv[3:]]
from rancf.__main__ import run
sys.exit(run())
"""


def _rancf(*args: str, thread: str = "") -> subprocess.CompletedProcess:
    cmd = [sys.executable, "-c", SCRIPT, "thread" if thread else "-", thread or "-", *args]
    return subprocess.run(cmd, capture_output=True, text=True)


def test_a_finished_command_skips_the_teardown_and_loses_nothing():
    p = _rancf("schema")
    assert p.returncode == 0
    assert json.loads(p.stdout)["title"] == "rancf scenario"  # 60 kB through a pipe, whole
    assert p.stderr.splitlines() == ["at-exit handler"]  # once, and no teardown


def test_a_failed_command_keeps_its_status_and_message(tmp_path):
    p = _rancf("simulate", str(tmp_path / "missing.toml"), "--out", str(tmp_path / "run"))
    assert p.returncode == 2
    lines = p.stderr.splitlines()
    assert lines[0].startswith("rancf: error: ") and "missing.toml" in lines[0]
    assert lines[1:] == ["at-exit handler"]


def test_a_running_thread_keeps_the_usual_exit(tmp_path):
    marker = tmp_path / "marker"
    p = _rancf("--version", thread=str(marker))
    assert p.returncode == 0 and p.stdout.startswith("rancf ")
    assert marker.read_text() == "done"  # waited for
    assert p.stderr.splitlines() == ["at-exit handler", "teardown"]


def test_a_profiler_running_the_command_writes_its_report(tmp_path):
    """``python -m cProfile -m rancf``: rancf is not the program, the profiler writes after it."""
    out = tmp_path / "profile.out"
    p = subprocess.run(
        [sys.executable, "-m", "cProfile", "-o", str(out), "-m", "rancf", "--version"],
        capture_output=True,
        text=True,
    )
    assert p.returncode == 0 and p.stdout.startswith("rancf ")
    assert out.stat().st_size > 0
