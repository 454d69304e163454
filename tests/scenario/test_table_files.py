"""``table = "path.csv"``: a time function's rows from a CSV file relative to the scenario file
(a header line, comments and blank lines allowed); bad files are refused in one line naming the
key, the file and the line; a run folder's copy names the file by its absolute path."""

from __future__ import annotations

import tomllib
from importlib.resources import files
from pathlib import Path

import numpy as np
import pytest

from rancf.cli import main
from rancf.scenario import load_scenario

CAPSTAN = (files("rancf.examples") / "capstan.toml").read_text(encoding="utf-8")


def _with_table(table: str) -> str:
    """The capstan example with its support's motion table replaced by ``table``."""
    i = CAPSTAN.index("table = [[0.0")
    j = CAPSTAN.index("[2.0, 0.0, -0.035]]") + len("[2.0, 0.0, -0.035]]")
    return CAPSTAN[:i] + f"table = {table}" + CAPSTAN[j:]


def test_a_table_from_a_csv_file_is_the_inline_table(tmp_path, monkeypatch):
    inline = np.array(tomllib.loads(CAPSTAN)["supports"][0]["motion"]["table"])
    folder = tmp_path / "case"
    folder.mkdir()
    lines = ["# pulled end: t [s], dx, dy [m]", "t, dx, dy", ""]
    lines += [", ".join(repr(float(x)) for x in row) for row in inline]
    (folder / "pull.csv").write_text("\n".join(lines) + "\n")
    (folder / "capstan.toml").write_text(_with_table('"pull.csv"'))
    monkeypatch.chdir(tmp_path)  # the file is found beside the scenario, not here
    sc = load_scenario("case/capstan.toml")
    f = sc.data["supports"][0]["motion"]
    np.testing.assert_array_equal(f.rows, inline)
    assert f.interpolation == "cubic"
    assert (
        main(["simulate", "case/capstan.toml", "--out", "run", "--quiet", "--t-end", "0.01"]) == 0
    )
    copy = tomllib.loads((tmp_path / "run" / "scenario.toml").read_text())
    assert copy["supports"][0]["motion"]["table"] == str((folder / "pull.csv").resolve())
    monkeypatch.chdir(folder)
    again = load_scenario(tmp_path / "run" / "scenario.toml")  # read from anywhere
    np.testing.assert_array_equal(again.data["supports"][0]["motion"].rows, inline)


@pytest.mark.parametrize(
    ("content", "needle"),
    [
        (None, "pull.csv does not exist"),
        ("0, 0, 0\n1, 0, oops\n", "pull.csv line 2: 'oops' is not a number"),
        ("0, 0, 0\n1, 0\n", "pull.csv line 2: 2 numbers, but the first row has 3"),
        ("t, x, y\n0, 0, 0\n", "holds 1 rows of numbers: at least 2"),
        ("0, 0, 0\n1, 0, nan\n", "pull.csv line 2: the numbers must be finite"),
        ("0, 0, 0\n0, 0, 1\n", "supports[0].motion.table[1][0]] times must increase"),
    ],
    ids=["missing", "word", "ragged", "one-row", "nan", "times"],
)
def test_bad_table_files_are_refused_in_one_line(tmp_path, monkeypatch, capsys, content, needle):
    monkeypatch.chdir(tmp_path)
    if content is not None:
        (tmp_path / "pull.csv").write_text(content)
    (tmp_path / "s.toml").write_text(_with_table('"pull.csv"'))
    assert main(["simulate", "s.toml", "--out", "run", "--quiet"]) == 2
    err = capsys.readouterr().err.strip()
    assert len(err.splitlines()) == 1 and needle in err, err
    assert err.startswith("rancf: error: s.toml: [supports[0].motion.table")
    assert not Path("run").exists()


def _csv_case(folder: Path, scale: float = 1.0) -> None:
    """The capstan with its motion table in ``pull.csv`` (scaled by ``scale``), beside it."""
    inline = np.array(tomllib.loads(CAPSTAN)["supports"][0]["motion"]["table"])
    inline[:, 1:] *= scale
    lines = [", ".join(repr(float(x)) for x in row) for row in inline]
    (folder / "pull.csv").write_text("\n".join(lines) + "\n")
    (folder / "capstan.toml").write_text(_with_table('"pull.csv"'))


