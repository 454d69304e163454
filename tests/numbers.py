"""Comparing output across processes and machines: the text exactly, the numbers in it within a
stated relative tolerance.

Round-off differs between CPUs, compilers and BLAS kernels (``OPENBLAS_CORETYPE``), so a number
printed to 12 significant digits may differ in its last digit on another machine.
Integers (counts: steps, Newton iterations, elements, frames) are compared exactly; every other
number (it has a decimal point or an exponent) within :data:`RTOL` of the expected value, or
:data:`ATOL` for values printed as zero, or one unit in the last printed digit of a number
printed to :data:`LAST_DIGIT_SIG` or more significant digits (a value a round-off away from a
rounding boundary prints either side of it).
"""

from __future__ import annotations

import re
from collections.abc import Mapping, Sequence
from pathlib import Path

import numpy as np

#: Relative tolerance of printed floating-point numbers: far above round-off (about 1e-12 after
#: the README's 1000 time steps), far below any change of the physics or of a printed digit that
#: is not round-off.
RTOL = 1e-7
#: Absolute tolerance for numbers whose expected value is zero (a coordinate at round-off level).
ATOL = 1e-12
#: Significant digits from which a number may differ by one unit in its last printed digit (at
#: most 1e-5 of it): round-off moves a value across a rounding boundary of the print.
LAST_DIGIT_SIG = 6

NUMBER = re.compile(r"(?<![\w.])[-+]?(?:\d+\.\d*|\.\d+|\d+)(?:[eE][-+]?\d+)?(?![\w.])")


def _is_float(token: str) -> bool:
    return any(c in token for c in ".eE")


def _last_digit(token: str) -> float:
    """One unit in the last printed digit of a number with at least :data:`LAST_DIGIT_SIG`
    significant digits (0 for shorter ones): ``1.981833`` -> 1e-6."""
    mantissa, _, exp = token.lower().lstrip("+-").partition("e")
    digits = mantissa.replace(".", "").lstrip("0")
    if len(digits) < LAST_DIGIT_SIG:
        return 0.0
    decimals = len(mantissa.partition(".")[2])
    return 10.0 ** (int(exp or 0) - decimals)


def numbers_match(got: str, expected: str, rtol: float = RTOL, atol: float = ATOL) -> bool:
    """Whether two numbers as printed agree (integers exactly, floats within the tolerance, or
    one unit apart in the last digit of a number printed to 6 or more significant digits: two
    values a round-off apart can round to either side of a printed digit)."""
    if not (_is_float(got) or _is_float(expected)):
        return int(got) == int(expected)
    a, b = float(got), float(expected)
    unit = 1.0001 * _last_digit(expected)
    return abs(a - b) <= max(rtol * abs(b), unit, atol if b == 0.0 or a == 0.0 else 0.0)


#: Counts that follow round-off (another BLAS kernel takes another Newton iteration): compared
#: as text around them, not as numbers.
COUNTS = re.compile(r"\b\d+ (?=(?:load steps|Newton iterations)\b)")


def text_matches(got: str, expected: str, rtol: float = RTOL, atol: float = ATOL) -> bool:
    """Whether ``got`` is ``expected`` with every number within the tolerance (iteration and
    load-step counts aside: :data:`COUNTS`)."""
    got, expected = COUNTS.sub("# ", got), COUNTS.sub("# ", expected)
    parts_got, parts_exp = NUMBER.split(got), NUMBER.split(expected)
    nums_got, nums_exp = NUMBER.findall(got), NUMBER.findall(expected)
    return (
        parts_got == parts_exp
        and len(nums_got) == len(nums_exp)
        and all(numbers_match(a, b, rtol, atol) for a, b in zip(nums_got, nums_exp, strict=True))
    )


def assert_lines_match(
    got: Sequence[str], expected: Sequence[str], rtol: float = RTOL, what: str = ""
) -> None:
    """Assert that two outputs agree line by line (:func:`text_matches`)."""
    bad = [
        (i, g, e)
        for i, (g, e) in enumerate(zip(got, expected, strict=False))
        if not text_matches(g, e, rtol)
    ]
    assert len(got) == len(expected) and not bad, (what, list(got), list(expected), bad)


def assert_rows_match(
    got: Sequence[Mapping[str, str]], expected: Sequence[Mapping[str, str]], rtol: float = RTOL
) -> None:
    """Assert that two tables (CSV rows as dictionaries of text) agree cell by cell."""
    assert [list(r) for r in got] == [list(r) for r in expected]
    for g, e in zip(got, expected, strict=True):
        for key in e:
            assert text_matches(g[key], e[key], rtol), (key, g[key], e[key])


def csv_columns(path: str | Path) -> dict[str, np.ndarray]:
    """A numeric CSV file with one header line (``sensors.csv``, ``reactions.csv``) as columns by
    name."""
    head, *rows = Path(path).read_text().splitlines()
    vals = np.array([[float(x) for x in r.split(",")] for r in rows])
    return {c: vals[:, i] for i, c in enumerate(head.split(","))}
