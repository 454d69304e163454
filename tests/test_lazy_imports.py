"""``rancf simulate`` loads only what the command uses: a plain run of a shipped example imports
neither SciPy (sparse solvers of the static and modal analyses) nor the plotting, viewer or
cluster libraries, whose imports would be most of its start-up, nor rancf's static solvers (a
run from the reference needs no equilibrium), nor the contact, fluid and winch modules of a
system that has none of them."""

from __future__ import annotations

import json
import subprocess
import sys

import pytest

from rancf.studies.common import example_path

HEAVY = ("scipy", "matplotlib", "plotly", "dask", "distributed")
#: rancf's static solvers: a dynamic run loads them only to start from the static equilibrium.
STATIC = (
    "rancf.solvers.static",
    "rancf.solvers.system_equilibrium",
    "rancf.solvers.arc_length",
    "rancf.solvers.relaxation",
    "rancf.solvers.newton",
)
#: rancf's contact, fluid and winch modules: loaded by a system that has obstacles, a fluid or
#: distributed loads, winches.
PARTS = (
    "rancf.system.contact",
    "rancf.system.contact_states",
    "rancf.system.contact_view",
    "rancf.system.fluid",
    "rancf.system.winches",
    "rancf.system.drums",
    "rancf.system.touchdown",
    "rancf.system.parts.winch",
    "rancf.system.parts.obstacle",
    "rancf.system.parts.contact_pair",
    "rancf.system.parts.distributed",
    "rancf.system.parts.fluid",
)
SCRIPT = """
import json, sys
from rancf.cli import main
code = main(["simulate", sys.argv[1], "--out", sys.argv[2], "--quiet"])
print(json.dumps([code, sorted(m for m in sys.modules if m.split(".")[0] in {heavy}
                               or m in {static})]))
"""


@pytest.mark.parametrize("name", ["planar-pendulum", "slider-crank"])
def test_simulate_loads_no_heavy_library(tmp_path, name):
    p = subprocess.run(
        [
            sys.executable,
            "-c",
            SCRIPT.format(heavy=set(HEAVY), static=set(STATIC + PARTS)),
            str(example_path(name)),
            str(tmp_path / "run"),
        ],
        capture_output=True,
        text=True,
        check=True,
    )
    code, loaded = json.loads(p.stdout.strip().splitlines()[-1])
    assert code == 0 and loaded == [], loaded


#: Prints, after ``rancf ARGS`` in this process, which of NumPy and pydantic were imported.
LIGHT = """
import json, sys
from rancf.cli import main
main(sys.argv[1:])
print(json.dumps(sorted({m.split(".")[0] for m in sys.modules} & {"numpy", "pydantic"})))
"""


@pytest.mark.parametrize(
    "args",
    [["--version"], ["--help"], ["simulate", "--help"], ["example", "list"], ["example", "copy"]],
)
def test_the_command_line_itself_loads_neither_numpy_nor_pydantic(args, tmp_path):
    if args == ["example", "copy"]:  # a user's first file
        args = [*args, "planar-pendulum", str(tmp_path)]
    p = subprocess.run([sys.executable, "-c", LIGHT, *args], capture_output=True, text=True)
    assert json.loads(p.stdout.strip().splitlines()[-1]) == []
    if "copy" in args:
        assert (tmp_path / "planar-pendulum.toml").read_bytes() == example_path(
            "planar-pendulum"
        ).read_bytes()


def test_lazily_exported_names_stay_functions_after_their_modules_load():
    """A name the package exports lazily is not shadowed by a submodule of the same name once
    that submodule has been imported (``from rancf.system import contact_outputs`` stays the
    function)."""
    code = (
        "import importlib, rancf.system as s\n"
        "for name, mod in s._LAZY.items():\n"
        "    importlib.import_module(mod)\n"
        "    assert callable(getattr(s, name)), name\n"
        "    assert getattr(s, name) is getattr(importlib.import_module(mod), name), name\n"
    )
    subprocess.run([sys.executable, "-c", code], check=True)
