"""Paths the command line writes to: checked before any work, and no partial output on failure.

* :func:`check_out_dir` and :func:`check_plot_path` reject unusable paths up front, naming the
  option (``--out``, ``--plot``), the path and the reason.
* :class:`OutputDir` creates a directory (and its missing parents) and removes what it created
  if the command fails before :meth:`OutputDir.keep` is called.
* :func:`atomic_path` gives a temporary file name next to the target; the target appears only
  when the block succeeds.
"""

from __future__ import annotations

import contextlib
import os
import shutil
import tempfile
from collections.abc import Iterator
from pathlib import Path
from types import TracebackType

from rancf.errors import InputError

__all__ = ["check_out_dir", "check_plot_path", "OutputDir", "atomic_path", "PLOT_FORMATS"]

#: File name extensions the figures can be written as (Matplotlib back ends).
PLOT_FORMATS = ("png", "pdf", "svg", "eps", "ps", "jpg", "jpeg", "tif", "tiff", "webp")


def _existing_parent(path: Path) -> Path:
    p = path.absolute()
    while not p.exists() and p != p.parent:
        p = p.parent
    return p


def _writable(option: str, path: Path, target: str) -> None:
    parent = _existing_parent(path)
    if not parent.is_dir():
        raise InputError(option, str(path), f"{target} (but {parent} is a file, not a directory)")
    if not os.access(parent, os.W_OK | os.X_OK):
        raise InputError(option, str(path), f"{target} ({parent} is not writable)")


def check_out_dir(path: str, option: str = "--out") -> Path:
    """Validate an output directory: an existing directory, or one that can be created."""
    out = Path(path)
    if out.exists() and not out.is_dir():
        raise InputError(option, str(out), "an output directory (this path is an existing file)")
    _writable(option, out, "a directory that can be created and written")
    return out


def check_plot_path(path: str, option: str = "--plot") -> Path:
    """Validate a figure file name: a supported extension, in an existing writable directory."""
    p = Path(path)
    ext = p.suffix.lower().lstrip(".")
    if ext not in PLOT_FORMATS:
        allowed = ", ".join(f".{e}" for e in PLOT_FORMATS)
        raise InputError(option, str(p), f"a file name ending in one of {allowed}")
    if p.is_dir():
        raise InputError(option, str(p), "a file name (this path is a directory)")
    parent = p.absolute().parent
    if parent.exists() and not parent.is_dir():
        raise InputError(option, str(p), f"a file in a directory ({parent} is a file)")
    if not parent.is_dir():
        raise InputError(option, str(p), f"a file in an existing directory ({parent} is missing)")
    if not os.access(parent, os.W_OK | os.X_OK):  # an existing figure is replaced
        raise InputError(
            option, str(p), f"a file in a writable directory ({parent} is not writable)"
        )
    return p


class OutputDir:
    """Create ``path`` for a command's outputs; undo the creation unless :meth:`keep` was called.

    Files written into a directory that already existed are the caller's to clean up (use
    :func:`atomic_path` or :func:`rancf.post.results.atomic_file`).
    """

    def __init__(self, path: Path, option: str = "--out") -> None:
        self.path = check_out_dir(str(path), option)
        self.option = option
        self.created: Path | None = None
        self.kept = False

    def __enter__(self) -> OutputDir:
        top = _existing_parent(self.path)
        try:
            self.path.mkdir(parents=True, exist_ok=True)
        except OSError as exc:
            raise InputError(
                self.option, str(self.path), f"a directory that can be created ({exc.strerror})"
            ) from None
        if top != self.path.absolute():
            rel = self.path.absolute().relative_to(top)
            self.created = top / rel.parts[0]
        return self

    def keep(self) -> None:
        """The command's results are in: keep the directory whatever happens next."""
        self.kept = True

    def __exit__(
        self, kind: type | None, exc: BaseException | None, tb: TracebackType | None
    ) -> None:
        if exc is not None and not self.kept and self.created is not None:
            shutil.rmtree(self.created, ignore_errors=True)


@contextlib.contextmanager
def atomic_path(path: Path) -> Iterator[Path]:
    """A temporary file name with the same extension, renamed to ``path`` when the block ends."""
    fd, tmp = tempfile.mkstemp(prefix=f".{path.name}.", suffix=path.suffix, dir=path.parent)
    os.close(fd)
    try:
        yield Path(tmp)
        mask = os.umask(0o022)
        os.umask(mask)
        os.chmod(tmp, 0o666 & ~mask)
        os.replace(tmp, path)
    except BaseException:
        with contextlib.suppress(OSError):
            os.unlink(tmp)
        raise
