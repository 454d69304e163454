"""Paths the command line writes to: checked before any work, locked, and no partial output.

* :func:`check_out_dir` and :func:`check_plot_path` reject unusable paths up front, naming the
  option (``--out``, ``--plot``), the path and the reason (an empty name is refused: it would
  mean the current folder).
* :class:`OutputDir` creates a folder (and its missing parents), holds the folder's lock while
  the command writes, applies the output-folder policy of its ``kind``, and removes the folders
  it created if the command fails before :meth:`OutputDir.keep` is called.

The output-folder policy (docs/guide/outputs.md, *Output folders and files*):

* a run folder (``simulate --out``, ``static --out``) must be new or empty; an earlier run's
  folder (one holding ``summary.json``) is replaced, wholly, only with ``--overwrite``; any
  other non-empty folder is refused;
* a sweep folder must be new, empty, or an earlier sweep's folder (which is resumed);
* ``simulate --resume`` takes a new or empty folder, or an earlier run's folder (whose run goes
  on: :mod:`rancf.cli.resume`);
* the other commands (``plot``, ``export``, ``example``, ``report``) add their files to the
  folder, replacing files of the same name;
* while a command writes, the folder holds ``.rancf.lock`` naming the process; a second rancf
  process with the same output folder is refused with one line naming that process.  The lock
  is an advisory ``flock`` on that file, so a process that was killed holds no lock (where the
  file system has no ``flock``, a lock file naming a process that no longer runs is stale).
"""

from __future__ import annotations

import contextlib
import errno
import os
import shutil
import sys
from pathlib import Path
from types import TracebackType
from typing import Literal

from rancf.errors import InputError

if sys.platform != "win32":  # POSIX; elsewhere folders are not locked
    import fcntl

__all__ = ["check_out_dir", "check_plot_path", "OutputDir", "PLOT_FORMATS", "LOCK_NAME"]

#: File name extensions the figures can be written as (Matplotlib back ends).
PLOT_FORMATS = ("png", "pdf", "svg", "eps", "ps", "jpg", "jpeg", "tif", "tiff", "webp")

#: The lock file a command holds in its output folder while it writes.
LOCK_NAME = ".rancf.lock"

Kind = Literal["run", "resume", "sweep", "any"]


#: ``flock`` errors that mean another process holds the lock.
_HELD = (errno.EWOULDBLOCK, errno.EAGAIN, errno.EACCES)


def _stale(holder: list[str]) -> bool:
    """Whether a lock file naming ``holder`` (its process id) is left by a process that no
    longer runs (or names none)."""
    if not holder or not holder[0].isdigit():
        return True
    try:
        os.kill(int(holder[0]), 0)
    except ProcessLookupError:
        return True
    except OSError:
        return False
    return int(holder[0]) == os.getpid()


def _take(fd: int) -> int:
    """Write this process's id into the lock file ``fd``; returns ``fd``."""
    os.ftruncate(fd, 0)
    os.lseek(fd, 0, os.SEEK_SET)
    os.write(fd, f"{os.getpid()}\n".encode())
    return fd


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


def check_out_dir(path: str | Path, option: str = "--out") -> Path:
    """Validate an output directory: an existing directory, or one that can be created."""
    if str(path) == "":
        raise InputError(option, "", "a folder name (an empty name would mean the current folder)")
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


def _is_run_folder(path: Path) -> bool:
    return (path / "summary.json").is_file()


def _is_sweep_folder(path: Path) -> bool:
    return (path / "results.csv").is_file() or (path / "runs").is_dir()


