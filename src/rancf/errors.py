"""Exception hierarchy of rancf.

Every error raised at the public boundary is a subclass of :class:`RancfError`.  Bad input
raises a subclass of :class:`InputError` (itself a :class:`ValueError`), whose message names the
parameter, the value received and what is allowed, so that the command line can print it on one
line.
"""

from __future__ import annotations

from typing import Any


class RancfError(Exception):
    """Base class of every error raised by rancf."""


class InputError(RancfError, ValueError):
    """A parameter has a value that is not allowed.

    Parameters
    ----------
    parameter : str
        Name of the offending parameter, as the user wrote it.
    value : Any
        The value received.
    allowed : str
        What would have been accepted.
    """

    def __init__(self, parameter: str, value: Any, allowed: str) -> None:
        self.parameter = parameter
        self.value = value
        self.allowed = allowed
        super().__init__(f"{parameter} = {_fmt(value)} is not allowed: {allowed}")


#: Longest value shown in an error message (longer ones are cut in the middle: a message stays
#: one readable line whatever was given, e.g. a 401-digit integer or a file's content).
MAX_SHOWN = 80


def shorten(text: str, limit: int = MAX_SHOWN) -> str:
    """``text`` cut to at most ``limit`` characters, the middle replaced by ``...``."""
    if len(text) <= limit:
        return text
    keep = (limit - 3) // 2
    return f"{text[:keep]}...{text[len(text) - keep :]}"


def _fmt(value: Any) -> str:
    try:
        import numpy as np

        if isinstance(value, np.ndarray):
            return shorten(np.array2string(value, precision=6, separator=", ").replace("\n", ""))
    except ImportError:  # pragma: no cover
        pass
    if isinstance(value, float):
        return f"{value:.6g}"
    if isinstance(value, int) and not isinstance(value, bool) and abs(value) >= 10**MAX_SHOWN:
        return f"an integer of about {int(abs(value).bit_length() * 0.30103) + 1} digits"
    return shorten(repr(value))


class AngleError(InputError):
    """An end-tangent angle outside the open interval (0°, 90°)."""


class ChordError(InputError):
    """A chord length that is not strictly positive (or coincident end points)."""


class InteriorPointError(InputError):
    """An interior point on or outside the tangent triangle, so that it fixes no conic arc."""


class MappingFactorError(InputError):
    """A mapping factor K outside the open interval (0, 1)."""


class ElementCountError(InputError):
    """A number of elements smaller than one."""


class KnotVectorError(InputError):
    """A knot vector that decreases, is too short, or has a knot of too high multiplicity."""


class WeightError(InputError):
    """A rational weight that is not strictly positive."""


class ScenarioError(RancfError, ValueError):
    """A scenario file that cannot be used; the message names the file and the key."""

    def __init__(self, path: str, key: str, problem: str) -> None:
        self.path = path
        self.key = key
        self.problem = problem
        super().__init__(f"{path}: [{key}] {problem}")


class ConvergenceError(RancfError):
    """A nonlinear solve that did not converge; carries the time or load level reached."""

    def __init__(self, message: str, reached: float | None = None) -> None:
        self.reached = reached
        super().__init__(message)


class RunTooLargeError(RancfError):
    """A run whose stored output would exceed the disk limit (``--max-output-gb``); refused
    before it starts."""


class RunFailedError(RancfError):
    """A run that started and then failed for a reason outside the model (a full disk, an
    unwritable file); its run directory keeps the results of its last complete checkpoint."""
