"""A flexible body's history read back (its centreline sampled: :mod:`rancf.post.centerline`).

Every flexible body of a run has its folder ``RUN_DIR/bodies/NAME`` (:mod:`rancf.post.run_files`)
whose ``results.npz`` holds the body's state history and, in its metadata, the section radius
and (beams) the reference nodal tangent angles (:func:`rancf.post.run_files.reader_metadata`),
so :func:`load_body` needs no scenario file; runs are read with
:func:`rancf.post.system_run.load_run`.  Runs written by rancf < 0.3 (one body, its arrays in
the run folder's own ``results.npz``, without those keys) take them from the scenario that
produced them (the run's ``scenario.toml`` when present, else the path recorded in
``summary.json``).
"""

from __future__ import annotations

import json
import logging
import math
import os
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np
from numpy.typing import NDArray

from rancf.bodies.families import ElementFamily, family
from rancf.errors import InputError, shorten
from rancf.post.results import load_results
from rancf.post.run_checks import check_results, scenario_fits

__all__ = ["RunData", "load_body", "frame_indices"]

logger = logging.getLogger(__name__)


@dataclass(frozen=True)
class RunData:
    """A run read back from its directory.

    Attributes
    ----------
    path : Path
        The run directory.
    t : ndarray, shape (n_t,)
    q, v : ndarray, shape (n_t, n_dofs)
        Full nodal coordinates and velocities.
    reference : ndarray, shape (n_dofs,)
    weights : ndarray, shape (n_el, 4)
    scales : ndarray, shape (n_el,)
    element : {"rancf", "ancf", "beam"}
    dim : int
    sensor_names : list of str
    sensors : ndarray, shape (n_t, n_sensor_columns)
    energies : dict of str -> ndarray (n_t,)
        ``kinetic``, ``strain``, ``gravity``.
    radius : float or None
        Section radius (``sqrt(A / π)`` for a section given by area), from the run's metadata
        (older runs: from their scenario; None if there is neither).
    tangent_angles : ndarray (n_nodes,) or None
        Reference tangent angles of beam nodes (None for cables, or an older run without its
        scenario).
    directors : ndarray (n_t, n_nodes, 3) or None
        Rods: the first material axis ``m1`` of every node's triad (None for other elements).
    static : bool
        A static load path (``rancf static --out``): ``t`` holds the load factor ``λ``.
    along : ndarray (n_t, n_points, n_names) or None
        Section quantities at ``ξ = 0, 1/4, 1/2, 3/4`` of every element and the last node
        (:mod:`rancf.bodies.section_outputs`; None for older runs).
    section_names : list of str
        Their names.
    """

    path: Path
    t: NDArray[np.float64]
    q: NDArray[np.float64]
    v: NDArray[np.float64]
    reference: NDArray[np.float64]
    weights: NDArray[np.float64]
    scales: NDArray[np.float64]
    element: str
    dim: int
    sensor_names: list[str]
    sensors: NDArray[np.float64]
    energies: dict[str, NDArray[np.float64]]
    radius: float | None
    tangent_angles: NDArray[np.float64] | None
    directors: NDArray[np.float64] | None = None
    static: bool = False
    along: NDArray[np.float64] | None = None
    section_names: list[str] = field(default_factory=list)

    @property
    def family(self) -> ElementFamily:
        """The element family of :attr:`element` (:mod:`rancf.bodies.families`)."""
        return family(self.element)

    @property
    def time_label(self) -> str:
        """Axis label of ``t``: the time, or the load factor of a static load path."""
        return "load factor λ [-]" if self.static else "t [s]"

    def time_text(self, value: float, fmt: str = ".4g") -> str:
        """``t = 0.5 s``, or ``λ = 0.5`` for a static load path."""
        return f"λ = {value:{fmt}}" if self.static else f"t = {value:{fmt}} s"

    @property
    def name(self) -> str:
        """The run's name: its directory name (bytes that are not UTF-8 shown as U+FFFD, so the
        name can go into file names, XML and figure titles)."""
        return os.fsencode(self.path.resolve().name).decode("utf-8", "replace")

    @property
    def n_nodes(self) -> int:
        """Number of nodes."""
        return self.weights.shape[0] + 1

    def time_index(self, time: float | None) -> int:
        """Index of the stored time closest to ``time`` (None: the last stored time)."""
        if time is None:
            return self.t.size - 1
        if not (math.isfinite(time) and self.t[0] - 1e-12 <= time <= self.t[-1] + 1e-12):
            raise InputError(
                "--time", time, f"a time within the stored range [{self.t[0]:g}, {self.t[-1]:g}] s"
            )
        return int(np.argmin(np.abs(self.t - time)))


def _summary(run_dir: Path) -> dict[str, Any]:
    try:
        doc = json.loads((run_dir / "summary.json").read_text(encoding="utf-8"))
    except (OSError, ValueError):
        return {}
    return doc if isinstance(doc, dict) else {}


