"""``[form]`` (``[bodies.form]`` in a system): a line's unstretched length found from what the
engineer specifies, exactly one of

* ``sag`` [m]: the largest distance below the chord under the static loads (vertical, against
  gravity, from the chord between the body's end positions);
* ``horizontal_tension`` [N]: the horizontal component of the axial force at the body's end;
* ``end_tension`` [N]: the axial force at the body's end.

The length is found by the static solve (:func:`rancf.solvers.form.find_form`) and used by every
analysis of the scenario.
"""

from __future__ import annotations

from typing import Literal

from pydantic import Field, model_validator

from rancf.scenario.base import Positive, Table, fail

__all__ = ["FormTable", "FORM_KEYS"]

#: The targets ``[form]`` takes, exactly one of them.
FORM_KEYS = ("sag", "horizontal_tension", "end_tension")


class FormTable(Table):
    """``[form]``: the target the body's unstretched length is found to meet."""

    sag: Positive | None = Field(
        None,
        description="the largest distance below the chord under the static loads [m] "
        "(vertical, from the chord between the body's ends)",
    )
    horizontal_tension: Positive | None = Field(
        None, description="the horizontal component of the axial force at the body's end [N]"
    )
    end_tension: Positive | None = Field(
        None, description="the axial force at the body's end [N] (the taut solution)"
    )

    @model_validator(mode="after")
    def _one(self) -> FormTable:
        given = [k for k in FORM_KEYS if self[k] is not None]
        if len(given) != 1:
            got = ", ".join(given) if given else "none"
            raise fail("", f"needs exactly one of {', '.join(FORM_KEYS)} (got {got})")
        return self

    @property
    def target(self) -> tuple[Literal["sag", "horizontal_tension", "end_tension"], float]:
        """The key given and its value."""
        for k in FORM_KEYS:
            v = self[k]
            if v is not None:
                return k, float(v)  # type: ignore[return-value]
        raise AssertionError("validated: one key is given")
