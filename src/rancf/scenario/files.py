"""Scenario files: reading TOML with one-line errors, writing atomically, and validating without
losing a Ctrl-C."""

from __future__ import annotations

import contextlib
import signal
import tomllib
from collections.abc import Iterator
from pathlib import Path
from typing import Any

from rancf.errors import ScenarioError
from rancf.scenario.base import shorten

__all__ = ["deferred_interrupts", "read_toml", "write_atomic"]


@contextlib.contextmanager
def deferred_interrupts() -> Iterator[None]:
    """Hold SIGINT back while the block runs and deliver it afterwards.

    pydantic-core calls Python validators from compiled code and reports an exception raised in
    one as "ignored" (a traceback on stderr, the validation going on): a Ctrl-C arriving there
    would be lost. Blocked, it is delivered as ``KeyboardInterrupt`` once the block ends. Where
    signals cannot be blocked (Windows, a thread without the mask) the block runs as it is.
    """
    mask = getattr(signal, "pthread_sigmask", None)
    if mask is None:
        yield
        return
    try:
        old = mask(signal.SIG_BLOCK, {signal.SIGINT})
    except (OSError, ValueError):
        yield
        return
    try:
        yield
    finally:
        mask(signal.SIG_SETMASK, old)


def _shipped(name: str) -> bool:
    """Whether ``name`` is a shipped example scenario (``rancf example list``)."""
    from importlib import resources

    return resources.files("rancf.examples").joinpath(f"{name}.toml").is_file()


def read_toml(p: Path) -> dict[str, Any]:
    """The TOML file ``p`` as a dictionary; one line naming the file if it cannot be read."""
    try:
        data = p.read_bytes()
    except OSError as exc:
        hint = ""
        if not p.exists() and p.suffix == "" and _shipped(p.name):
            hint = f" (a shipped scenario: `rancf example copy {p.name} .` writes {p.name}.toml)"
        raise ScenarioError(str(p), "file", f"cannot be read: {exc.strerror}{hint}") from None
    try:
        text = data.decode("utf-8")
    except UnicodeDecodeError as exc:
        line = data[: exc.start].count(b"\n") + 1
        raise ScenarioError(
            str(p), "file", f"is not UTF-8 text (byte {exc.start}, line {line}); save it as UTF-8"
        ) from None
    try:
        return tomllib.loads(text)
    except RecursionError:
        raise ScenarioError(
            str(p), "file", "is nested too deeply (arrays or tables within each other)"
        ) from None
    except ValueError as exc:  # TOMLDecodeError, or an integer of more than 4300 digits
        raise ScenarioError(str(p), "file", f"is not valid TOML: {shorten(str(exc))}") from None


def write_atomic(path: Path, text: str) -> None:
    """Write ``text`` atomically with the umask's mode (:func:`rancf.atomic.atomic_write`);
    errors name the file."""
    from rancf.atomic import atomic_write

    try:
        atomic_write(path, text)
    except OSError as exc:
        raise ScenarioError(str(path), "file", f"cannot be written: {exc.strerror}") from None
