"""``python -m rancf`` and the ``rancf`` console script.

Kept minimal: an interrupt while the command line's modules are still being imported ends with
the same one line and exit status 130 as any later interrupt.  A finished command ends its
process without the interpreter's teardown (:func:`_exit_now`).
"""

import os
import signal
import sys
from types import FrameType

#: Set by the first Ctrl-C: an import that an interrupt breaks can end in another exception
#: (NumPy's C modules turn it into an ``ImportError``), which is then the same interrupt.
_INTERRUPTED: list[int] = []


def _on_sigint(signum: int, frame: object) -> None:
    _INTERRUPTED.append(signum)
    raise KeyboardInterrupt


def run() -> int:
    """Import the command line and run it; Ctrl-C during the import exits 130 quietly, also
    when the interrupted import ends in another exception.

    After an interrupt the process ends with ``os._exit(130)`` once the output is flushed: an
    interrupt that passed through C-level code run by an extension's import can leave CPython
    set to re-raise SIGINT at exit, which would turn status 130 into "killed by SIGINT".
    """
    if signal.getsignal(signal.SIGINT) is signal.default_int_handler:
        signal.signal(signal.SIGINT, _on_sigint)
    try:
        from rancf.cli import main

        status = main()
    except KeyboardInterrupt:
        print("rancf: interrupted", file=sys.stderr)
        status = 130
    except Exception:
        if not _INTERRUPTED:
            raise
        print("rancf: interrupted", file=sys.stderr)  # an import broken by the interrupt
        status = 130
    if status == 130:
        signal.signal(signal.SIGINT, signal.SIG_IGN)  # a second Ctrl-C must not add a traceback
        for stream in (sys.stdout, sys.stderr):
            try:
                stream.flush()
            except (OSError, ValueError):
                pass
        os._exit(130)
    _exit_now(status)
    return status


def _flushed() -> bool:
    """Flush standard output and error; whether both took it (or are closed)."""
    for stream in (sys.stdout, sys.stderr):
        try:
            if stream is not None:
                stream.flush()
        except (OSError, ValueError):
            return False
    return True


#: The frames of runpy below a module run by ``python -m``.
_RUNPY = ("_run_code", "_run_module_as_main")


def _the_program() -> bool:
    """Whether :func:`run` was called by the program itself: the console script, ``python -m
    rancf`` or ``python -c``, with no tracer or profiler active (not under ``python -m cProfile
    -m rancf``, a coverage run or a test)."""
    if sys.gettrace() is not None or sys.getprofile() is not None:
        return False
    frame: FrameType | None
    try:
        frame = sys._getframe(3)  # the caller of run() (this function, _exit_now, run, it)
    except ValueError:  # run() called from outside Python (an embedding)
        return False
    if frame.f_code.co_name != "<module>":
        return False
    frame = frame.f_back
    while frame is not None:  # python -m rancf: runpy's two frames, nothing else
        code = frame.f_code
        if "runpy" not in code.co_filename or code.co_name not in _RUNPY:
            return False
        frame = frame.f_back
    return True


def _exit_now(status: int) -> None:
    """End the process with ``status`` at once, if nothing is left that the interpreter's own
    exit would still do; else return (and the interpreter exits as usual).

    That exit frees every module and object one by one before the process ends: after a run,
    30-50 ms in which nothing is written (the operating system frees the memory at once).  What
    matters of it is done here first: the standard streams are flushed and the at-exit handlers
    run.  Not when another thread is alive (the usual exit waits for it), a stream cannot be
    flushed (the usual exit then reports it as it always did), or :func:`run` is not the program
    itself (a profiler or coverage tool that runs it writes its report after it returns).
    """
    import atexit
    import threading

    if not _the_program() or threading.active_count() > 1 or not _flushed():
        return
    # the command is done and its output out: a late Ctrl-C must not break the exit with a
    # traceback (SIGTERM still ends a handler that hangs)
    old = signal.signal(signal.SIGINT, signal.SIG_IGN)
    atexit._run_exitfuncs()  # each handler once: this empties their list
    if _flushed():
        os._exit(status)
    signal.signal(signal.SIGINT, old)


if __name__ == "__main__":
    sys.exit(run())
