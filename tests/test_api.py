"""The public API: names exported from ``rancf``, equal defaults, the scenario JSON Schema."""

import inspect
import json
import tomllib

import pytest

import rancf
from rancf.cli import main
from rancf.errors import ScenarioError
from rancf.scenario import parse_scenario
from rancf.scenario.geometry import GEOMETRY_KEYS
from rancf.scenario.schema import scenario_schema
from rancf.solvers.dynamic import DynamicOptions
from tests.scenario.test_scenario import BASE


@pytest.mark.parametrize("name", [n for n in rancf.__all__ if n != "__version__"])
def test_every_exported_name_resolves(name):
    assert getattr(rancf, name) is not None


def test_version(capsys):
    assert main(["--version"]) == 0
    assert capsys.readouterr().out.strip() == f"rancf {rancf.__version__}"


def test_scenario_defaults_are_the_python_defaults():
    sc = parse_scenario(tomllib.loads(BASE), "base.toml")
    opts = DynamicOptions(t_end=1.0, step=1e-3)
    for key in ("rho_inf", "adaptive", "rtol", "min_step", "output_step", "newton_tol"):
        assert sc.solver[key] == getattr(opts, key), key
    assert sc.solver["max_newton"] == opts.max_newton and sc.solver["newton"] == opts.newton
    static = inspect.signature(rancf.solve_static).parameters
    assert sc.solver["load_steps"] == static["load_steps"].default
    # the quadrature default is the Model's own (6 for ANCF elements, 10 for rational ones)
    assert sc.data["mesh"]["quadrature_points"] is None
    model = sc.build_model()
    direct = rancf.Model(
        rancf.mesh_conic(rancf.conic_arc(0.5, [30, 40], [0.315, 0.077]), 3),
        "rancf",
        rancf.Section.circular(0.02),
        rancf.Material(6000.0, 2.0e6),
    )
    assert model.kernel.xi.size == direct.kernel.xi.size == 10


def _allowed(raw_changes) -> set[str]:
    """Keys the parser accepts in one table, read from its unknown-key message."""
    d = tomllib.loads(BASE)
    raw_changes(d)
    with pytest.raises(ScenarioError, match="unknown key") as info:
        parse_scenario(d, "x.toml")
    return set(str(info.value).split("allowed: ")[1].rstrip(")").split(", "))


TABLES = {
    "mesh": lambda d: d["mesh"].update(zz=1),
    "section": lambda d: d["section"].update(zz=1),
    "material": lambda d: d["material"].update(zz=1),
    "solver": lambda d: d["solver"].update(zz=1),
    "loads": lambda d: d.update(loads={"zz": 1}),
    "damping": lambda d: d.update(damping={"zz": 1}),
    "modes": lambda d: d.update(modes={"zz": 1}),
}


def _resolved(schema: dict, node: dict) -> dict:
    """A schema node with its ``$ref`` followed."""
    while "$ref" in node:
        node = schema["$defs"][node["$ref"].rsplit("/", 1)[1]]
    return node


@pytest.mark.parametrize("table", list(TABLES))
def test_schema_has_the_parsers_keys(table):
    schema = scenario_schema()
    props = _resolved(schema, schema["properties"][table])["properties"]
    assert set(props) == _allowed(TABLES[table])


def test_schema_geometry_and_arrays():
    schema = scenario_schema()
    kinds = [_resolved(schema, k) for k in schema["properties"]["geometry"]["oneOf"]]
    keys = set().union(*(k["properties"] for k in kinds))
    assert keys == {"kind", *(k for ks in GEOMETRY_KEYS.values() for k in ks)}
    conic = next(k for k in kinds if k["properties"]["kind"]["const"] == "conic")
    assert set(conic["properties"]) == _allowed(lambda d: d["geometry"].update(zz=1))
    for array in ("sensors", "supports"):
        items = _resolved(schema, schema["properties"][array]["items"])["properties"]
        assert set(items) == _allowed(lambda d, a=array: d[a][0].update(zz=1))


def test_schema_command_prints_json(capsys):
    assert main(["schema"]) == 0
    doc = json.loads(capsys.readouterr().out)
    assert doc["$schema"].startswith("https://json-schema.org/")
    # one flexible body (the four tables) or a system of bodies
    assert doc["anyOf"][0]["required"] == ["geometry", "mesh", "section", "material"]
    assert doc["anyOf"][1]["required"] == ["bodies"]
    assert doc == scenario_schema()


def test_command_table_names_every_command_of_its_module():
    """`rancf CMD` imports only CMD's module: the table must list exactly what each registers."""
    import argparse
    import importlib

    from rancf.cli import COMMAND_MODULES

    for module, commands in COMMAND_MODULES.items():
        sub = argparse.ArgumentParser().add_subparsers()
        importlib.import_module(module).add_parsers(sub)
        assert tuple(sub.choices) == commands, module
