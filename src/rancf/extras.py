"""Optional dependencies: a clear one-line message naming the extra to install when one is missing.

Extras: ``cad`` (cadquery-ocp: STEP and IGES files) and ``mp4`` (imageio-ffmpeg: MP4 animations).
"""

from __future__ import annotations

import importlib
from types import ModuleType

from rancf.errors import RancfError

__all__ = ["MissingExtraError", "require"]


class MissingExtraError(RancfError):
    """An optional dependency is not installed; the message says which extra to install."""


def require(module: str, extra: str, purpose: str) -> ModuleType:
    """Import ``module`` or raise :class:`MissingExtraError` naming ``pip install 'rancf[extra]'``.

    Parameters
    ----------
    module : str
        Module to import, e.g. ``"OCP"``.
    extra : str
        The rancf extra that installs it, e.g. ``"cad"``.
    purpose : str
        What needs it, e.g. ``"STEP and IGES files"``.
    """
    try:
        return importlib.import_module(module)
    except ImportError:
        raise MissingExtraError(
            f"{purpose} need the optional package {module!r}: pip install 'rancf[{extra}]'"
        ) from None
