"""The ``rancf`` command line: a table of sub-commands and one error path.

Sub-commands live in their own modules; each registers its parsers with an ``add_parsers(sub)``
function listed in :data:`COMMAND_MODULES` with the commands it adds (add a line there to add
commands); a command line imports only the module of its command.  Heavy imports
(NumPy, the compiled core, Matplotlib) happen inside the commands, so ``rancf --help`` is fast
and an interrupt during them reaches the error path below.

Every expected failure ends here as one line on standard error, ``rancf: error: ...`` naming the
file, key or option, the value and what is allowed:

* bad input (options, scenario files, geometry), unusable or locked paths, unreadable or
  non-UTF-8 files, too large a run, an operating-system error before a run started (a full
  disk): exit status 2, and nothing written;
* a run that started and failed (no convergence, a full disk): exit status 3; its folder keeps
  the results of its last complete checkpoint and its ``summary.json`` says ``failed``;
* Ctrl-C (SIGINT) or SIGTERM at any moment: exit status 130 (a started run keeps its files);
* standard output closed early by the reader (``rancf conic --json | head``): exit status 141,
  silently, as a process killed by SIGPIPE;
* standard output closed before the start (``rancf ... >&-``), or failing (``> /dev/full``):
  exit status 2, with one line naming it.

Names that are not UTF-8 (a run folder given as raw bytes) are printed back as the same bytes.
"""

from __future__ import annotations

import argparse
import contextlib
import importlib
import os
import signal
import sys
from collections.abc import Callable, Sequence
from typing import Any, NoReturn

__all__ = ["main", "COMMAND_MODULES"]

#: Modules that register sub-commands, and their commands, in the order of ``rancf --help``.
COMMAND_MODULES: dict[str, tuple[str, ...]] = {
    "rancf.cli.conic": ("conic",),
    "rancf.cli.sim": ("simulate",),
    "rancf.cli.equilibrium": ("static", "modes", "buckling"),
    "rancf.cli.files": ("example", "report", "schema"),
    "rancf.cli.post": ("export", "plot", "animate", "cad"),
    "rancf.cli.sweep": ("sweep",),
    "rancf.cli.view": ("view",),
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
    with contextlib.suppress(OSError, ValueError, AttributeError):  # stderr may be gone too
        print(f"rancf: {message}", file=sys.stderr)
    return status


class StdoutError(Exception):
    """Standard output cannot be written (closed, or a full device)."""


class _Stdout:
    """Standard output whose write errors name it (other than a broken pipe: exit 141)."""

    def __init__(self, stream: Any) -> None:
        self._stream = stream

    def _call(self, name: str, *args: Any) -> Any:
        try:
            return getattr(self._stream, name)(*args)
        except BrokenPipeError:
            raise
        except (OSError, ValueError) as exc:
            reason = exc.strerror if isinstance(exc, OSError) and exc.strerror else str(exc)
            raise StdoutError(f"standard output: {reason}") from None

    def write(self, text: str) -> int:
        return self._call("write", text)

    def flush(self) -> None:
        self._call("flush")

    def __getattr__(self, name: str) -> Any:
        return getattr(self._stream, name)


def _open_stdout() -> str | None:
    """Make standard output name itself in errors and print undecodable names back as their
    bytes; returns why it cannot be used, or None."""
    stream = sys.stdout
    if stream is None:
        return "standard output is closed (redirect it to a file or to /dev/null)"
    if isinstance(stream, _Stdout):
        return None
    reconfigure = getattr(stream, "reconfigure", None)  # a text file's (io.TextIOWrapper)
    if reconfigure is not None:
        with contextlib.suppress(ValueError, OSError):
            reconfigure(errors="surrogateescape")
    sys.stdout = _Stdout(stream)
    return None


def _on_sigterm(signum: int, frame: Any) -> None:
    raise KeyboardInterrupt


def main(argv: Sequence[str] | None = None) -> int:
    """Entry point of the ``rancf`` console script; returns the exit status."""
    old_term = signal.getsignal(signal.SIGTERM)
    if old_term in (signal.SIG_DFL, None):
        signal.signal(signal.SIGTERM, _on_sigterm)
    old_int = signal.getsignal(signal.SIGINT)
    saved = sys.stdout
    try:
        closed = _open_stdout()
        if closed is not None:
            return _fail(f"error: {closed}", 2)
        return _dispatch(argv)
    except KeyboardInterrupt:
        signal.signal(signal.SIGINT, signal.SIG_IGN)  # a second Ctrl-C must not add a traceback
        return _fail("interrupted", 130)
    except BrokenPipeError:
        _silence_stdout()
        return 141
    except StdoutError as exc:
        _silence_stdout()
        return _fail(f"error: {exc}", 2)
    finally:
        sys.stdout = saved
        if old_term in (signal.SIG_DFL, None):
            signal.signal(signal.SIGTERM, signal.SIG_DFL)
        if old_int is not None:  # a caller in Python keeps its Ctrl-C after an interrupt
            signal.signal(signal.SIGINT, old_int)


def _dispatch(argv: Sequence[str] | None) -> int:
    from rancf.errors import (
        ConvergenceError,
        InputError,
        RancfError,
        RunFailedError,
        ScenarioError,
    )

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
    except RunFailedError as exc:
        return _fail(f"error: {_one_line(exc)}", 3)
    except RancfError as exc:
        return _fail(f"error: {_one_line(exc)}", 2)
    except BrokenPipeError:
        raise
    except MemoryError:
        return _fail("error: out of memory (make the model or the run smaller)", 2)
    except OSError as exc:
        where = f"{exc.filename}: " if exc.filename is not None else ""
        return _fail(f"error: {where}{exc.strerror or exc}", 2)


def _one_line(exc: BaseException) -> str:
    return " ".join(str(exc).split())


def _silence_stdout() -> None:
    """After a broken pipe or a failing standard output, point it at /dev/null so the
    interpreter's final flush is quiet."""
    try:
        devnull = os.open(os.devnull, os.O_WRONLY)
        os.dup2(devnull, sys.stdout.fileno())
    except (OSError, ValueError, AttributeError):  # pragma: no cover - stdout already gone
        pass


if __name__ == "__main__":  # pragma: no cover
    sys.exit(main())
