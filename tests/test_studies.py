"""Every shipped example in reduced form: physical sanity, not numbers copied from the paper."""

import os
import re

import numpy as np
import pytest

from rancf.cli import main
from rancf.scenario import load_scenario
from rancf.studies import EXAMPLES, study_runner
from rancf.studies.common import example_path


@pytest.mark.parametrize("name", list(EXAMPLES))
def test_example_scenarios_are_valid(name):
    sc = load_scenario(example_path(name))
    model = sc.build_model()
    assert model.n_el >= 1 and sc.sensors


#: The umask the studies run under (files 0640, folders 0750: not the 0600 of a temporary file).
STUDY_UMASK = 0o027


@pytest.fixture(scope="module")
def studies(tmp_path_factory):
    out = tmp_path_factory.mktemp("studies")
    old = os.umask(STUDY_UMASK)
    try:
        return {name: (study_runner(name)(out / name, True), out / name) for name in EXAMPLES}
    finally:
        os.umask(old)


def test_study_files_honour_the_umask(studies, tmp_path):
    """What `rancf example run` and `rancf report` write (figures, tables, run folders,
    animations, the report itself) gets the umask's permissions."""
    from rancf.studies.report import write_report

    old = os.umask(STUDY_UMASK)
    try:
        write_report(tmp_path, [(res, folder) for res, folder in studies.values()], quick=True)
    finally:
        os.umask(old)
    paths = [p for _, folder in studies.values() for p in folder.rglob("*")]
    paths += list(tmp_path.iterdir())
    want = {p: (0o777 if p.is_dir() else 0o666) & ~STUDY_UMASK for p in paths}
    assert {p: p.stat().st_mode & 0o777 for p in paths} == want
    assert {p.suffix for p in paths} >= {".png", ".gif", ".csv", ".npz", ".json", ".html"}


def test_planar_pendulum(studies):
    res, folder = studies["planar-pendulum"]
    assert all((folder / f).stat().st_size > 5000 for _, f in res.figures)
    assert (folder / "element_efficiency.csv").exists()
    # the Kopt element is the most uniform parameterization
    ratios = res.data["ratios"]
    assert ratios[1] < ratios[2] < ratios[0]
    # energy of the reference run: generalized-alpha with rho_inf = 0.9 keeps it within 0.1 %
    assert res.data["energy_drift"] < 1e-3
    # the pendulum swings down: the tip ends well below the hinge
    assert res.data["ref_tip"][-1, 1] < -0.2


def test_spatial_pendulum_moves_out_of_plane_and_converges(studies):
    res, _ = studies["spatial-pendulum"]
    assert res.data["out_of_plane"] > 0.01
    assert res.data["energy_drift"] < 1e-2
    errs = {
        row[0]: float(row[2])
        for row in [r for t in res.tables if t[3] == "error_vs_elements.csv" for r in t[2]]
        if row[1] == 4
    }
    first = {
        row[0]: float(row[2])
        for row in [r for t in res.tables if t[3] == "error_vs_elements.csv" for r in t[2]]
        if row[1] == 1
    }
    for kind in ("Kopt", "K = 0.1"):
        assert errs[kind] < first[kind]
    # the rod reruns the study: converging, energy kept, out of plane too
    rod = res.data["rod_errors"]
    assert rod[4] < rod[2]
    assert res.data["rod_energy_drift"] < 1e-2
    assert res.data["rod_out_of_plane"] > 0.01


def test_arc_vibration(studies):
    res, folder = studies["arc-vibration"]
    d = res.data
    # FFT peak of the free in-plane vibration agrees with the eigenvalue analysis
    assert abs(d["f_fft"] - d["f_modal"]) < 0.05 * d["f_modal"]
    # other element types give the same frequency
    assert d["f_ancf"] == pytest.approx(d["f_modal"], rel=1e-4)
    assert d["f_beam"] == pytest.approx(d["f_modal"], rel=5e-3)
    # undamped, rho_inf = 1: energy conserved
    assert d["drift_in"] < 1e-3
    # curved spatial cable: zero-frequency out-of-plane modes are reported, not hidden
    assert d["n_zero_out"] >= 1
    # the forced response oscillates at the excitation frequency, near the linear amplitude
    assert d["f_forced"] == pytest.approx(d["f_fft"], rel=0.05)
    assert 0.5 * d["lin"] < d["amp"] < 1.2 * d["lin"]
    assert (folder / "modes.csv").exists()
    # the rod: no zero modes, in-plane modes of the planar cable, out-of-plane ones converging
    # from above, and the free out-of-plane vibration at the first out-of-plane frequency
    assert d["rod_n_zero"] == 0 and d["rod_in_diff"] < 1e-8
    assert np.all(np.diff(d["rod_out_modes"], axis=0) < 0)
    assert d["rod_fft_out"] == pytest.approx(d["rod_f1_out"], rel=0.05)
    assert (folder / "rod_out_of_plane_modes.csv").exists()


def test_exact_geometry_pays_when_stiff(studies):
    res, folder = studies["exact-geometry"]
    errs = res.data["errors"]
    soft, stiff = 2e6, 2e9
    ancf = "ANCF (Hermite reference)"
    for e in (soft, stiff):
        kopt = errs[e]["Kopt"]
        assert kopt[3] < kopt[2] < kopt[1]  # converges under refinement
        assert res.data["ref_check"][e] < kopt[3]  # the reference resolves the errors compared
    # stiff: the exact reference geometry beats the Hermite one; soft: the two are alike
    assert errs[stiff][ancf][3] > 1.5 * errs[stiff]["Kopt"][3]
    assert errs[soft][ancf][3] < 1.5 * errs[soft]["Kopt"][3]
    # the beam's chord-polygon reference is worse still when stiff
    assert errs[stiff]["Euler–Bernoulli beam"][3] > errs[stiff][ancf][3]
    # every run is a row of the study's sweep
    rows = (folder / "sweep" / "results.csv").read_text().splitlines()[1:]
    assert len(rows) == 2 * 2 + 2 * 5 * 3 and all(",completed," in r for r in rows)
    assert (folder / "elements_needed.csv").exists() and (folder / "animation.gif").exists()


