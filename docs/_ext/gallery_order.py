"""The order of the gallery: the paper's studies, the other shipped scenarios, then scripts."""

from __future__ import annotations

from pathlib import Path

ORDER = [
    "plot_planar_pendulum.py",
    "plot_spatial_pendulum.py",
    "plot_arc_vibration.py",
    "plot_exact_geometry.py",
    "plot_belt_drive.py",
    "plot_cantilever.py",
    "plot_capstan.py",
    "plot_installed_hose.py",
    "plot_robot_cable.py",
    "plot_slider_crank.py",
    "plot_spin_up_beam.py",
    "plot_tether_payload.py",
    "plot_ring.py",
    "plot_mooring_line.py",
    "plot_power_line_gust.py",
    "plot_power_line_sag.py",
]


class GalleryOrder:
    """sphinx-gallery's ``within_subsection_order``: scripts of :data:`ORDER` first, in that
    order, then any other script by file name."""

    def __init__(self, src_dir: str) -> None:
        self.src_dir = src_dir

    def __call__(self, filename: str) -> tuple[int, str]:
        name = Path(filename).name
        return (ORDER.index(name) if name in ORDER else len(ORDER), name)