class OutputDir:
    """Create or take ``path`` for a command's outputs under the policy of ``kind`` (module
    docstring); undo the creation unless :meth:`keep` was called.

    Files written into a folder that already existed are the caller's to clean up (write them
    through :mod:`rancf.atomic`, so a failure leaves no partial file).

    Parameters
    ----------
    path : Path
        The folder.
    option : str
        The option that named it (in error messages).
    kind : {"run", "sweep", "any"}
        The policy for a folder that is not empty.
    overwrite : bool
        ``kind = "run"``: replace an earlier run's folder.
    """

    def __init__(
        self, path: Path, option: str = "--out", kind: Kind = "any", overwrite: bool = False
    ) -> None:
        self.path = check_out_dir(path, option)
        self.option = option
        self.kind = kind
        self.overwrite = overwrite
        self.created: Path | None = None
        self.kept = False
        #: ``kind = "resume"``: the folder holds an earlier run.
        self.earlier_run = False
        self._lock: int | None = None

    def _fail(self, allowed: str) -> InputError:
        return InputError(self.option, str(self.path), allowed)

    def _mkdir(self) -> None:
        """Create the missing folders one by one; remember the first one this process made."""
        missing = []
        p = self.path.absolute()
        while not p.exists() and p != p.parent:
            missing.append(p)
            p = p.parent
        for p in reversed(missing):
            try:
                p.mkdir()
            except FileExistsError:
                continue  # made by another process meanwhile: not ours to remove
            except OSError as exc:
                raise self._fail(f"a directory that can be created ({exc.strerror})") from None
            if self.created is None:
                self.created = p
        if not self.path.is_dir():
            raise self._fail("an output directory (this path is an existing file)")

    def _acquire(self) -> None:
        """Hold ``.rancf.lock`` (an exclusive ``flock``) or refuse naming its holder."""
        if sys.platform == "win32":  # pragma: no cover - no flock
            return
        lock = self.path / LOCK_NAME
        for _ in range(10):
            try:
                fd = os.open(lock, os.O_RDWR | os.O_CREAT, 0o666)
            except OSError as exc:
                raise self._fail(f"a writable directory ({exc.strerror})") from None
            try:
                fcntl.flock(fd, fcntl.LOCK_EX | fcntl.LOCK_NB)
            except OSError as exc:
                holder = os.read(fd, 200).decode("ascii", "replace").split()
                if exc.errno not in _HELD and _stale(holder):  # no flock here: by the pid
                    self._lock = _take(fd)
                    return
                os.close(fd)
                who = f"process {holder[0]}" if holder else "another process"
                raise self._fail(
                    f"a folder no other rancf process is writing to ({who} is; see {lock})"
                ) from None
            try:
                same = os.fstat(fd).st_ino == os.stat(lock).st_ino
            except OSError:
                same = False
            if same:  # not a lock file its last holder removed meanwhile
                self._lock = _take(fd)
                return
            os.close(fd)
        raise self._fail("a folder whose lock can be taken")  # pragma: no cover

    def _release(self) -> None:
        if self._lock is None:
            return
        with contextlib.suppress(OSError):
            os.unlink(self.path / LOCK_NAME)
        os.close(self._lock)
        self._lock = None

    def _apply_policy(self) -> None:
        entries = sorted(p.name for p in self.path.iterdir() if p.name != LOCK_NAME)
        if not entries or self.kind == "any":
            return
        shown = ", ".join(entries[:3]) + (", ..." if len(entries) > 3 else "")
        if self.kind == "sweep":
            if not _is_sweep_folder(self.path):
                raise self._fail(
                    f"a new or empty folder, or an earlier sweep's folder to resume (it holds "
                    f"{shown}, and no results.csv)"
                )
            return
        if not _is_run_folder(self.path):
            raise self._fail(
                f"a new or empty folder (it holds {shown}, and is not a rancf run folder)"
            )
        if self.kind == "resume":
            self.earlier_run = True
            return
        if not self.overwrite:
            raise self._fail(
                f"a new or empty folder (it holds an earlier run: {shown}); add --overwrite to "
                "replace that run"
            )
        self._empty()

    def _empty(self) -> None:
        """Remove the earlier run, wholly (its plots/ and exports too)."""
        for p in self.path.iterdir():
            if p.name == LOCK_NAME:
                continue
            if p.is_dir() and not p.is_symlink():
                shutil.rmtree(p)
            else:
                p.unlink()

    def clear(self) -> None:
        """``kind = "resume"``: the earlier run has nothing to go on from (it wrote no
        checkpoint): remove it, so that the run starts anew."""
        if self.earlier_run:
            self._empty()
            self.earlier_run = False

    def __enter__(self) -> OutputDir:
        self._mkdir()
        try:
            self._acquire()
            if any(p.name != LOCK_NAME for p in self.path.iterdir()):
                self.created = None  # another process wrote here first: not ours to remove
            self._apply_policy()
        except BaseException:
            self._release()
            self._remove_empty()
            raise
        return self

    def _remove_empty(self) -> None:
        """Remove the folders this process created, as far as they are empty (a refused
        command leaves a folder another process has meanwhile written into alone)."""
        if self.created is None:
            return
        p = self.path.absolute()
        while True:
            try:
                p.rmdir()
            except OSError:
                return
            if p == self.created or p == p.parent:
                return
            p = p.parent

    def keep(self) -> None:
        """The command's results are in: keep the directory whatever happens next."""
        self.kept = True

    def _undo(self) -> None:
        if not self.kept and self.created is not None:
            shutil.rmtree(self.created, ignore_errors=True)

    def __exit__(
        self, kind: type | None, exc: BaseException | None, tb: TracebackType | None
    ) -> None:
        self._release()
        if exc is not None:
            self._undo()
