"""The ``rancf`` command line: a table of sub-commands and one error path.

Sub-commands live in their own modules; each registers its parsers with an ``add_parsers(sub)``
function listed in :data:`COMMAND_MODULES` with the commands it adds (add a line there to add
commands); a command line imports only the module of its command.  Heavy imports
(NumPy, the compiled core, Matplotlib) happen inside the commands, so ``rancf --help`` is fast
and an interrupt during them reaches the error path below.

Every expected failure ends here as one line on standard error, ``rancf: error: ...`` naming the
file, key or option, the value and what is allowed:

* bad input (options, scenario files, geometry), unusable paths, unreadable or non-UTF-8 files,
  too large a run: exit status 2, and nothing written;
* a run that started and failed to converge: exit status 3 (results so far are kept);
* Ctrl-C (SIGINT) or SIGTERM at any moment: exit status 130 (a started run keeps its files);
* standard output closed early by the reader (``rancf conic --json | head``): exit status 141,
  silently, as a process killed by SIGPIPE.
"""

from __future__ import annotations

import argparse
import importlib
import os
import signal
import sys
from collections.abc import Callable, Sequence
from typing import Any, NoReturn

__all__ = ["main", "COMMAND_MODULES"]

#: Modules that register sub-commands, and their commands, in the order of ``rancf --help``.
COMMAND_MODULES: dict[str, tuple[str, ...]] = {
    "rancf.cli_conic": ("conic",),
    "rancf.cli_sim": ("simulate", "static", "modes"),
    "rancf.cli_equilibrium": ("buckling",),
    "rancf.cli_files": ("example", "report", "schema"),
    "rancf.cli_post": ("export", "plot", "animate", "cad"),
    "rancf.cli_sweep": ("sweep",),
}


class UsageError(Exception):
    """A command line argparse rejects (printed on one line, exit status 2)."""


class _Parser(argparse.ArgumentParser):
    def error(self, message: str) -> NoReturn:
        raise UsageError(f"{message} (see `{self.prog} --help`)")


def _version() -> str:
    from rancf import __version__

    return __version__


class _Version(argparse.Action):
    def __call__(self, parser: Any, namespace: Any, values: Any, option_string: Any = None) -> None:
        print(f"rancf {_version()}")
        parser.exit()


def build_parser(command: str | None = None) -> argparse.ArgumentParser:
    """The argument parser: of ``command``'s module alone, or of every sub-command."""
    p = _Parser(
        prog="rancf",
        description="Rational ANCF conic-section cable elements: geometry, CAD and dynamics.",
    )
    p.add_argument("--version", action=_Version, nargs=0, help="print the version and exit")
    sub = p.add_subparsers(dest="command", required=True, parser_class=_Parser)
    modules = [m for m, cmds in COMMAND_MODULES.items() if command in cmds] or COMMAND_MODULES
    for name in modules:
        importlib.import_module(name).add_parsers(sub)
    return p


def _fail(message: str, status: int) -> int:
    print(f"rancf: {message}", file=sys.stderr)
    return status


def _on_sigterm(signum: int, frame: Any) -> None:
    raise KeyboardInterrupt


def main(argv: Sequence[str] | None = None) -> int:
    """Entry point of the ``rancf`` console script; returns the exit status."""
    old_term = signal.getsignal(signal.SIGTERM)
    if old_term in (signal.SIG_DFL, None):
        signal.signal(signal.SIGTERM, _on_sigterm)
    try:
        return _dispatch(argv)
    except KeyboardInterrupt:
        signal.signal(signal.SIGINT, signal.SIG_IGN)  # a second Ctrl-C must not add a traceback
        return _fail("interrupted", 130)
    except BrokenPipeError:
        _silence_stdout()
        return 141
    finally:
        if old_term in (signal.SIG_DFL, None):
            signal.signal(signal.SIGTERM, signal.SIG_DFL)


def _dispatch(argv: Sequence[str] | None) -> int:
    from rancf.errors import ConvergenceError, InputError, RancfError, ScenarioError

    argv = sys.argv[1:] if argv is None else list(argv)
    try:
        args = build_parser(argv[0] if argv else None).parse_args(argv)
        func: Callable[[argparse.Namespace], int] = args.func
        status = func(args)
        sys.stdout.flush()
        return status
    except SystemExit as exc:  # --help, --version
        return int(exc.code or 0) if not isinstance(exc.code, str) else _fail(exc.code, 2)
    except UsageError as exc:
        return _fail(f"error: {exc}", 2)
    except (InputError, ScenarioError) as exc:
        return _fail(f"error: {_one_line(exc)}", 2)
    except ConvergenceError as exc:
        return _fail(f"did not converge: {_one_line(exc)}", 3)
    except RancfError as exc:
        return _fail(f"error: {_one_line(exc)}", 2)
    except BrokenPipeError:
        raise
    except MemoryError:
        return _fail("error: out of memory (make the model or the run smaller)", 2)
    except OSError as exc:
        where = exc.filename if exc.filename is not None else ""
        return _fail(f"error: {where}: {exc.strerror or exc}", 2)


def _one_line(exc: BaseException) -> str:
    return " ".join(str(exc).split())


def _silence_stdout() -> None:
    """After a broken pipe, point stdout at /dev/null so the interpreter's final flush is quiet."""
    try:
        devnull = os.open(os.devnull, os.O_WRONLY)
        os.dup2(devnull, sys.stdout.fileno())
    except (OSError, ValueError):  # pragma: no cover - stdout already gone
        pass


if __name__ == "__main__":  # pragma: no cover
    sys.exit(main())
