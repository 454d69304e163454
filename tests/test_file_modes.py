"""Every file and folder a command writes gets the permissions the umask allows:
``0666 & ~umask`` for files, ``0777 & ~umask`` for folders, as a plain ``open`` and ``mkdir``
would give.  Files are written under a temporary name (created ``0600``) and renamed: under
umask 0022 a forgotten ``chmod`` shows as ``0600`` instead of ``0644``."""

from __future__ import annotations

import os
from pathlib import Path

import pytest

from rancf.atomic import FileSet, atomic_write, file_mode
from rancf.cli import main
from tests.test_cli_errors import LINE, ROD, mutated

CONIC = ["conic", "--chord", "0.5", "--angles", "30", "40", "--point", "0.315", "0.077"]
SWEEP = """base = "c.toml"
analysis = "static"
[grid]
"mesh.elements" = [2, 3]
"""


def _modes(root: Path, since: set[Path]) -> dict[str, int]:
    """Permission bits of every path under ``root`` that is not in ``since``."""
    return {
        str(p.relative_to(root)): p.stat().st_mode & 0o777
        for p in sorted(root.rglob("*"))
        if p not in since
    }


def _check(root: Path, since: set[Path], umask: int) -> dict[str, int]:
    modes = _modes(root, since)
    want = {name: (0o777 if (root / name).is_dir() else 0o666) & ~umask for name in modes}
    assert modes == want
    hidden = [n for n in modes if Path(n).name.startswith(".")]
    assert not hidden, f"temporary or lock files left: {hidden}"
    return modes


def _commands(tmp: Path) -> list[list[str]]:
    (tmp / "s.toml").write_text(mutated(solver__t_end=0.01))
    (tmp / "rod.toml").write_text(ROD)
    clamped = {"supports": [{"at": 0, "kind": "clamp"}], "geometry": LINE}
    (tmp / "c.toml").write_text(
        mutated(**clamped, loads={"point": [{"at": -1, "force": [0, -1e-3]}]})
    )
    (tmp / "sweep.toml").write_text(SWEEP)
    (tmp / "adir").mkdir()
    cmds = [
        ["simulate", "s.toml", "--out", "run", "--quiet"],
        ["simulate", "rod.toml", "--out", "rodrun", "--quiet"],
        ["static", "c.toml", "--out", "eq"],
        ["modes", "rod.toml", "--plot", "modes.png", "--count", "2"],
        [*CONIC, "--plot", "conic.png"],
        ["export", "run", "--vtk", "vtk"],
        ["export", "rodrun", "--vtk", "adir/rodvtk"],
        ["export", "run", "--nurbs", "shape.json"],
        ["export", "run", "--nurbs", "shape.dxf"],
        ["plot", "run"],
        ["plot", "eq", "--out", "eqplots"],
        ["animate", "run", "--out", "run.gif", "--every", "5"],
        ["view", "run", "--frames", "2"],
        ["example", "copy", "cantilever", "copies"],
        ["sweep", "sweep.toml", "--out", "sw", "--workers", "1", "--quiet"],
    ]
    try:
        import OCP  # noqa: F401 - the optional CAD extra

        cmds += [["export", "run", "--nurbs", "shape.step"]]
        cmds += [["export", "run", "--nurbs", "shape.iges"]]
    except ImportError:
        pass
    return cmds


@pytest.mark.parametrize("umask", [0o022, 0o077])
def test_every_command_honours_the_umask(tmp_path, monkeypatch, capsys, umask):
    monkeypatch.chdir(tmp_path)
    cmds = _commands(tmp_path)
    before = set(tmp_path.rglob("*"))
    old = os.umask(umask)
    try:
        for argv in cmds:
            assert main(argv) == 0, (argv, capsys.readouterr().err)
    finally:
        os.umask(old)
    modes = _check(tmp_path, before, umask)
    written = {Path(n).suffix for n in modes}
    assert {".csv", ".npz", ".json", ".toml", ".png", ".gif", ".vtu", ".pvd", ".dxf"} <= written
    assert "sw/results.csv" in modes and "run/plots/configurations.png" in modes


