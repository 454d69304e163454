"""rancf: rational ANCF conic-section cable elements — geometry, CAD conversions and dynamics."""

from importlib.metadata import PackageNotFoundError, version

try:
    __version__ = version("rancf")
except PackageNotFoundError:  # pragma: no cover - running from a source tree
    __version__ = "0+unknown"

__all__ = ["__version__"]
