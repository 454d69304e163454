"""The CSV rows of the run folders: the bytes ``np.savetxt(..., delimiter=",", fmt="%.12g")``
writes, for every kind of float."""

from __future__ import annotations

import io

import numpy as np
import pytest

from rancf.post.csv_rows import write_rows

SPECIAL = [0.0, -0.0, 1.0, -1.5, 1e-300, 5e-324, 1.7976931348623157e308, np.nan, np.inf, -np.inf]


def _savetxt(table: np.ndarray) -> bytes:
    fh = io.BytesIO()
    np.savetxt(fh, table, delimiter=",", fmt="%.12g")
    return fh.getvalue()


def _ours(table: np.ndarray) -> bytes:
    fh = io.BytesIO()
    write_rows(fh, table)
    return fh.getvalue()


@pytest.mark.parametrize("shape", [(1, 1), (7, 3), (200, 11), (0, 4), (5,)])
def test_the_same_bytes_as_savetxt(shape):
    """Random numbers over 600 decades and the special values, in tables of several shapes
    (a 1-D table is one column; no rows, no bytes)."""
    rng = np.random.default_rng(7)
    table = rng.standard_normal(shape) * 10.0 ** rng.integers(-300, 300, size=shape)
    flat = table.reshape(-1)
    flat[: min(flat.size, len(SPECIAL))] = SPECIAL[: flat.size]
    assert _ours(table) == _savetxt(table)
    assert _ours(table.tolist()) == _savetxt(table)  # not an array: as NumPy reads it


def test_rows_are_appended():
    """Two calls write the rows of both, one after the other."""
    fh = io.BytesIO()
    write_rows(fh, np.array([[1.0, 2.0]]))
    write_rows(fh, np.array([[3.0, 0.1]]))
    assert fh.getvalue() == b"1,2\n3,0.1\n"