def _find_scenario(run_dir: Path) -> tuple[Path | None, bool]:
    """The run's scenario and whether it is the run's own copy (``scenario.toml``)."""
    own = run_dir / "scenario.toml"
    if own.is_file():
        return own, True
    recorded = _summary(run_dir).get("scenario")
    if isinstance(recorded, str) and recorded and Path(recorded).is_file():
        return Path(recorded), False
    return None, False


def read_results(path: Path) -> dict[str, Any]:
    """``path/results.npz`` read (:func:`rancf.post.results.load_results`), or one line naming
    the folder or the file and what is wrong with it."""
    npz = path / "results.npz"
    if not path.is_dir():
        why = "it is a file" if path.exists() else "the folder does not exist"
        raise InputError(
            "RUN_DIR", str(path), f"a run directory written by `rancf simulate` ({why})"
        )
    if not npz.is_file():
        raise InputError("RUN_DIR", str(path), "a run directory holding results.npz")
    try:
        data = load_results(npz)
        if not isinstance(data["metadata"], dict):
            raise ValueError("its metadata is not a table")
    except Exception as exc:  # noqa: BLE001 - a damaged file: cut short, empty, not a zip
        reason = shorten(" ".join(f"{type(exc).__name__}: {exc}".split()))
        raise InputError("RUN_DIR", str(npz), f"a readable results.npz ({reason})") from None
    return data


def load_body(folder: str | Path, static: bool = False) -> RunData:
    """Read a flexible body's ``FOLDER/results.npz`` (``static``: of a static load path).

    A run of rancf < 0.3 (its one body's arrays in the run folder itself) takes what its
    results lack from its scenario: its own ``scenario.toml`` must match the results; a
    scenario found only through the path ``summary.json`` records is skipped, with a warning,
    when it no longer matches or no longer reads.

    Raises
    ------
    InputError
        If ``folder`` is not a directory holding a readable, consistent ``results.npz``, or
        its own ``scenario.toml`` does not match it.
    """
    path = Path(folder)
    data = read_results(path)
    npz = path / "results.npz"
    try:
        check_results(npz, data)
    except InputError:
        raise
    except Exception as exc:  # noqa: BLE001 - arrays missing
        reason = shorten(" ".join(f"{type(exc).__name__}: {exc}".split()))
        raise InputError("RUN_DIR", str(npz), f"a readable results.npz ({reason})") from None
    meta: dict[str, Any] = data["metadata"]
    radius = meta.get("section_radius")
    angles = None if meta.get("tangent_angles") is None else np.array(meta["tangent_angles"])
    sc_path, own = _find_scenario(path)
    if radius is not None and not own:
        sc_path = None  # the results hold what readers need; the run's own copy is still checked
    sc = None
    if sc_path is not None:
        from rancf.errors import ScenarioError
        from rancf.scenario import load_scenario

        try:
            sc = load_scenario(sc_path)
            why = scenario_fits(sc, meta)
        except ScenarioError as exc:
            if own:
                raise
            sc, why = None, str(exc)
        if why is not None and own:
            raise InputError(
                "RUN_DIR", str(path), f"a run whose scenario.toml fits its results ({why})"
            )
        if why is not None:
            logger.warning("%s: skipping the scenario %s: %s", path, sc_path, why)
            sc = None
    if sc is not None and radius is None:  # runs of rancf < 0.3
        s = sc.data["bodies"][0]["section"]
        radius = s["radius"] if s["radius"] is not None else math.sqrt(s["area"] / math.pi)
        if not family(meta["element"]).gradient and angles is None:
            nodes = sc.build_model().mesh.nodes
            if nodes.shape[0] != meta["n_elements"] + 1:
                raise InputError(
                    "RUN_DIR",
                    str(path),
                    f"a run whose scenario fits its results ({sc_path} "
                    f"meshes {nodes.shape[0] - 1} elements, the results hold {meta['n_elements']})",
                )
            angles = np.arctan2(nodes[:, 1, 1], nodes[:, 1, 0])
    elif radius is None:
        logger.warning("%s: no scenario found; no radius field, beams drawn with chords", path)
    return RunData(
        path=path,
        t=data["t"],
        q=data["q"],
        v=data["v"],
        reference=data["reference"],
        weights=data["weights"],
        scales=data["scales"],
        element=meta["element"],
        dim=int(meta["dim"]),
        sensor_names=list(meta["sensor_columns"]),
        sensors=np.asarray(data["sensors"]).reshape(data["t"].size, -1),
        energies={k: data[k] for k in ("kinetic", "strain", "gravity")},
        radius=radius,
        tangent_angles=angles,
        directors=data.get("directors"),
        static=static,
        along=data.get("along"),
        section_names=list(meta.get("section_names", [])),
    )


def frame_indices(n_t: int, every: int) -> NDArray[np.int64]:
    """Every ``every``-th stored time from the first, and always the last."""
    if isinstance(every, bool) or not isinstance(every, int | np.integer) or every < 1:
        raise InputError("--every", every, "an integer >= 1")
    idx = np.arange(0, n_t, every)
    if idx[-1] != n_t - 1:
        idx = np.append(idx, n_t - 1)
    return idx
