"""A read-only install used without a home directory: nothing compiled, cached or written.

The installed package is copied read-only and run from the copy.  An editable install
(``pip install -e``, scikit-build-core's redirect mode) splits the package: the compiled core in
site-packages, the Python files and scenarios in ``src/rancf``, joined by an import hook that
takes ``rancf`` before ``PYTHONPATH`` is looked at.  There the copy joins both parts (what a
wheel installs) and runs without ``site`` (no hook; site-packages on ``PYTHONPATH`` instead).
"""

import json
import os
import shutil
import site
import stat
import subprocess
import sys
from importlib import metadata
from pathlib import Path

import rancf
from tests.scenario.test_scenario import BASE as SCENARIO  # a short planar pendulum


def _tree(root: Path) -> dict[str, float]:
    return {str(p.relative_to(root)): p.stat().st_mtime for p in root.rglob("*")}


def _editable() -> bool:
    """Whether rancf is an editable install (PEP 610: ``direct_url.json``, ``dir_info``)."""
    url = metadata.distribution("rancf").read_text("direct_url.json")
    return bool(url and json.loads(url).get("dir_info", {}).get("editable"))


def test_read_only_install_without_home(tmp_path):
    ro = tmp_path / "site"
    for part in rancf.__path__:  # one folder; an editable install's two, joined
        shutil.copytree(
            part, ro / "rancf", ignore=shutil.ignore_patterns("__pycache__"), dirs_exist_ok=True
        )
    assert list((ro / "rancf" / "kernels").glob("_core.*")) and (ro / "rancf" / "examples").is_dir()
    for p in [ro, *ro.rglob("*")]:  # read-only for everyone (root ignores it: see the tree check)
        mode = p.stat().st_mode & ~(stat.S_IWUSR | stat.S_IWGRP | stat.S_IWOTH)
        p.chmod(mode)
    before = _tree(ro)
    home = tmp_path / "no-such-home"
    env = {k: v for k, v in os.environ.items() if not k.startswith(("MPL", "NUMBA", "XDG"))}
    path, flags = [str(ro)], []
    if _editable():
        path, flags = [*path, *site.getsitepackages()], ["-S"]
    env.update(HOME=str(home), PYTHONPATH=os.pathsep.join(path), PYTHONDONTWRITEBYTECODE="1")
    scenario = tmp_path / "p.toml"
    scenario.write_text(SCENARIO)

    def run(*args: str) -> subprocess.CompletedProcess:
        return subprocess.run(
            [sys.executable, *flags, *args], env=env, cwd=tmp_path, capture_output=True, text=True
        )

    where = run("-c", "import rancf.kernels._core as c, rancf; print(rancf.__file__)")
    assert where.returncode == 0, where.stderr
    assert where.stdout.strip().startswith(str(ro))
    sim = run("-m", "rancf", "simulate", str(scenario), "--out", "out", "--quiet")
    assert sim.returncode == 0, sim.stderr
    assert (tmp_path / "out" / "summary.json").is_file()
    rep = run("-m", "rancf", "report", "--quick", "--out", "rep")
    assert rep.returncode == 0, rep.stderr
    assert (tmp_path / "rep" / "report.html").is_file()
    assert "Traceback" not in sim.stderr + rep.stderr
    assert _tree(ro) == before  # nothing written into the install
    # nor anything of ours in a home directory (running as root, Matplotlib may create its own
    # font cache there; an ordinary user without a home gets its temporary-directory fallback)
    made = {p.relative_to(home).parts for p in home.rglob("*")} if home.exists() else set()
    assert all(len(p) < 2 or p[1] == "matplotlib" for p in made), made
    for p in [ro, *ro.rglob("*")]:
        p.chmod(p.stat().st_mode | stat.S_IWUSR)  # let pytest clean up
