import json
import subprocess
import sys

import numpy as np
import pytest

from rancf.cli import main


def run(capsys, *argv):
    code = main(list(argv))
    out, err = capsys.readouterr()
    return code, out, err


def test_conic_json_example1(capsys):
    code, out, _ = run(
        capsys,
        "conic",
        "--chord",
        "0.5",
        "--angles",
        "30",
        "40",
        "--point",
        "0.315",
        "0.077",
        "--json",
        "--elements",
        "3",
    )
    assert code == 0
    d = json.loads(out)
    assert d["type"] == "ellipse"
    assert d["omega"] == pytest.approx(0.86501, abs=5e-6)
    assert d["kopt"] == pytest.approx(0.4065, abs=5e-4)
    assert d["k"] == pytest.approx(d["kopt"])
    assert d["gradient_ratio"] == pytest.approx(1.042, abs=5e-4)
    assert d["arc_length"] == pytest.approx(0.53303, abs=5e-6)
    assert len(d["elements"]) == 3
    for e in d["elements"]:
        assert set(e) >= {"k", "weights", "nodal_coordinates", "gradient_ratio"}
        assert len(e["weights"]) == 4 and len(e["nodal_coordinates"]) == 8
    # shared nodes: the end of element j is the start of element j + 1
    e = np.array([x["nodal_coordinates"] for x in d["elements"]])
    assert np.allclose(e[:-1, 4:], e[1:, :4], atol=1e-14)


@pytest.mark.parametrize(("k", "ratio"), [("0.2", 1.960), ("0.6", 1.685)])
def test_conic_json_given_k(capsys, k, ratio):
    code, out, _ = run(
        capsys,
        "conic",
        "--chord",
        "0.5",
        "--angles",
        "30",
        "40",
        "--point",
        "0.315",
        "0.077",
        "--json",
        "--k",
        k,
    )
    d = json.loads(out)
    assert code == 0 and d["k"] == float(k)
    assert d["gradient_ratio"] == pytest.approx(ratio, abs=5e-4)
    assert d["elements"][0]["gradient_ratio"] == pytest.approx(ratio, abs=5e-4)


def test_conic_plot(tmp_path, capsys):
    f = tmp_path / "c.png"
    code, out, _ = run(
        capsys,
        "conic",
        "--chord",
        "0.5",
        "--angles",
        "30",
        "30",
        "--point",
        "0.25",
        "0.067",
        "--plot",
        str(f),
    )
    assert code == 0 and f.stat().st_size > 10_000
    assert "Kopt            0.5000" in out


BAD = [
    (["--angles", "0", "40", "--point", "0.3", "0.05"], "angles"),
    (["--angles", "30", "90", "--point", "0.3", "0.05"], "angles"),
    (["--angles", "30", "40", "--point", "0.3", "0.5"], "point"),
    (["--angles", "30", "40", "--point", "0.3", "0.05", "--k", "1"], "k = 1"),
    (["--angles", "30", "40", "--point", "0.3", "0.05", "--k", "0"], "k = 0"),
    (["--angles", "30", "40", "--point", "0.3", "0.05", "--elements", "0"], "elements"),
]


@pytest.mark.parametrize(("extra", "needle"), BAD)
def test_bad_input_exits_2_with_one_line(capsys, extra, needle):
    code, out, err = run(capsys, "conic", "--chord", "0.5", *extra)
    assert code == 2
    assert out == ""
    lines = err.strip().splitlines()
    assert len(lines) == 1 and needle in lines[0] and "not allowed" in lines[0]


def test_bad_chord_through_a_real_process():
    p = subprocess.run(
        [
            sys.executable,
            "-m",
            "rancf",
            "conic",
            "--chord",
            "-0.5",
            "--angles",
            "30",
            "40",
            "--point",
            "0.3",
            "0.05",
        ],
        capture_output=True,
        text=True,
        check=False,
    )
    assert p.returncode == 2
    assert p.stdout == ""
    assert p.stderr.strip().count("\n") == 0
    assert "chord = -0.5 is not allowed" in p.stderr and "Traceback" not in p.stderr


EX1 = ("conic", "--chord", "0.5", "--angles", "30", "40", "--point", "0.315", "0.077")


def test_json_takes_more_elements_than_the_table(capsys):
    # the table stops at 1000 rows; --json takes the scenario limit
    from rancf.elements.mapping import gradient_ratio
    from rancf.geometry.conic import conic_arc
    from rancf.mesh.factories import mesh_conic

    code, out, _ = run(capsys, *EX1, "--elements", "1500", "--json")
    assert code == 0
    d = json.loads(out)
    assert len(d["elements"]) == 1500 and d["type"] == "ellipse"
    e = np.array([x["nodal_coordinates"] for x in d["elements"]])
    assert np.array_equal(e[:-1, 4:], e[1:, :4])  # shared nodes
    assert e[-1, 4:6].tolist() == [0.5, 0.0]
    # beyond the table the ratios are sampled (33 points, parabolas): checked against the exact
    ratios = np.array([x["gradient_ratio"] for x in d["elements"]])
    mesh = mesh_conic(conic_arc(0.5, (30.0, 40.0), (0.315, 0.077)), 1500)
    some = np.linspace(0, 1499, 12).astype(int)
    curves = mesh.element_curves()
    exact = np.array([gradient_ratio(curves[j]) for j in some])
    assert np.abs(ratios[some] / exact - 1.0).max() < 1e-9


def test_table_stops_at_1000_elements_and_says_json_goes_further(capsys):
    code, out, err = run(capsys, *EX1, "--elements", "1001")
    assert code == 2 and out == ""
    assert err.count("\n") == 1 and "at most 1000 for the table" in err and "--json" in err
    code, out, err = run(capsys, *EX1, "--elements", "1000001", "--json")
    assert code == 2 and out == "" and "at most 1000000" in err


def test_json_text_is_the_json_of_the_whole_object():
    from rancf.cli.conic import json_text

    head = {"a": 1, "b": [1.5, 2.0], "c": {"d": "e"}}
    for items in ([], [{"x": 0.1, "y": [1, 2]}], [{"x": i / 7} for i in range(5)]):
        text = "".join(json_text(head, "items", iter(items)))
        assert json.loads(text) == {**head, "items": items} and text.endswith("}\n")
