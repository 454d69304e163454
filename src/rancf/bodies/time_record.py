"""The records of time functions that the compiled core evaluates.

:func:`core_record` packs a :class:`~rancf.bodies.time_function.TimeFunction` into the named
record of :class:`rancf.kernels.records.TimeFunctionRecord`; the core evaluates the same closed
forms (T.1)-(T.6) (``src/cpp/system/time_function.hpp``), a table as its piecewise cubic
coefficients (:func:`table_coefficients`).
"""

from __future__ import annotations

import numpy as np
from numpy.typing import NDArray

from rancf.bodies.time_function import TimeFunction
from rancf.errors import InputError
from rancf.kernels.records import TimeFunctionRecord, floats

__all__ = ["CORE_KINDS", "core_record", "table_coefficients"]

#: The kinds the compiled core evaluates and its names of them (a callable goes as its sampled
#: table).
CORE_KINDS = {
    "constant": "constant",
    "table": "piecewise",
    "ramp": "ramp",
    "harmonic": "harmonic",
    "spin_up": "spin_up",
}


def table_coefficients(f: TimeFunction) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """A table's breakpoints ``(k + 1,)`` and piecewise-cubic coefficients ``(k, 4, n)``
    (``c0 + c1 s + c2 s² + c3 s³``, ``s = t − t_i``); empty arrays for the other kinds."""
    if f.kind != "table" or f.rows is None:
        return np.zeros(0), np.zeros(0)
    t, v = f.rows[:, 0], f.rows[:, 1:]
    coef = np.zeros((t.size - 1, 4, v.shape[1]))
    if f.spline is None:
        coef[:, 0] = v[:-1]
        coef[:, 1] = np.diff(v, axis=0) / np.diff(t)[:, None]
    else:
        coef = np.transpose(f.spline.c[::-1], (1, 0, 2))
    return t.copy(), np.ascontiguousarray(coef)


def core_record(f: TimeFunction) -> TimeFunctionRecord:
    """The record of ``f`` the compiled core evaluates
    (:class:`rancf.kernels.records.TimeFunctionRecord`; a table is the core's ``piecewise``
    kind with its :func:`table_coefficients`).

    A callable cannot be called from the compiled loop: give ``f.sampled(t_end)`` instead.
    """
    if f.kind not in CORE_KINDS:
        raise InputError(
            "time function",
            f.fn,
            "a function the core evaluates (sample a Python callable first: f.sampled(t_end))",
        )
    breaks, coef = table_coefficients(f)
    return TimeFunctionRecord(
        CORE_KINDS[f.kind],
        floats(f.values),
        f.duration,
        f.frequency,
        f.phase,
        floats(breaks),
        floats(coef),
        f.build_up,
    )