@pytest.mark.parametrize("umask", [0o022, 0o077])
def test_the_helper_follows_the_umask_and_names_the_file(tmp_path, umask):
    old = os.umask(umask)
    try:
        assert file_mode() == 0o666 & ~umask
        atomic_write(tmp_path / "a.txt", "x")
        with FileSet() as files:
            files.write(tmp_path / "b.txt", b"y")
            files.write(tmp_path / "c.txt", b"z")
    finally:
        os.umask(old)
    assert _modes(tmp_path, set()) == dict.fromkeys(["a.txt", "b.txt", "c.txt"], 0o666 & ~umask)


def test_a_file_set_replaces_all_or_nothing(tmp_path):
    for name in ("a.csv", "b.npz"):
        (tmp_path / name).write_text("old")
    with pytest.raises(RuntimeError), FileSet() as files:
        files.write(tmp_path / "a.csv", "new")
        files.write(tmp_path / "b.npz", "new")
        raise RuntimeError("the third file failed")
    assert [(p.name, p.read_text()) for p in sorted(tmp_path.iterdir())] == [
        ("a.csv", "old"),
        ("b.npz", "old"),
    ]


def test_a_failed_write_names_its_target(tmp_path):
    def fail(tmp: Path) -> None:
        raise OSError(28, "No space left on device")  # as a write on a full disk: no file name

    with pytest.raises(OSError) as info, FileSet() as files, files.path(tmp_path / "r.npz") as t:
        fail(t)
    assert info.value.filename == str(tmp_path / "r.npz")
    assert list(tmp_path.iterdir()) == []


def test_a_file_set_is_flushed_whole_before_any_file_is_renamed(tmp_path, monkeypatch):
    """Every file of a set is flushed to disk (at the same time, on threads) before the first
    rename: a crash leaves the old set or the new one, never a renamed file not yet on disk."""
    events: list[tuple[str, str]] = []
    fsync, replace = os.fsync, os.replace

    def logged_fsync(fd: int) -> None:
        fsync(fd)
        events.append(("fsync", os.path.basename(os.readlink(f"/proc/self/fd/{fd}"))))

    def logged_replace(src: str, dst: str) -> None:
        events.append(("replace", os.path.basename(src)))
        replace(src, dst)

    if not os.path.isdir("/proc/self/fd"):
        pytest.skip("needs /proc to name a descriptor's file")
    monkeypatch.setattr(os, "fsync", logged_fsync)
    monkeypatch.setattr(os, "replace", logged_replace)
    names = [f"f{i}.csv" for i in range(11)]  # more files than flushing threads
    with FileSet() as files:
        for name in names:
            files.write(tmp_path / name, name)
    kinds = [k for k, _ in events]
    assert kinds == ["fsync"] * len(names) + ["replace"] * len(names)
    flushed = sorted(n for k, n in events if k == "fsync")
    assert flushed == sorted(n for k, n in events if k == "replace")  # each temporary file once
    assert all(n.startswith(".f") for n in flushed)
    assert sorted(p.name for p in tmp_path.iterdir()) == sorted(names)
    assert all((tmp_path / n).read_text() == n for n in names)


def test_a_failed_flush_keeps_the_old_set_and_names_a_target(tmp_path, monkeypatch):
    for name in ("a.csv", "b.npz", "c.json"):
        (tmp_path / name).write_text("old")
    fsync = os.fsync

    def fail_on_b(fd: int) -> None:
        if ".b.npz." in os.readlink(f"/proc/self/fd/{fd}"):
            raise OSError(5, "Input/output error")  # as the disk reports it: no file name
        fsync(fd)

    if not os.path.isdir("/proc/self/fd"):
        pytest.skip("needs /proc to name a descriptor's file")
    monkeypatch.setattr(os, "fsync", fail_on_b)
    with pytest.raises(OSError) as info, FileSet() as files:
        for name in ("a.csv", "b.npz", "c.json"):
            files.write(tmp_path / name, "new")
    assert info.value.filename == str(tmp_path / "b.npz")
    assert info.value.strerror == "Input/output error"
    assert [(p.name, p.read_text()) for p in sorted(tmp_path.iterdir())] == [
        ("a.csv", "old"),
        ("b.npz", "old"),
        ("c.json", "old"),
    ]