def test_a_sweep_runs_again_after_its_table_file_changed(tmp_path, monkeypatch, capsys):
    """A finished run is reused only while the CSV file it read is as it was."""
    monkeypatch.chdir(tmp_path)
    _csv_case(tmp_path)
    Path("sweep.toml").write_text(
        'base = "capstan.toml"\nanalysis = "simulate"\n[grid]\n"solver.t_end" = [0.01]\n'
    )
    argv = ["sweep", "sweep.toml", "--out", "out", "--threads", "1", "--quiet"]
    assert main(argv) == 0
    assert main(argv) == 0
    assert "1 already finished" in capsys.readouterr().out
    _csv_case(tmp_path, scale=2.0)  # the same path, other rows
    assert main(argv) == 0
    assert "0 already finished, 1 run" in capsys.readouterr().out


def test_resume_refuses_a_changed_table_file(tmp_path, monkeypatch, capsys):
    """A resumed run reads the table its first part read, or is refused."""
    monkeypatch.chdir(tmp_path)
    _csv_case(tmp_path)
    args = ["simulate", "capstan.toml", "--out", "run", "--quiet"]
    assert main([*args, "--t-end", "0.01"]) == 0
    summary = (tmp_path / "run" / "summary.json").read_bytes()
    _csv_case(tmp_path, scale=2.0)
    capsys.readouterr()
    assert main([*args, "--resume", "--t-end", "0.02"]) == 2
    err = capsys.readouterr().err.strip()
    assert len(err.splitlines()) == 1, err
    assert f"{(tmp_path / 'pull.csv').resolve()} changed since the run started" in err, err
    assert (tmp_path / "run" / "summary.json").read_bytes() == summary
    _csv_case(tmp_path)  # back as it was: the run goes on
    assert main([*args, "--resume", "--t-end", "0.02"]) == 0


def test_a_byte_order_mark_keeps_the_first_row(tmp_path):
    """A CSV saved with a byte-order mark (spreadsheets do) loses no row to a 'header'
    as a header."""
    inline = np.array(tomllib.loads(CAPSTAN)["supports"][0]["motion"]["table"])
    lines = [", ".join(repr(float(x)) for x in row) for row in inline]
    (tmp_path / "pull.csv").write_text("\n".join(lines) + "\n", encoding="utf-8-sig")
    (tmp_path / "s.toml").write_text(_with_table('"pull.csv"'))
    f = load_scenario(tmp_path / "s.toml").data["supports"][0]["motion"]
    np.testing.assert_array_equal(f.rows, inline)


def test_the_files_a_scenario_reads_are_fingerprinted_by_content(tmp_path):
    """Every CSV table and CAD file, in a one-body file or in [[bodies]], relative to the
    scenario's folder; a digest changes with the content, not only with the name."""
    from rancf.scenario.read_files import changed_file, file_digests, read_file_paths

    raw = {
        "geometry": {"kind": "cad", "file": "top.step"},
        "bodies": [{"geometry": {"kind": "cad", "file": "/abs/leg.iges"}}],
        "supports": [{"motion": {"table": "pull.csv"}}],
        "winches": [{"length": {"table": "sub/reel.csv"}}],
    }
    scenario = tmp_path / "s.toml"
    assert read_file_paths(raw, scenario) == sorted(
        [
            tmp_path / "top.step",
            Path("/abs/leg.iges"),
            tmp_path / "pull.csv",
            tmp_path / "sub" / "reel.csv",
        ]
    )
    (tmp_path / "pull.csv").write_text("0, 0\n1, 1\n")
    before = file_digests(raw, scenario)
    assert before[str(tmp_path / "top.step")] == "unreadable"
    (tmp_path / "pull.csv").write_text("0, 0\n1, 2\n")
    assert changed_file(before, file_digests(raw, scenario)) == str(tmp_path / "pull.csv")


def test_a_run_folders_copy_names_every_cad_file_absolutely(tmp_path):
    """A body's CAD file ([bodies.geometry]) is made absolute in a run folder's copy as the
    one-body file's is (it stayed relative, read against the run folder)."""
    from rancf.sweep.toml_out import with_absolute_paths

    raw = {
        "bodies": [{"name": "a", "geometry": {"kind": "cad", "file": "leg.step"}}],
        "geometry": {"kind": "cad", "file": "top.step"},
    }
    out = with_absolute_paths(raw, tmp_path / "s.toml")
    assert out["bodies"][0]["geometry"]["file"] == str(tmp_path / "leg.step")
    assert out["geometry"]["file"] == str(tmp_path / "top.step")
    assert raw["bodies"][0]["geometry"]["file"] == "leg.step"  # a copy
