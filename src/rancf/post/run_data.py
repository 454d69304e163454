"""A finished run directory read back, and its centreline sampled densely from the elements.

A run directory (written by :func:`rancf.post.results.write_run`) holds ``results.npz`` with the
full state history and, in its metadata, the section radius and (beams) the reference nodal
tangent angles (:func:`rancf.post.results.reader_metadata`), so :func:`load_run` needs no
scenario file.  Runs written before those keys existed take them from the scenario that
produced them (the run's ``scenario.toml`` when present, else the path recorded in
``summary.json``).

:func:`sample_centerline` evaluates the *exact* element interpolation, not the node polyline:
for cable elements ``r(ξ) = Σ N_k(ξ) e_k`` with the rational shape functions of
:mod:`rancf.elements.cable` (conic-section paper eqs. 17–22), and the fields

* axial strain (Green–Lagrange, as in the element) ``ε = (|r'|² − |r0'|²) / (2 |r0'|²)``;
* curvature ``κ = (r' × r'')·e_z / |r'|³`` (planar, signed) or ``|r' × r''| / |r'|³`` (spatial);
* displacement ``r − r0`` and velocity ``Σ N_k(ξ) ė_k``.

Rod elements (nodal ``r, r_x, φ``) have the cable's centreline; their runs also store the nodal
directors ``m1`` (:attr:`RunData.directors`), which with the tangent give each node's material
frame (:func:`nodal_frames`).

Beam elements (nodal ``x, y, θ``) are drawn as the cubic Hermite curve through the nodes with end
tangents ``L (cos ψ, sin ψ)``, ``ψ = ψ0 + θ``, ``L`` the current chord; their axial strain is the
element's chord strain ``(L² − L0²) / (2 L0²)``.

Shape conventions: states ``q``, ``v`` ``(n_t, n_dofs)``; sampled fields ``(n_points, ...)``.
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

from rancf.elements.cable import axial_strain, cable_shape_functions
from rancf.errors import InputError, shorten
from rancf.post.results import load_results
from rancf.post.run_checks import check_results, scenario_fits

__all__ = [
    "RunData",
    "Centerline",
    "NodalFrames",
    "load_run",
    "sample_centerline",
    "centerline_nodes",
    "nodal_frames",
    "frame_indices",
]

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


def load_run(run_dir: str | Path) -> RunData:
    """Read ``RUN_DIR/results.npz`` (and the scenario, if it can be found).

    The run's own ``scenario.toml`` must match the results; a scenario found only through the
    path ``summary.json`` records (older runs) is skipped, with a warning, when it no longer
    matches or no longer reads.

    Raises
    ------
    InputError
        If ``run_dir`` is not a directory holding a readable, consistent ``results.npz``, or
        its own ``scenario.toml`` does not match it.
    """
    path = Path(run_dir)
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
        check_results(npz, data)
    except InputError:
        raise
    except Exception as exc:  # noqa: BLE001 - a damaged file: cut short, empty, not a zip
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
        s = sc.data["section"]
        radius = s["radius"] if s["radius"] is not None else math.sqrt(s["area"] / math.pi)
        if meta["element"] == "beam" and angles is None:
            nodes = sc.build_model().mesh.nodes
            if nodes.shape[0] != meta["n_elements"] + 1:
                raise InputError(
                    "RUN_DIR", str(path), f"a run whose scenario fits its results ({sc_path} "
                    f"meshes {nodes.shape[0] - 1} elements, the results hold {meta['n_elements']})",
                )  # fmt: skip
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
        static=_summary(path).get("analysis") == "static",
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


@dataclass(frozen=True)
class Centerline:
    """Dense samples of the centreline in one configuration.

    Attributes
    ----------
    points, reference, displacement, velocity : ndarray, shape (n_points, dim)
    axial_strain, curvature : ndarray, shape (n_points,)
    element : ndarray of int, shape (n_points,)
        Element each sample belongs to (a shared node counts for the element it starts).
    """

    points: NDArray[np.float64]
    reference: NDArray[np.float64]
    displacement: NDArray[np.float64]
    velocity: NDArray[np.float64]
    axial_strain: NDArray[np.float64]
    curvature: NDArray[np.float64]
    element: NDArray[np.int64]


def _join(a: NDArray) -> NDArray:
    """``(n_el, n_xi, ...)`` samples with shared element ends → ``(n_el (n_xi-1) + 1, ...)``."""
    return np.concatenate([a[:, :-1].reshape((-1,) + a.shape[2:]), a[-1:, -1]], axis=0)


def _curvature(d1: NDArray, d2: NDArray) -> NDArray:
    speed = np.linalg.norm(d1, axis=-1)
    if d1.shape[-1] == 2:
        cross = d1[..., 0] * d2[..., 1] - d1[..., 1] * d2[..., 0]
    else:
        cross = np.linalg.norm(np.cross(d1, d2), axis=-1)
    return cross / speed**3


def centerline_nodes(run: RunData, x: NDArray) -> NDArray[np.float64]:
    """Nodal position and gradient ``(n_nodes, 2, dim)`` of a cable or rod state ``x``
    (coordinates or velocities); a rod's twist ``φ`` is left out."""
    if run.element == "beam":
        raise ValueError("beam elements have no nodal gradients")
    nodes = np.asarray(x, dtype=float).reshape(run.n_nodes, -1)
    return nodes[:, : 2 * run.dim].reshape(run.n_nodes, 2, run.dim)


