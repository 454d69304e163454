"""Element families in the compiled core: what differs between the element kinds is asked of
the registry (``src/cpp/elements/registry.hpp``: ``kernel_for(m)`` and its traits), never of the
model's element kind elsewhere in ``src/cpp``."""

from __future__ import annotations

import re
from pathlib import Path

CPP = Path(__file__).resolve().parents[2] / "src" / "cpp"

#: A test of an element kind: a comparison with, or a case of, an ElementKind value.
KIND_TEST = re.compile(
    r"(==|!=)\s*(rancf::)?ElementKind::|ElementKind::\w+\s*(==|!=)|case\s+ElementKind::"
)
#: Where the kinds are named: the registry itself, and the binding that reads a model record's
#: per-family arrays (cable quadrature, beam lengths, rod frames) into the model's views.
REGISTRY = {"elements/registry.cpp", "elements/registry.hpp", "bindings/bindings_model.hpp"}


def _found() -> list[str]:
    return [
        f"{f.relative_to(CPP)}:{i}: {line.strip()}"
        for f in sorted([*CPP.rglob("*.cpp"), *CPP.rglob("*.hpp")])
        if str(f.relative_to(CPP)) not in REGISTRY
        for i, line in enumerate(f.read_text(encoding="utf-8").splitlines(), 1)
        if KIND_TEST.search(line)
    ]


def test_no_element_kind_dispatch_outside_the_registry():
    found = _found()
    assert not found, "\n".join(found)


def test_the_scan_finds_a_dispatch():
    assert KIND_TEST.search("if (m.kind == ElementKind::rod) return;")
    assert KIND_TEST.search("if (h.m.kind != rancf::ElementKind::beam)")
    assert KIND_TEST.search("    case ElementKind::cable:")
    assert not KIND_TEST.search("ElementKind kind = ElementKind::cable;")


def test_the_registry_dispatches_once():
    """The registry's own switch is the one place the kinds are told apart (one case each)."""
    text = (CPP / "elements" / "registry.cpp").read_text(encoding="utf-8")
    assert sorted(re.findall(r"case ElementKind::(\w+)", text)) == ["beam", "cable", "rod", "shell"]
