"""``static``, ``modes`` and ``buckling`` of every shipped one-body example, written as a one-body
file and in its one-``[[bodies]]`` form (:func:`rancf.scenario.as_bodies`): one system, so the
same answer (1e-9 of each number's scale) or the same one-line refusal, and the same output
format (the support labels are the places as each file writes them: ``start``, ``body:start``)."""

from __future__ import annotations

import json
import shutil

import numpy as np
import pytest

from rancf.cli import main
from rancf.scenario import as_bodies, load_scenario
from rancf.studies.common import EXAMPLES, SCENARIO_ANALYSES, example_path

ONE_BODY = [
    n
    for n in sorted(set(EXAMPLES) | set(SCENARIO_ANALYSES))
    if not load_scenario(example_path(n)).bodies
]
COMMANDS = (["static"], ["modes", "--count", "3"], ["buckling", "--count", "2"])


def _numbers(doc, path: str = "") -> dict[str, float]:
    """Every number of a JSON document by its path (the support labels' body prefix dropped)."""
    if isinstance(doc, dict):
        return {k: v for key, val in doc.items() for k, v in _numbers(val, f"{path}/{key}").items()}
    if isinstance(doc, list):
        return {k: v for i, val in enumerate(doc) for k, v in _numbers(val, f"{path}/{i}").items()}
    if isinstance(doc, bool) or not isinstance(doc, int | float) or "wall_time" in path:
        return {}
    return {path: float(doc)}


def _strings(doc) -> list[str]:
    if isinstance(doc, dict):
        return [s for key, val in doc.items() for s in [key, *_strings(val)]]
    if isinstance(doc, list):
        return [s for val in doc for s in _strings(val)]
    return [doc] if isinstance(doc, str) else []


@pytest.mark.parametrize("name", ONE_BODY)
def test_every_analysis_gives_the_same_answer_in_both_forms(tmp_path, capsys, name):
    sc = load_scenario(example_path(name))
    sc.save(tmp_path / "one.toml")
    as_bodies(sc).save(tmp_path / "bodies.toml")
    for cmd in COMMANDS:
        results = []
        for form in ("one", "bodies"):
            out = tmp_path / f"{form}-{cmd[0]}"
            code = main(
                [
                    cmd[0],
                    str(tmp_path / f"{form}.toml"),
                    *cmd[1:],
                    "--json",
                    *(["--out", str(out)] if cmd[0] == "static" else []),
                ]
            )
            captured = capsys.readouterr()
            results.append((code, captured.out, captured.err, out))
        (ca, oa, ea, da), (cb, ob, eb, db) = results
        assert ca == cb, (cmd, ea, eb)
        if ca != 0:  # the same refusal, in one line (naming its own file and key)
            ea = ea.replace(str(tmp_path / "one.toml"), "FILE")
            eb = eb.replace(str(tmp_path / "bodies.toml"), "FILE").replace("[bodies[0].", "[")
            assert ea == eb and len(ea.splitlines()) == 1, cmd
            continue
        a, b = json.loads(oa), json.loads(ob)
        na, nb = _numbers(a), _numbers(b)
        assert sorted(na) == sorted(nb), cmd  # the same format
        scale = max((abs(v) for v in na.values()), default=1.0)
        for key, val in na.items():
            assert (
                abs(val - nb[key]) <= 1e-9 * max(abs(val), 1e-300)
                or abs(val - nb[key]) <= 1e-12 * scale
            ), (cmd, key, val, nb[key])
        labels_a = [s for s in _strings(a.get("reactions", []))]
        labels_b = [s.removeprefix("body:") for s in _strings(b.get("reactions", []))]
        assert labels_a == labels_b, cmd
        if cmd[0] == "static":  # the same run folder, file by file
            files = sorted(p.relative_to(da).as_posix() for p in da.rglob("*") if p.is_file())
            assert files == sorted(
                p.relative_to(db).as_posix() for p in db.rglob("*") if p.is_file()
            )
            shell = "bodies/body/body.pvd" in files  # a shell's folder holds its surfaces
            assert shell or "bodies/body/along.csv" in files
            along = [] if shell else ["bodies/body/along.csv"]
            for f in along:
                ta = np.genfromtxt(da / f, delimiter=",", names=True)
                tb = np.genfromtxt(db / f, delimiter=",", names=True)
                assert ta.dtype.names == tb.dtype.names
                for col in ta.dtype.names:
                    scale = max(float(np.abs(ta[col]).max()), 1e-300)
                    assert np.abs(ta[col] - tb[col]).max() <= 1e-9 * scale, col
            shutil.rmtree(da), shutil.rmtree(db)
