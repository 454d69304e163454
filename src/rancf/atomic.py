"""Every file rancf writes: atomically, with the permissions the umask allows, errors naming it.

A file is written under a temporary name in its own folder (``.NAME.XXXXXX.EXT``), given the mode
``0666 & ~umask`` that any newly created file gets (``0644`` under umask ``0022``, ``0600`` under
``0077``; the temporary file itself starts as ``0600``), flushed to disk (the files of a set all
at the same time, before any is renamed), and renamed over the target with :func:`os.replace`,
atomic on POSIX and Windows.  If anything fails on the way (a full disk, an interrupt, an
exception of the writer) the temporary file is removed and the target is left as it was; an
:class:`OSError` that names no file (``No space left on device`` raised by a write) is re-raised
naming the target.

* :func:`atomic_path` — a temporary path, for writers that take a file name (Matplotlib,
  meshio, ezdxf, Pillow);
* :func:`atomic_file` — a binary file handle;
* :func:`atomic_write` — bytes or text;
* :class:`FileSet` — several files that replace their targets together: each is written under
  its temporary name, and only when all are written are they renamed (a run's CSV files and
  ``results.npz``, an export's ``.vtu`` files and ``.pvd``), so a failure leaves the earlier set
  untouched instead of a mix of old and new files.

The one implementation of atomic writing in rancf (layer 0: every package may use it).
"""

from __future__ import annotations

import contextlib
import os
import tempfile
import threading
from collections.abc import Iterator
from pathlib import Path
from typing import IO

__all__ = ["atomic_path", "atomic_file", "atomic_write", "FileSet", "umask", "file_mode"]

_UMASK_LOCK = threading.Lock()


def umask() -> int:
    """The process umask, read without changing it where the system allows (Linux
    ``/proc/self/status``); else set and restored under a lock, so that threads writing files at
    the same time (the worker threads of a local Dask cluster) never see a changed mask."""
    try:
        with open("/proc/self/status", encoding="ascii") as fh:
            for line in fh:
                if line.startswith("Umask:"):
                    return int(line.split()[1], 8)
    except (OSError, ValueError, IndexError):  # pragma: no cover - not Linux
        pass
    with _UMASK_LOCK:  # pragma: no cover - not Linux
        mask = os.umask(0o022)
        os.umask(mask)
    return mask  # pragma: no cover


def file_mode() -> int:
    """Permission bits of a new file: ``0o666 & ~umask``."""
    return 0o666 & ~umask()


def _named(exc: OSError, target: Path, tmp: str) -> OSError:
    """``exc`` naming ``target`` (not the temporary file, and not nothing)."""
    if exc.filename is not None and exc.filename not in (tmp, os.fsencode(tmp)):
        return exc
    new = OSError(exc.errno, exc.strerror or str(exc), str(target))
    return new


def _flush(tmp: str, target: Path) -> None:
    """``fsync`` the written file ``tmp`` (its data and mode); an error names ``target``."""
    try:
        fd = os.open(tmp, os.O_RDONLY)
        try:
            os.fsync(fd)
        finally:
            os.close(fd)
    except OSError as exc:
        raise _named(exc, target, tmp) from None


#: Most threads that flush a set's files at the same time.
FLUSH_THREADS = 8


def _flush_all(ready: list[tuple[str, Path]]) -> None:
    """Flush the files ``(tmp, target)`` at the same time (up to :data:`FLUSH_THREADS` threads):
    the file system then commits them together instead of one journal commit after another
    (the eight files of a run's checkpoint: a quarter to a half of the time on ext4).  Returns
    once every file is on disk; raises the first error."""
    if len(ready) < 2:
        for tmp, target in ready:
            _flush(tmp, target)
        return
    n = min(len(ready), FLUSH_THREADS)
    errors: list[BaseException] = []

    def share(k: int) -> None:
        for tmp, target in ready[k::n]:
            try:
                _flush(tmp, target)
            except BaseException as exc:  # noqa: BLE001 - handed to the caller's thread
                errors.append(exc)

    threads = [threading.Thread(target=share, args=(k,), daemon=True) for k in range(n)]
    for th in threads:
        th.start()
    for th in threads:
        th.join()
    if errors:
        raise errors[0]