def _cable_fields(run: RunData, q: NDArray, v: NDArray, xi: NDArray) -> tuple[NDArray, ...]:
    n, n1, n2 = cable_shape_functions(run.weights, run.scales, xi)

    def element_nodal(x: NDArray) -> NDArray:
        nodes = centerline_nodes(run, x)
        return np.concatenate([nodes[:-1], nodes[1:]], axis=1)  # (n_el, 4, dim)

    e, e0, ev = element_nodal(q), element_nodal(run.reference), element_nodal(v)
    r, r0 = np.einsum("eqk,ekd->eqd", n, e), np.einsum("eqk,ekd->eqd", n, e0)
    d1, d10 = np.einsum("eqk,ekd->eqd", n1, e), np.einsum("eqk,ekd->eqd", n1, e0)
    d2 = np.einsum("eqk,ekd->eqd", n2, e)
    vel = np.einsum("eqk,ekd->eqd", n, ev)
    return r, r0, vel, axial_strain(d1, d10), _curvature(d1, d2)


def _hermite(xi: NDArray) -> tuple[NDArray, NDArray, NDArray]:
    """Cubic Hermite basis ``[H0, H1, H2, H3]`` and its derivatives, each ``(n_xi, 4)``."""
    x = xi
    h = np.stack(
        [1 - 3 * x**2 + 2 * x**3, x - 2 * x**2 + x**3, 3 * x**2 - 2 * x**3, x**3 - x**2], 1
    )
    h1 = np.stack([-6 * x + 6 * x**2, 1 - 4 * x + 3 * x**2, 6 * x - 6 * x**2, 3 * x**2 - 2 * x], 1)
    h2 = np.stack([-6 + 12 * x, -4 + 6 * x, 6 - 12 * x, 6 * x - 2], 1)
    return h, h1, h2


