"""Sphinx directive ``scenario-reference``: every scenario key from the typed models.

The source is :func:`rancf.scenario_schema`, the JSON Schema that ``rancf schema`` prints and that
pydantic generates from the models of :mod:`rancf.scenario`; nothing here is written by hand.
One section per table model (``[solver]``, ``[[bodies]]`` of each kind, each geometry kind, each
time-function form), one row per key: type, default, allowed values, units (the bracketed unit
of the key's description) and description. Every row has the id ``key-<model>-<key>`` (lower
case), every section ``scenario-<model>``; ``tests/test_docs_build.py`` checks that every key the
schema knows has its row in the built page.
"""

from __future__ import annotations

import re
from typing import Any

from docutils import nodes
from docutils.statemachine import StringList
from sphinx.util.docutils import SphinxDirective

_UNIT = {"m", "s", "Hz", "N", "Pa", "deg", "rad", "kg", "J", "1/s"}


def section_id(model: str) -> str:
    return f"scenario-{model.lower()}"


def key_id(model: str, key: str) -> str:
    return f"key-{model.lower()}-{key.lower()}"


def units(description: str) -> str:
    """The unit in brackets in a key's description (``"end time [s]"`` -> ``s``), else ''."""
    for found in re.findall(r"\[([^\]]+)\]", description):
        tokens = re.split(r"[ /]", found.replace("^", " ^").replace(" ^", "^"))
        if tokens and all(re.sub(r"\^\d$", "", t) in _UNIT or t == "1" for t in tokens if t):
            return found
    return ""


#: A cross-reference role of a docstring (``:mod:`rancf.x```, ``:func:`~rancf.x.f```).
_ROLE = r":(?:py:)?(?:mod|func|class|meth|attr|data|obj):`(~?)([^`]+)`"


def plain(text: str) -> str:
    """A model's or key's description as the reference shows it: the docstrings' cross-reference
    roles (pointers into the code, in parentheses of their own) and equation labels of the design
    notes (``(T.2)``, ``(T.5; Kane ...)``) dropped, any other role as plain code."""
    text = re.sub(rf"\s*\(\s*{_ROLE}\s*\)", "", text)
    text = re.sub(_ROLE, lambda m: f"``{m[2].rsplit('.', 1)[-1] if m[1] else m[2]}``", text)
    text = re.sub(r"\s*\(T\.\d+\)", "", text)
    return re.sub(r"\(T\.\d+; ", "(", text)


def _number(x: Any) -> str:
    return f"{x:g}" if isinstance(x, float) else str(x)


def type_text(p: dict[str, Any]) -> list[tuple[str, str | None]]:
    """The type of a schema node as ``(text, model it refers to or None)`` pieces."""
    if "$ref" in p:
        name = p["$ref"].rsplit("/", 1)[-1]
        return [(name, name)]
    if "const" in p:
        return [(f'"{p["const"]}"' if isinstance(p["const"], str) else str(p["const"]), None)]
    for alt in ("oneOf", "anyOf"):
        if alt in p and "type" not in p:
            out: list[tuple[str, str | None]] = []
            for i, a in enumerate(p[alt]):
                out += ([(" or ", None)] if i else []) + type_text(a)
            return out
    t = p.get("type", "any")
    if t == "array":
        n = (p.get("minItems"), p.get("maxItems"))
        size = (
            f"{n[0]}"
            if n[0] is not None and n[0] == n[1]
            else f"{n[0]}–{n[1]}"
            if None not in n
            else f"≥ {n[0]}"
            if n[0] is not None
            else ""
        )
        head = f"array ({size}) of " if size else "array of "
        return [(head, None), *type_text(p.get("items", {}))]
    if t == "object" and "patternProperties" in p:
        (value,) = p["patternProperties"].values()
        return [("table of NAME = ", None), *type_text(value)]
    return [(t, None)]


def allowed_text(p: dict[str, Any]) -> str:
    """Allowed values of a schema node: choices, bounds, sizes, name patterns."""
    out = []
    if "enum" in p:
        out.append(" | ".join(f'"{v}"' for v in p["enum"]))
    if "const" in p:
        out.append(f'"{p["const"]}"' if isinstance(p["const"], str) else str(p["const"]))
    lo = [
        (f"≥ {_number(p['minimum'])}") if "minimum" in p else None,
        (f"> {_number(p['exclusiveMinimum'])}") if "exclusiveMinimum" in p else None,
    ]
    hi = [
        (f"≤ {_number(p['maximum'])}") if "maximum" in p else None,
        (f"< {_number(p['exclusiveMaximum'])}") if "exclusiveMaximum" in p else None,
    ]
    bounds = [b for b in lo + hi if b]
    if bounds:
        out.append(", ".join(bounds))
    if "minLength" in p:
        out.append("not empty")
    if "pattern" in p:
        out.append("a name: letters, digits, _ (not starting with a digit)")
    items = p.get("items")
    if isinstance(items, dict) and "type" in items and items.get("type") != "array":
        inner = allowed_text(items)
        if inner:
            out.append(f"each {inner}")
    elif isinstance(items, dict) and items.get("type") == "array":
        inner = allowed_text(items.get("items", {}))
        if inner:
            out.append(f"each coordinate {inner}")
    for alt in ("oneOf", "anyOf"):
        for a in p.get(alt, []):
            inner = allowed_text(a)
            if inner and "$ref" not in a:
                out.append(inner)
    return "; ".join(dict.fromkeys(out))


