"""The JSON Schema of ``rancf schema`` is generated from the models: every key the models know is
in it with a description (and its default and allowed values), and every shipped scenario is
valid against it (a small structural validator: jsonschema is not a dependency)."""

from __future__ import annotations

import re
import tomllib
import typing
from importlib.resources import files

import pytest

from rancf.scenario import Scenario, scenario_schema
from rancf.scenario.base import Table
from tests import pages
from tests.scenario.systems import SLIDER_CRANK, TETHER_3D
from tests.scenario.test_scenario import BASE

SCHEMA = scenario_schema()


def _tables() -> list[type[Table]]:
    out, todo = [], list(Table.__subclasses__())
    while todo:
        cls = todo.pop()
        todo += cls.__subclasses__()
        if cls.model_fields and not cls.__name__.startswith("_"):  # not a shared base
            out.append(cls)
    return out


def _resolve(node: dict) -> dict:
    while "$ref" in node:
        node = SCHEMA["$defs"][node["$ref"].rsplit("/", 1)[1]]
    return node


def _properties(cls: type[Table]) -> dict:
    return SCHEMA["properties"] if cls is Scenario else SCHEMA["$defs"][cls.__name__]["properties"]


@pytest.mark.parametrize("cls", _tables(), ids=lambda c: c.__name__)
def test_every_key_is_in_the_schema_with_a_description(cls):
    props = _properties(cls)
    assert set(props) == set(cls.file_keys())
    for name, field in cls.model_fields.items():
        key = field.alias or name
        p = props[key]
        assert p.get("description") or _resolve(p).get("description"), f"{cls.__name__}.{key}"
        default = field.default
        if isinstance(default, bool | int | float | str):
            assert p["default"] == default, f"{cls.__name__}.{key}"
        if typing.get_origin(field.annotation) is typing.Literal:
            allowed = list(typing.get_args(field.annotation))
            assert p.get("enum", [p.get("const")]) == allowed, f"{cls.__name__}.{key}"


def test_every_table_is_reachable_from_the_root():
    """Each model's schema is referenced (no table the file format cannot reach)."""
    text = repr(SCHEMA)
    for cls in _tables():
        if cls is not Scenario:
            assert f"#/$defs/{cls.__name__}'" in text, cls.__name__


# ---------------------------------------------------------------- a structural validator
def _problems(value, node: dict, where: str = "$") -> list[str]:
    """What makes ``value`` invalid against the schema ``node`` (the keywords the generated
    schema uses: $ref, type, properties, additionalProperties, required, items, min/maxItems,
    enum, const, minimum/maximum (exclusive), minLength, pattern, oneOf, anyOf, not)."""
    node = _resolve(node)
    out: list[str] = []
    types = {"object": dict, "array": list, "string": str, "boolean": bool}
    t = node.get("type")
    if t == "number" and (isinstance(value, bool) or not isinstance(value, int | float)):
        return [f"{where}: not a number"]
    if t == "integer" and (isinstance(value, bool) or not isinstance(value, int)):
        return [f"{where}: not an integer"]
    if t in types and not isinstance(value, types[t]):
        return [f"{where}: not {t}"]
    if "const" in node and value != node["const"]:
        out.append(f"{where}: not {node['const']!r}")
    if "enum" in node and value not in node["enum"]:
        out.append(f"{where}: not one of {node['enum']}")
    bounds = (
        ("minimum", float.__ge__),
        ("maximum", float.__le__),
        ("exclusiveMinimum", float.__gt__),
        ("exclusiveMaximum", float.__lt__),
    )
    for k, op in bounds:
        if k in node and not op(float(value), float(node[k])):
            out.append(f"{where}: {k} {node[k]}")
    if "minLength" in node and len(value) < node["minLength"]:
        out.append(f"{where}: too short")
    if "pattern" in node and not re.search(node["pattern"], value):
        out.append(f"{where}: does not match {node['pattern']}")
    if isinstance(value, list):
        if len(value) < node.get("minItems", 0) or len(value) > node.get("maxItems", 1 << 30):
            out.append(f"{where}: {len(value)} items")
        if "items" in node:
            for i, x in enumerate(value):
                out += _problems(x, node["items"], f"{where}[{i}]")
    if isinstance(value, dict):
        props = node.get("properties", {})
        for k in node.get("required", []):
            if k not in value:
                out.append(f"{where}.{k}: missing")
        for k, v in value.items():
            if k in props:
                out += _problems(v, props[k], f"{where}.{k}")
            elif node.get("additionalProperties") is False:
                out.append(f"{where}.{k}: unknown")
            elif isinstance(node.get("additionalProperties"), dict):
                out += _problems(v, node["additionalProperties"], f"{where}.{k}")
    if "oneOf" in node and sum(not _problems(value, n) for n in node["oneOf"]) != 1:
        out.append(f"{where}: matches not exactly one of oneOf")
    if "anyOf" in node and all(_problems(value, n) for n in node["anyOf"]):
        out.append(f"{where}: matches none of anyOf")
    if "not" in node and not _problems(value, node["not"]):
        out.append(f"{where}: matches 'not'")
    return out


