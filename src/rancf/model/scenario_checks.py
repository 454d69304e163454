"""Validation primitives of the scenario parsers: typed values, tables with fixed keys, node places.

Each check takes the scenario's path and the key it validates and raises
:class:`~rancf.errors.ScenarioError` naming both. The helpers are shared by
:mod:`rancf.model.scenario`, :mod:`rancf.model.scenario_tables`,
:mod:`rancf.model.scenario_sensors` and :mod:`rancf.model.scenario_parts` and private to them.
"""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

import numpy as np

from rancf.errors import MAX_SHOWN, InputError, ScenarioError, shorten

_REQ = object()  # marker: required key


def _err(path: str, key: str, problem: str) -> ScenarioError:
    """The error for ``key`` of the scenario at ``path``."""
    return ScenarioError(path, key, problem)


def _number(
    path: str,
    key: str,
    v: Any,
    positive: bool = False,
    nonneg: bool = False,
    bound: float | None = None,
) -> float:
    """A finite number (not a bool), optionally ``> 0`` or ``>= 0``, and at most ``bound`` in
    size."""
    if isinstance(v, bool) or not isinstance(v, int | float):
        raise _err(path, key, f"must be a number, got {_repr(v)}")
    try:
        f = float(v)
    except OverflowError:
        f = float("inf")
    if not np.isfinite(f):
        raise _err(path, key, f"must be finite, got {_repr(v)}")
    if bound is not None and abs(f) > bound:
        raise _err(path, key, f"must be at most {bound:g} in size, got {_repr(v)}")
    if positive and not f > 0:
        raise _err(path, key, f"must be > 0, got {_repr(v)}")
    if nonneg and f < 0:
        raise _err(path, key, f"must be >= 0, got {_repr(v)}")
    return f


def _integer(path: str, key: str, v: Any, minimum: int | None = None) -> int:
    """An integer (not a bool), optionally ``>= minimum``."""
    if isinstance(v, bool) or not isinstance(v, int):
        raise _err(path, key, f"must be an integer, got {_repr(v)}")
    if minimum is not None and v < minimum:
        raise _err(path, key, f"must be >= {minimum}, got {_repr(v)}")
    return int(v)


def _vector(
    path: str, key: str, v: Any, sizes: tuple[int, ...], bound: float | None = None
) -> list[float]:
    """A list of finite numbers (each at most ``bound`` in size) whose length is one of
    ``sizes``."""
    if not isinstance(v, list) or len(v) not in sizes:
        want = " or ".join(str(s) for s in sizes)
        raise _err(path, key, f"must be a list of {want} numbers, got {_repr(v)}")
    return [_number(path, f"{key}[{i}]", x, bound=bound) for i, x in enumerate(v)]


def _choice(path: str, key: str, v: Any, options: tuple[str, ...]) -> str:
    """One of ``options``."""
    if v not in options:
        raise _err(
            path, key, f"must be one of {', '.join(repr(o) for o in options)}, got {_repr(v)}"
        )
    return v


def _table(path: str, key: str, v: Any, schema: dict[str, Any]) -> dict[str, Any]:
    """A table with the keys of ``schema`` only, defaults filled in (``_REQ``: required)."""
    if not isinstance(v, dict):
        raise _err(path, key, f"must be a table, got {_repr(v)}")
    for k in v:
        if k not in schema:
            raise _err(path, f"{key}.{k}", f"unknown key (allowed: {', '.join(schema)})")
    out = {}
    for k, default in schema.items():
        if k in v:
            out[k] = v[k]
        elif default is _REQ:
            raise _err(path, f"{key}.{k}", "required key is missing")
        else:
            out[k] = default
    return out


def _place(path: str, key: str, v: Any) -> int:
    """A node: ``"start"`` (0), ``"end"`` (-1) or a node index."""
    if v == "start":
        return 0
    if v == "end":
        return -1
    if isinstance(v, int) and not isinstance(v, bool):
        return v
    raise _err(path, key, f'must be "start", "end" or a node index, got {_repr(v)}')


def _guard(path: str, key: str, fn: Callable[[], Any]) -> Any:
    """``fn()``, with an :class:`~rancf.errors.InputError` turned into a scenario error."""
    try:
        return fn()
    except ScenarioError:
        raise
    except InputError as exc:
        raise _err(path, exc.parameter, f"{exc.allowed} (got {_show(exc.value)})") from None


def _repr(value: Any) -> str:
    """``repr(value)`` as an error message shows it: at most :data:`~rancf.errors.MAX_SHOWN`
    characters, a huge integer by its number of digits."""
    if isinstance(value, int) and not isinstance(value, bool) and abs(value) >= 10**MAX_SHOWN:
        return f"an integer of about {int(abs(value).bit_length() * 0.30103) + 1} digits"
    return shorten(repr(value))


def _show(value: Any) -> str:
    """A value as an error message shows it (floats and arrays to 6 digits, at most
    :data:`~rancf.errors.MAX_SHOWN` characters)."""
    if isinstance(value, float):
        return f"{value:.6g}"
    if isinstance(value, np.ndarray):
        return shorten(np.array2string(value, precision=6, separator=", ").replace("\n", ""))
    return shorten(value) if isinstance(value, str) else _repr(value)