def _beam_fields(run: RunData, q: NDArray, v: NDArray, xi: NDArray) -> tuple[NDArray, ...]:
    nodes, vel_n = q.reshape(run.n_nodes, 3), v.reshape(run.n_nodes, 3)
    ref = run.reference.reshape(run.n_nodes, 3)
    x, x0, xd = nodes[:, :2], ref[:, :2], vel_n[:, :2]
    chord0 = x0[1:] - x0[:-1]
    if run.tangent_angles is not None:
        psi0 = run.tangent_angles
    else:  # chord directions averaged at interior nodes
        a = np.arctan2(chord0[:, 1], chord0[:, 0])
        psi0 = np.concatenate([[a[0]], 0.5 * (a[:-1] + a[1:]), [a[-1]]])
    h, h1, h2 = _hermite(xi)

    def curve(pos: NDArray, psi: NDArray) -> tuple[NDArray, NDArray, NDArray, NDArray]:
        d = pos[1:] - pos[:-1]
        length = np.linalg.norm(d, axis=1)
        t = np.stack([np.cos(psi), np.sin(psi)], axis=1)
        e = np.stack([pos[:-1], length[:, None] * t[:-1], pos[1:], length[:, None] * t[1:]], 1)
        return tuple(np.einsum("qk,ekd->eqd", b, e) for b in (h, h1, h2)) + (e,)  # type: ignore

    r, d1, d2, _ = curve(x, psi0 + nodes[:, 2])
    r0 = curve(x0, psi0)[0]
    # time derivative of the Hermite data: L' = d·d'/L, t' = ψ' (-sin ψ, cos ψ)
    psi = psi0 + nodes[:, 2]
    d, dd = x[1:] - x[:-1], xd[1:] - xd[:-1]
    length = np.linalg.norm(d, axis=1)
    ldot = np.sum(d * dd, axis=1) / length
    t = np.stack([np.cos(psi), np.sin(psi)], axis=1)
    tdot = vel_n[:, 2:3] * np.stack([-np.sin(psi), np.cos(psi)], axis=1)
    ev = np.stack(
        [
            xd[:-1],
            ldot[:, None] * t[:-1] + length[:, None] * tdot[:-1],
            xd[1:],
            ldot[:, None] * t[1:] + length[:, None] * tdot[1:],
        ],
        1,
    )
    vel = np.einsum("qk,ekd->eqd", h, ev)
    strain = np.repeat(axial_strain(d, chord0)[:, None], xi.size, axis=1)
    return r, r0, vel, strain, _curvature(d1, d2)


def sample_centerline(run: RunData, i: int, per_element: int = 16) -> Centerline:
    """The centreline of stored state ``i`` at ``per_element`` equal ξ-steps per element."""
    if isinstance(per_element, bool) or not isinstance(per_element, int) or per_element < 1:
        raise InputError("per_element", per_element, "an integer >= 1")
    xi = np.linspace(0.0, 1.0, per_element + 1)
    fields = _beam_fields if run.element == "beam" else _cable_fields
    r, r0, vel, strain, kappa = fields(run, run.q[i], run.v[i], xi)
    el = np.repeat(np.arange(r.shape[0])[:, None], xi.size, axis=1)
    r, r0 = _join(r), _join(r0)
    return Centerline(
        points=r,
        reference=r0,
        displacement=r - r0,
        velocity=_join(vel),
        axial_strain=_join(strain),
        curvature=_join(kappa),
        element=_join(el),
    )


@dataclass(frozen=True)
class NodalFrames:
    """A rod's nodes in one configuration with their material frames.

    Attributes
    ----------
    points, displacement, velocity : ndarray, shape (n_nodes, 3)
    tangent, m1, m2 : ndarray, shape (n_nodes, 3)
        Unit tangent and the two material axes of the cross-section (``m2 = t × m1``).
    twist : ndarray, shape (n_nodes,)
        The nodal twist coordinate ``φ`` [rad] (cumulative, as the ``twist`` sensor).
    """

    points: NDArray[np.float64]
    displacement: NDArray[np.float64]
    velocity: NDArray[np.float64]
    tangent: NDArray[np.float64]
    m1: NDArray[np.float64]
    m2: NDArray[np.float64]
    twist: NDArray[np.float64]


def nodal_frames(run: RunData, i: int) -> NodalFrames:
    """The nodes and material frames of stored state ``i`` of a rod run (the stored directors
    ``m1``; the tangent is the nodal gradient's direction)."""
    if run.element != "rod" or run.directors is None:
        raise InputError("RUN_DIR", str(run.path), "a run of rod elements (with stored directors)")
    nodes, ref = centerline_nodes(run, run.q[i]), centerline_nodes(run, run.reference)
    vel = centerline_nodes(run, run.v[i])
    t = nodes[:, 1] / np.linalg.norm(nodes[:, 1], axis=1, keepdims=True)
    m1 = np.asarray(run.directors[i], dtype=float)
    twist = np.asarray(run.q[i], dtype=float).reshape(run.n_nodes, -1)[:, 6]
    return NodalFrames(
        points=nodes[:, 0],
        displacement=nodes[:, 0] - ref[:, 0],
        velocity=vel[:, 0],
        tangent=t,
        m1=m1,
        m2=np.cross(t, m1),
        twist=twist,
    )