def default_text(p: dict[str, Any]) -> str:
    if "default" not in p:
        return ""
    d = p["default"]
    if isinstance(d, bool):
        return "true" if d else "false"
    if isinstance(d, str):
        return f'"{d}"'
    if d == []:
        return "[] (none)"
    return _number(d)


def _para(*children: nodes.Node) -> nodes.paragraph:
    para = nodes.paragraph()
    para.extend(children)
    return para


def _type_para(p: dict[str, Any]) -> nodes.paragraph:
    para = nodes.paragraph()
    for text, ref in type_text(p):
        if ref is None:
            para += nodes.Text(text)
        else:
            link = nodes.reference("", "", internal=True, refid=section_id(ref))
            link += nodes.literal(text=ref)
            para += link
    return para


def _table(headers: list[str], rows: list[list[nodes.Node]], widths: list[int]) -> nodes.table:
    table = nodes.table(classes=["scenario-keys"])
    group = nodes.tgroup(cols=len(headers))
    table += group
    for w in widths:
        group += nodes.colspec(colwidth=w)
    head = nodes.thead()
    group += head
    row = nodes.row()
    for h in headers:
        row += nodes.entry("", nodes.paragraph(text=h))
    head += row
    body = nodes.tbody()
    group += body
    for cells in rows:
        row = nodes.row()
        for cell in cells:
            row += nodes.entry("", cell)
        body += row
    return table


def _targets(document: Any, node: nodes.Node) -> None:
    """Register ``node`` and the rows inside it as targets of ``{ref}`` (label = id)."""
    for n in node.findall(lambda x: bool(getattr(x, "get", lambda k: None)("names"))):
        document.note_explicit_target(n, n)


def key_rows(model: str, props: dict[str, Any], required: list[str]) -> list[list[nodes.Node]]:
    rows = []
    for key, p in props.items():
        desc = plain(p.get("description", ""))
        name = _para(nodes.literal(text=key))
        name["ids"] = [key_id(model, key)]
        name["names"] = [key_id(model, key)]
        if key in required:
            name += nodes.Text(" (required)")
        items = p.get("items") if isinstance(p.get("items"), dict) else {}
        if items.get("description"):
            desc = f"{desc}. Each: {plain(items['description'])}"
        rows.append(
            [
                name,
                _type_para(p),
                _para(nodes.Text(default_text(p))),
                _para(nodes.Text(allowed_text(p))),
                _para(nodes.Text(units(desc))),
                _para(nodes.Text(desc)),
            ]
        )
    return rows


HEADERS = ["key", "type", "default", "allowed", "units", "description"]
WIDTHS = [14, 16, 8, 18, 8, 36]


class ScenarioReference(SphinxDirective):
    """``.. scenario-reference::``: the top-level keys, then one section per table model."""

    has_content = False

    def _rst(self, text: str) -> list[nodes.Node]:
        holder = nodes.container()
        self.state.nested_parse(StringList(text.splitlines(), "rancf schema"), 0, holder)
        return list(holder.children)

    def run(self) -> list[nodes.Node]:
        from rancf import scenario_schema

        schema = scenario_schema()
        out: list[nodes.Node] = []
        top = nodes.section(ids=[section_id("scenario")], names=[section_id("scenario")])
        top += nodes.title(text="Top-level keys")
        top += _para(
            nodes.Text(
                "A file holds either one flexible body (geometry, mesh, section and material, all "
                "required) or a system ([[bodies]]), never both."
            )
        )
        top += _table(HEADERS, key_rows("scenario", schema["properties"], []), WIDTHS)
        out.append(top)
        for name, model in sorted(schema["$defs"].items()):
            sec = nodes.section(ids=[section_id(name)], names=[section_id(name)])
            sec += nodes.title(text=name)
            sec.extend(self._rst(plain(model.get("description", ""))))
            props = model.get("properties", {})
            sec += _table(HEADERS, key_rows(name, props, model.get("required", [])), WIDTHS)
            out.append(sec)
        for sec in out:
            _targets(self.state.document, sec)
        return out


def setup(app: Any) -> dict[str, Any]:
    app.add_directive("scenario-reference", ScenarioReference)
    return {"version": "1", "parallel_read_safe": True, "parallel_write_safe": True}
