"""Element families: what differs between the element kinds is asked of one registry
(:mod:`rancf.bodies.families`), never of the kind's name elsewhere in the package."""

from __future__ import annotations

import re
import tomllib
from pathlib import Path

import pytest

from rancf.bodies.families import FAMILIES, family, framed
from rancf.errors import InputError
from rancf.scenario import parse_scenario

SRC = Path(__file__).resolve().parents[2] / "src" / "rancf"

#: A comparison with an element kind's name.
KIND_TEST = re.compile(
    r'(==|!=|\bin|\bnot in)\s*\(?"(rod|beam|rancf|ancf)"|"(rod|beam|rancf|ancf)"\s*(==|!=|\bin\b)'
)
#: A test of a body's kernel class (the family knows it: ``family.rod_kernel(kernel)``).
KERNEL_TEST = re.compile(
    r"isinstance\([^)]*\b(CableKernel|RodKernel|BeamKernel)\b|\{(CableKernel|RodKernel|BeamKernel):"
)
#: Being split into a stepper and its loop on another branch.
PENDING = {"solvers/dynamic.py"}

SPATIAL = """
[geometry]
kind = "line"
start = [0.0, 0.0, 0.0]
end = [1.0, 0.0, 0.0]
[mesh]
elements = 3
element = "{element}"
[section]
radius = 0.01
[material]
density = 1000.0
youngs_modulus = 1.0e7
poisson_ratio = 0.3
[[supports]]
at = "start"
kind = "clamp"
"""


def test_no_kind_names_compared_outside_the_registry():
    found = [
        f"{f.relative_to(SRC)}:{i}: {line.strip()}"
        for f in sorted(SRC.rglob("*.py"))
        if f.name != "families.py" and str(f.relative_to(SRC)) not in PENDING
        for i, line in enumerate(f.read_text(encoding="utf-8").splitlines(), 1)
        if KIND_TEST.search(line)
    ]
    assert not found, "\n".join(found)
    assert KIND_TEST.search('if model.element == "rod":') and KIND_TEST.search('el in ("rancf",')


def test_no_kernel_classes_tested_outside_the_registry():
    found = [
        f"{f.relative_to(SRC)}:{i}: {line.strip()}"
        for f in sorted(SRC.rglob("*.py"))
        if f.name != "families.py"
        for i, line in enumerate(f.read_text(encoding="utf-8").splitlines(), 1)
        if KERNEL_TEST.search(line)
    ]
    assert not found, "\n".join(found)
    assert KERNEL_TEST.search("c = k.cable if isinstance(k, RodKernel) else k")
    assert KERNEL_TEST.search("if not isinstance(kernel, CableKernel | RodKernel):")
    assert KERNEL_TEST.search("kind = {CableKernel: 0, BeamKernel: 1}[type(k)]")
    assert not KERNEL_TEST.search("def _cable(model: Model) -> CableKernel:")


@pytest.mark.parametrize("name", sorted(FAMILIES))
def test_a_family_gives_its_kernel_as_its_class(name):
    """Each family's kernel accessors answer for its own kernel only, and the core's kind."""
    fam = family(name)
    dim = fam.dims[-1]
    text = SPATIAL.format(element=name)
    if dim == 2:
        text = text.replace("0.0, 0.0, 0.0", "0.0, 0.0").replace("1.0, 0.0, 0.0", "1.0, 0.0")
    if not fam.has_triads:
        text = text.replace("poisson_ratio = 0.3\n", "")
    k = parse_scenario(tomllib.loads(text)).build_model().kernel
    got = {
        "cable": fam.cable_kernel(k) is k,
        "rod": fam.rod_kernel(k) is k,
        "beam": fam.beam_kernel(k) is k,
    }
    assert got == {"cable": fam.cable, "rod": fam.has_triads, "beam": not fam.gradient}
    assert (
        sum(x is not None for x in (fam.cable_kernel(k), fam.rod_kernel(k), fam.beam_kernel(k)))
        == 1
    )
    line = fam.centre_line(k)
    assert (line is None) == (not fam.gradient)
    assert line is None or type(line).__name__ == "CableKernel"
    assert fam.core_kind == {"cable": 0, "beam": 1, "rod": 2}[fam.place_kind]


@pytest.mark.parametrize("dim", [2, 3])
@pytest.mark.parametrize("name", sorted(FAMILIES))
def test_a_family_knows_its_layout(name, dim):
    fam = family(name)
    if dim not in fam.dims:
        with pytest.raises(InputError, match="mesh.element"):
            fam.check_dim(dim)
        return
    text = SPATIAL.format(element=name)
    if dim == 2:
        text = text.replace("0.0, 0.0, 0.0", "0.0, 0.0").replace("1.0, 0.0, 0.0", "1.0, 0.0")
    if not fam.has_triads:
        text = text.replace("poisson_ratio = 0.3\n", "")
    model = parse_scenario(tomllib.loads(text)).build_model()
    assert model.family is fam and model.dpn == fam.dofs_per_node(dim)
    assert model.kernel.mass_matrices().shape[1:] == (2 * model.dpn, 2 * model.dpn)
    assert framed(name) is fam.has_triads and fam.place_kind in ("cable", "rod", "beam")


def test_an_unknown_kind_is_refused_naming_the_known_ones():
    with pytest.raises(InputError, match='one of "rancf", "ancf", "beam", "rod"'):
        family("shell")
    assert not framed("rigid") and not framed(None)
