"""The scenario format as a JSON Schema (draft 2020-12), generated from the models.

``rancf schema`` prints :func:`scenario_schema`: every key with its type, default, allowed
values and description (units in brackets), from the fields of :mod:`rancf.scenario`.  The
models stay the authority for the checks a schema cannot express (``step <= t_end``, places
against the bodies, node indices against the mesh).
"""

from __future__ import annotations

from typing import Any

from rancf.scenario.scenario import Scenario

__all__ = ["scenario_schema"]

_ONE_BODY = ["geometry", "mesh", "section", "material"]


def _tidy(node: Any) -> Any:
    """The generated schema without what a TOML file cannot hold or need: ``null`` (an absent
    key is the default ``None``), tables' defaults (those of their keys) and pydantic's property
    titles (``"T End"``); a lone ``allOf`` reference as the reference itself."""
    if isinstance(node, list):
        return [_tidy(x) for x in node]
    if not isinstance(node, dict):
        return node
    out = {k: _tidy(v) for k, v in node.items()}
    if len(out.get("allOf", ())) == 1:  # pydantic < 2.9 wraps a $ref with siblings in allOf
        out = {**out.pop("allOf")[0], **out}
    if out.get("default", 0) is None or isinstance(out.get("default"), dict):
        del out["default"]  # absent; a table's defaults are those of its keys
    alts = out.get("anyOf")
    if isinstance(alts, list) and {"type": "null"} in alts:
        rest = [a for a in alts if a != {"type": "null"}]
        del out["anyOf"]
        out = {**rest[0], **out} if len(rest) == 1 else {**out, "anyOf": rest}
    if isinstance(out.get("properties"), dict):
        out["properties"] = {
            name: {k: v for k, v in p.items() if k != "title"}
            for name, p in out["properties"].items()
        }
    return out


def scenario_schema() -> dict[str, Any]:
    """JSON Schema of a scenario file (the TOML document as JSON)."""
    schema = _tidy(Scenario.model_json_schema(by_alias=True, mode="validation"))
    schema.pop("title", None)
    return {
        "$schema": "https://json-schema.org/draft/2020-12/schema",
        "title": "rancf scenario",
        **schema,
        "description": "A model and its analysis (TOML): one flexible body (geometry, mesh, "
        "section, material) or a system ([[bodies]], [[joints]], [[springs]]). See the rancf "
        "documentation (docs/reference/scenario.md).",
        "anyOf": [
            {"required": _ONE_BODY, "not": {"required": ["bodies"]}},
            {"required": ["bodies"], "not": {"anyOf": [{"required": [k]} for k in _ONE_BODY]}},
        ],
    }
