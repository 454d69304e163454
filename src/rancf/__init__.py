"""rancf: rational ANCF conic-section cable elements — geometry, CAD conversions and dynamics."""

__version__ = "0.2.0"  # the single source of the version (pyproject reads it)

__all__ = ["__version__"]