def test_grid_on_dask_gives_the_sequential_numbers(studies, tmp_path, capsys):
    # a driver process with its grid on a local cluster: the tables of the sequential run
    seq, folder = studies["planar-pendulum"]
    argv = ["example", "run", "planar-pendulum", "--quick", "--out", str(tmp_path)]
    assert main([*argv, "--workers", "2"]) == 0
    assert "on a local Dask cluster of 2 worker(s)" in capsys.readouterr().err
    par = tmp_path  # `example run` writes its files directly into --out
    for name in ("error_vs_elements.csv", "element_efficiency.csv", "mesh_refinement.csv"):
        a = (folder / name).read_text().splitlines()
        b = (par / name).read_text().splitlines()
        if name == "element_efficiency.csv":  # the last column is a wall time
            a, b = ([r.rsplit(",", 1)[0] for r in x] for x in (a, b))
        assert a == b, name
    # every run of the sequential loop ran (a size beyond its stop may have run before it was
    # cancelled; the tables leave it out)
    runs = {p.name for p in (par / "sweep" / "runs").iterdir()}
    assert runs >= {p.name for p in (folder / "sweep" / "runs").iterdir()}
    assert (tmp_path / "report.html").is_file()


def test_example_cli(tmp_path, capsys):
    assert main(["example", "list"]) == 0
    out = capsys.readouterr().out
    assert all(name in out for name in EXAMPLES)
    assert main(["example", "run", "no-such-example", "--out", str(tmp_path)]) == 2
    assert "no-such-example" in capsys.readouterr().err


def test_report_html(studies, tmp_path):
    from rancf.studies.report import write_report

    items = [(res, folder) for res, folder in studies.values()]
    for res, folder in items:
        res.write_comparison_csv(folder)
    path = write_report(tmp_path, items, quick=True)
    text = path.read_text()
    assert text.count("data:image/png;base64,") == sum(len(r.figures) for r, _ in items)
    # one animation per study, embedded as GIF
    assert all(len(r.animations) == 1 for r, _ in items)
    assert text.count("data:image/gif;base64,R0lGOD") == len(items)
    assert "Paper says / we get" in text
    assert np.all([(f / "comparison.csv").exists() for _, f in items])


def test_report_cites_the_papers_and_explains_missing_values(studies, tmp_path):
    from rancf.studies.report import write_report

    items = [(res, folder) for res, folder in studies.values()]
    text = write_report(tmp_path, items, quick=True).read_text()
    refs = text[text.index("<h2 id='references'>") :]
    assert "10.1007/s11044-009-9157-3" in refs and "Sanborn" in refs and "Shabana" in refs
    assert "conic-section" in refs and "P. L., Y. L., M. S., M. L." in refs
    # no bare non-finite numbers in any table cell
    cells = re.findall(r"<td>([^<]*)</td>", re.sub(r"base64,[A-Za-z0-9+/=]+", "", text))
    assert not [c for c in cells if c.strip().lower() in {"inf", "-inf", "nan"}]


def test_reference_1_describes_the_paper_without_placeholders(tmp_path):
    # the conic-section paper is described as the copy rancf was written from gives it (its
    # abstract, keywords, authors' initials, funding), with no "unknown"/"not given" metadata
    from rancf.studies.report import write_report

    text = write_report(tmp_path, [], quick=True).read_text()
    first = text[text.index("[1] ") : text.index("[2] ")]
    assert "direct definition method for RANCF elements" in first
    assert "P. L., Y. L., M. S., M. L." in first and "Keywords: rational absolute nodal" in first
    low = first.lower()
    for placeholder in ("neither", "not known", "unknown", "left out", "guess", "n/a", "doi"):
        assert placeholder not in low


def test_missing_values_in_tables_are_explained():
    from rancf.studies.common import NOT_REACHED, NOT_RUN, format_error
    from rancf.studies.report import _table

    assert format_error(float("inf")) == NOT_REACHED
    assert format_error(float("nan")) == NOT_RUN
    assert format_error(1.5e-3) == "1.5000e-03"
    html = _table(["n", "error"], [[1, format_error(float("inf"))], [2, "inf"], [3, "2e-3"]])
    assert "<td>inf</td>" not in html and "—*" in html
    assert f"“{NOT_REACHED}”:" in html and "no value" in html
    assert "footnote" not in _table(["n", "error"], [[1, "2e-3"]])


def test_legends_count_one_element_in_the_singular():
    from rancf.post.plots import pyplot
    from rancf.studies.common import n_elements
    from rancf.studies.figures import plot_ab

    assert (n_elements(1), n_elements(2)) == ("1 element", "2 elements")
    plt = pyplot()
    t = np.linspace(0.0, 1.0, 5)
    runs = {n: {"t": t, "ab": t * n} for n in (1, 2)}
    fig = plot_ab(plt, runs, {"t": t, "ab": t, "n_el": 8}, [1, 2], "AB")
    labels = [x.get_text() for x in fig.axes[0].get_legend().get_texts()]
    plt.close(fig)
    assert labels == ["1 element", "2 elements", "reference (8 elements)"]