def _shipped() -> dict[str, dict]:
    docs = {
        p.name: tomllib.loads(p.read_text())
        for p in files("rancf.examples").iterdir()
        if p.name.endswith(".toml")
    }
    for page in pages.PAGES:  # the README and the documentation pages
        for i, block in enumerate(pages.blocks(pages.text(page), "toml")):
            d = tomllib.loads(block)
            if {"geometry", "mesh"} <= set(d) or "bodies" in d:  # complete scenarios, not snippets
                docs[f"{pages.name(page)}[{i}]"] = d
    docs["slider-crank"] = tomllib.loads(SLIDER_CRANK)
    docs["tether"] = tomllib.loads(TETHER_3D)
    return docs


SHIPPED = _shipped()


@pytest.mark.parametrize("name", list(SHIPPED))
def test_shipped_scenarios_are_valid_against_the_schema(name):
    assert len(SHIPPED) >= 9
    assert _problems(SHIPPED[name], SCHEMA) == []


@pytest.mark.parametrize(
    ("change", "problem"),
    [
        (lambda d: d["mesh"].update(elements=0), "$.mesh.elements: matches not exactly one"),
        (lambda d: d["mesh"].update(elemnts=3), "$.mesh.elemnts: unknown"),
        (lambda d: d["geometry"].update(kind="spline"), "$.geometry: matches not exactly one"),
        (lambda d: d["supports"][0].update(kind="weld"), "$.supports[0].kind: not one of"),
        (lambda d: d["material"].pop("density"), "$.material.density: missing"),
        (lambda d: d.pop("geometry"), "$: matches none of anyOf"),
        (
            lambda d: d.update(
                bodies=[{"name": "m", "kind": "mass", "mass": 1.0, "position": [0.0, 0.0]}]
            ),
            "$: matches none of anyOf",
        ),
        (lambda d: d["sensors"][0].update(name="1x"), "$.sensors[0].name: does not match"),
    ],
)
def test_the_validator_finds_problems(change, problem):
    """The structural validator can fail: the schema refuses what the models refuse."""
    d = tomllib.loads(BASE)
    change(d)
    assert any(p.startswith(problem) for p in _problems(d, SCHEMA)), _problems(d, SCHEMA)


def test_the_schema_users_see_is_the_stored_one():
    """``rancf schema`` prints the schema editors use: a one-body file and a file with
    ``[[bodies]]`` are its two forms, whatever the code does with them after parsing.  A change
    of the models that changes the schema shows here; regenerate the stored copy with
    ``rancf schema > tests/scenario/data/schema.json`` when the change is meant."""
    import json
    import subprocess
    import sys
    from pathlib import Path

    stored = Path(__file__).parent / "data" / "schema.json"
    out = subprocess.run(
        [sys.executable, "-m", "rancf", "schema"], capture_output=True, text=True, check=True
    ).stdout
    assert json.loads(out) == json.loads(stored.read_text(encoding="utf-8"))
    assert out == stored.read_text(encoding="utf-8")
