"""Membrane locking of the shell element, at the kernel level (linear solves of
benchmarks/shell_locking.py; docs/derivations/shell.md sec. 5, 9): the Scordelis–Lo roof and
the pinched cylinder against their published values, the projected membrane strains softer than
the full ones where the full ones lock, a flat plate unchanged by the treatment, and the
convergence table of the derivation reproduced."""

from __future__ import annotations

import importlib.util
import re
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]
SPEC = importlib.util.spec_from_file_location(
    "shell_locking", ROOT / "benchmarks" / "shell_locking.py"
)
assert SPEC is not None and SPEC.loader is not None
CASES = importlib.util.module_from_spec(SPEC)
SPEC.loader.exec_module(CASES)
DOC = (ROOT / "docs" / "derivations" / "shell.md").read_text(encoding="utf-8")


def test_scordelis_lo_roof_on_a_coarse_mesh():
    """The middle of the free edge moves down 0.3006 within 1.5 % with 2 × 2 elements on the
    quarter (projected membrane strains) and within 0.1 % with 4 × 4."""
    assert CASES.roof(2, "projected") == pytest.approx(CASES.ROOF_REF, rel=0.015)
    assert CASES.roof(4, "projected") == pytest.approx(CASES.ROOF_REF, rel=0.001)


def test_pinched_cylinder_with_16_elements_a_side():
    """1.8248e-5 under the load within 2 % with 16 × 16 elements on the eighth."""
    assert CASES.pinched(16, "projected") == pytest.approx(CASES.PINCHED_REF, rel=0.02)


def test_projected_membrane_strains_relieve_locking():
    """Where the full membrane strains lock (the pinched cylinder on coarse meshes), the
    projected ones are softer and closer to the reference on every mesh, by a third of the
    error with 4 × 4 elements."""
    ref = CASES.PINCHED_REF
    for n in (2, 4, 8):
        full, projected = CASES.pinched(n, "full"), CASES.pinched(n, "projected")
        assert abs(projected - ref) < abs(full - ref), (n, full, projected)
        if n == 4:
            assert abs(projected - ref) <= abs(full - ref) * 2.0 / 3.0, (full, projected)


def test_a_flat_plate_is_the_same_with_every_treatment():
    """No membrane–bending coupling in a flat plate: the treatments agree to 1e-10 and converge
    to the Navier series (1e-4 with 8 × 8 elements)."""
    values = [CASES.plate(8, m) for m in ("full", "projected", "reduced")]
    assert max(values) - min(values) <= 1e-10
    assert values[0] == pytest.approx(1.0, abs=1e-4)


def test_the_derivation_holds_the_convergence_table():
    table = CASES.table([2, 4, 8, 16])
    section = DOC[DOC.index("## 9.") :]
    for line in table.splitlines():
        assert line in section, line
    assert re.search(r"\| 16 \|", section)
