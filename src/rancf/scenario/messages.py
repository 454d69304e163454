"""Pydantic validation errors as the one-line :class:`~rancf.errors.ScenarioError`.

A :class:`pydantic.ValidationError` lists every problem with its location, a tuple such as
``("geometry", "[conic]", "angles_deg", 1)``: keys, list indices and the tags of the unions
(``"[conic]"``: which kind of geometry was tried).  The first problem becomes the error: its
location without the tags, plus the key a table's own check named
(:func:`rancf.scenario.base.fail`), spelled
as the file has it (``geometry.angles_deg[1]``, ``loads.point[0].force``, ``bodies[1].mass``),
and the problem in words with the value received (``must be > 0, got -1.0``).
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np
from pydantic import ValidationError
from pydantic_core import ErrorDetails

from rancf.errors import MAX_SHOWN, ScenarioError, shorten

__all__ = ["scenario_error", "key_path", "show"]


def show(value: Any) -> str:
    """A value as an error message shows it: ``repr``, at most :data:`MAX_SHOWN` characters, an
    integer of hundreds of digits by its number of digits."""
    if isinstance(value, int) and not isinstance(value, bool) and abs(value) >= 10**MAX_SHOWN:
        return f"an integer of {math.floor(math.log10(abs(value))) + 1} digits"
    if isinstance(value, np.ndarray):
        value = value.tolist()
    try:
        return shorten(repr(value))
    except RecursionError:
        return f"a {type(value).__name__} nested too deeply to show"


#: Tables that are required at the top of a one-body file (a missing one is a "table").
_TOP_TABLES = ("geometry", "mesh", "section", "material")


def key_path(loc: tuple[Any, ...], extra: str = "") -> str:
    """The key as the file spells it: ``a.b[2].c`` (union tags ``[...]`` left out), followed by
    ``extra`` (a key relative to the location)."""
    out = ""
    for part in loc:
        if isinstance(part, int):
            out += f"[{part}]"
        elif "[" in part or "(" in part:  # a union's tag or a pydantic-internal step
            continue
        else:
            out += f".{part}" if out else part
    if extra:
        out += extra if extra.startswith("[") or not out else f".{extra}"
    return out


def _bound(v: Any) -> str:
    return f"{v:g}" if isinstance(v, float) else str(v)


def problem_of(err: ErrorDetails) -> str:
    """The problem of one pydantic error, in the words of the scenario errors."""
    kind, ctx, value = err["type"], err.get("ctx") or {}, err.get("input")
    got = show(value)
    if kind == "scenario":
        return str(ctx["problem"])
    if kind == "missing":
        return "required key is missing"
    if kind == "choice":  # a kind that selects the table's model (a discriminated union)
        if not isinstance(value, dict):
            return f"must be a table, got {got}"
        if ctx["key"] not in value:
            return "required key is missing"
        return f"must be one of {ctx['allowed']}, got {show(value[ctx['key']])}"
    if kind == "time_function":
        return (
            "must be a number, a vector or a table with one of the keys table, ramp, harmonic, "
            f"spin_up, got {got}"
        )
    simple = {
        "greater_than": lambda: f"must be > {_bound(ctx['gt'])}, got {got}",
        "greater_than_equal": lambda: f"must be >= {_bound(ctx['ge'])}, got {got}",
        "less_than": lambda: f"must be < {_bound(ctx['lt'])}, got {got}",
        "less_than_equal": lambda: f"must be at most {_bound(ctx['le'])}, got {got}",
        "literal_error": lambda: f"must be one of {ctx['expected']}, got {got}",
        "too_short": lambda: f"must have at least {ctx['min_length']} items, got {got}",
        "too_long": lambda: f"must have at most {ctx['max_length']} items, got {got}",
        "list_type": lambda: f"must be an array, got {got}",
        "tuple_type": lambda: f"must be an array, got {got}",
        "dict_type": lambda: f"must be a table, got {got}",
        "model_type": lambda: f"must be a table, got {got}",
        "model_attributes_type": lambda: f"must be a table, got {got}",
        "string_type": lambda: f"must be a string, got {got}",
        "string_pattern_mismatch": lambda: f"must match {ctx['pattern']}, got {got}",
        "extra_forbidden": lambda: "unknown key",
        "frozen_instance": lambda: "cannot be changed (build a new scenario)",
    }
    if kind in simple:
        return simple[kind]()
    msg = str(err.get("msg", kind))
    return msg.removeprefix("Value error, ").removeprefix("Assertion failed, ")


def scenario_error(exc: ValidationError, path: str, prefix: str = "") -> ScenarioError:
    """The :class:`~rancf.errors.ScenarioError` of the first problem of ``exc``.

    Parameters
    ----------
    exc : ValidationError
        What pydantic reported.
    path : str
        The scenario file (or ``"<scenario>"``), named first in the message.
    prefix : str
        The location of the validated table in the scenario (``""``: the whole scenario).
    """
    errors = exc.errors(include_url=False)
    err = errors[0]
    ctx = err.get("ctx") or {}
    loc = tuple(err["loc"])
    extra = str(ctx.get("key", "")) if err["type"] in ("scenario", "choice") else ""
    if err["type"] == "choice" and not isinstance(err.get("input"), dict):
        extra = ""
    key = key_path(loc, extra)
    if prefix:
        key = f"{prefix}.{key}" if key else prefix
    problem = problem_of(err)
    if err["type"] == "missing" and key in _TOP_TABLES:
        problem = "required table is missing"
    return ScenarioError(path, key or "scenario", problem)