class FileSet:
    """Files that replace their targets together (see the module docstring).

    Use as a context manager: the files given by :meth:`path` or :meth:`file` inside the block
    are renamed into place when it ends without error (:meth:`commit`), else removed
    (:meth:`discard`)::

        with FileSet() as files:
            with files.file(out / "a.csv") as fh:
                fh.write(b"...")
            with files.path(out / "b.png") as tmp:
                fig.savefig(tmp)
    """

    def __init__(self) -> None:
        self._ready: list[tuple[str, Path]] = []

    @contextlib.contextmanager
    def path(self, target: str | Path) -> Iterator[Path]:
        """A temporary file name beside ``target`` (same extension) for a writer to fill."""
        target = Path(target)
        try:
            fd, tmp = tempfile.mkstemp(
                prefix=f".{target.name}.", suffix=target.suffix, dir=target.parent
            )
        except OSError as exc:
            raise _named(exc, target, "") from None
        os.close(fd)
        try:
            yield Path(tmp)
            os.chmod(tmp, file_mode())
        except BaseException as exc:
            with contextlib.suppress(OSError):
                os.unlink(tmp)
            if isinstance(exc, OSError):
                raise _named(exc, target, tmp) from None
            raise
        self._ready.append((tmp, target))

    @contextlib.contextmanager
    def file(self, target: str | Path) -> Iterator[IO[bytes]]:
        """A binary file handle whose content becomes ``target``."""
        with self.path(target) as tmp, open(tmp, "wb") as fh:
            yield fh

    def write(self, target: str | Path, data: bytes | str) -> None:
        """``target``'s new content: bytes, or text written as UTF-8."""
        with self.file(target) as fh:
            fh.write(data.encode("utf-8") if isinstance(data, str) else data)

    def commit(self) -> None:
        """Flush every written file to disk, then rename each over its target (in the order they
        were written); if a flush fails, every file is removed and the targets stay as they
        were."""
        ready, self._ready = self._ready, []
        try:
            _flush_all(ready)
        except BaseException:
            for t, _ in ready:
                with contextlib.suppress(OSError):
                    os.unlink(t)
            raise
        for i, (tmp, target) in enumerate(ready):
            try:
                os.replace(tmp, target)
            except BaseException as exc:
                for t, _ in ready[i:]:
                    with contextlib.suppress(OSError):
                        os.unlink(t)
                if isinstance(exc, OSError):
                    raise _named(exc, target, tmp) from None
                raise

    def discard(self) -> None:
        """Remove the written files; the targets stay as they were."""
        ready, self._ready = self._ready, []
        for tmp, _ in ready:
            with contextlib.suppress(OSError):
                os.unlink(tmp)

    def __enter__(self) -> FileSet:
        return self

    def __exit__(self, kind: type | None, exc: BaseException | None, tb: object) -> None:
        if exc is None:
            self.commit()
        else:
            self.discard()


@contextlib.contextmanager
def atomic_path(path: str | Path) -> Iterator[Path]:
    """A temporary file name with ``path``'s extension, renamed to ``path`` when the block ends
    without error."""
    with FileSet() as files, files.path(path) as tmp:
        yield tmp


@contextlib.contextmanager
def atomic_file(path: str | Path) -> Iterator[IO[bytes]]:
    """A binary file handle whose content replaces ``path`` when the block ends without error."""
    with FileSet() as files, files.file(path) as fh:
        yield fh


def atomic_write(path: str | Path, data: bytes | str) -> None:
    """Replace ``path`` by ``data`` (bytes, or text written as UTF-8)."""
    with FileSet() as files:
        files.write(path, data)
