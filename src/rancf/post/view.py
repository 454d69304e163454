"""A run as one self-contained, interactive HTML page (``rancf view``): a 3D view of the bodies,
the obstacles and the contact forces, with play, pause and a time slider.

Drawn with Plotly (its JavaScript library is written into the page, so it works offline):

* every body as :meth:`~rancf.post.system_run.SystemRun.shapes` draws it (a flexible body's exact
  element curve sampled ``per_element`` times per element; a rigid body's polyline through its
  points; a point mass a dot), in the colours of :data:`BODY_COLORS`;
* every obstacle of the run's metadata (:func:`rancf.system.contact.obstacle_records`): a plane
  as a square (a segment in 2D) about the point of it nearest the bodies' centre, a cylinder as
  a circle in 2D and a tube in 3D, a sphere as its surface; an obstacle carried by a rigid body
  moves with it;
* the contact force of every obstacle (normal plus friction: the force the obstacle exerts on
  the bodies, the ``reactions`` of :mod:`rancf.system.outputs`) as an arrow from the plane's
  drawn centre or the obstacle's centre, the largest force over the run a quarter of the scene
  long.

At most ``frames`` stored times are drawn (evenly spaced; the first and the last always), which
keeps the page small: the plotting library is about 5 MB and every frame adds the bodies'
points.  A planar run is drawn in the plane ``z = 0``, seen from ``+z``.
"""

from __future__ import annotations

import json
from pathlib import Path
from typing import Any

import numpy as np
from numpy.typing import NDArray

from rancf.atomic import atomic_write
from rancf.errors import InputError
from rancf.post.system_run import SystemRun
from rancf.post.view_options import DEFAULT_FRAMES

__all__ = ["write_view", "view_figure", "view_frames", "BODY_COLORS", "DEFAULT_FRAMES"]

#: Colours of the bodies, in the run's body order (repeated past the tenth body).
BODY_COLORS = (
    "#d62728",
    "#1f77b4",
    "#2ca02c",
    "#9467bd",
    "#ff7f0e",
    "#8c564b",
    "#e377c2",
    "#17becf",
    "#bcbd22",
    "#7f7f7f",
)
OBSTACLE_COLOR = "#999999"
FORCE_COLOR = "#000000"


def view_frames(n_t: int, frames: int) -> NDArray[np.int64]:
    """Indices of at most ``frames`` evenly spaced stored times of ``n_t`` (first and last
    included)."""
    if not (isinstance(frames, int) and frames >= 1):
        raise InputError("--frames", frames, "an integer >= 1")
    return np.unique(np.linspace(0, n_t - 1, min(frames, n_t)).round().astype(np.int64))


def _contact(run: SystemRun) -> tuple[list[dict[str, Any]], NDArray, list[str]]:
    """The run's obstacles, its ``reactions (n_t, k)`` and their column names (only these
    arrays of ``results.npz`` are read)."""
    with np.load(run.path / "results.npz", allow_pickle=False) as z:
        meta = json.loads(str(z["metadata"]))
        obstacles = meta.get("obstacles") or []
        if not obstacles:
            return [], np.zeros((run.t.size, 0)), []
        return (
            obstacles,
            np.asarray(z["reactions"]).reshape(run.t.size, -1),
            list(meta["reaction_columns"]),
        )


def _circle(center: NDArray, axis: NDArray, radius: float, n: int = 73) -> NDArray:
    """Points ``(n, 3)`` of the circle about ``axis`` (unit) through ``center``."""
    u = np.cross(axis, [1.0, 0.0, 0.0] if abs(axis[0]) < 0.9 else [0.0, 1.0, 0.0])
    u /= np.linalg.norm(u)
    v = np.cross(axis, u)
    th = np.linspace(0.0, 2.0 * np.pi, n)
    return center + radius * (np.cos(th)[:, None] * u + np.sin(th)[:, None] * v)


def _obstacle_mesh(
    ob: dict[str, Any], dim: int, size: float, centre: NDArray, x: NDArray, axes: NDArray
) -> dict[str, Any]:
    """An obstacle's drawing at a carrying frame ``x + p @ axes`` (module docstring): ``line``
    points ``(k, 3)`` (2D) or a surface ``(x, y, z)`` grid (3D)."""
    p = x + np.asarray(ob["point"], float) @ axes
    d = np.asarray(ob["direction"], float) @ axes
    r = float(ob["radius"])
    if ob["kind"] == "plane":
        foot = centre - np.dot(centre - p, d) * d  # the plane's point nearest the bodies
        if dim == 2:
            t = np.array([-d[1], d[0], 0.0])
            return {"line": foot + np.outer([-size, size], t), "anchor": foot}
        u = np.cross(d, [1.0, 0.0, 0.0] if abs(d[0]) < 0.9 else [0.0, 1.0, 0.0])
        u /= np.linalg.norm(u)
        v = np.cross(d, u)
        a, b = np.meshgrid([-size, size], [-size, size])
        grid = foot + a[..., None] * u + b[..., None] * v
        return {"surface": grid, "anchor": foot}
    if ob["kind"] == "cylinder" and dim == 2:
        return {"line": _circle(p, np.array([0.0, 0.0, 1.0]), r), "anchor": p}
    if ob["kind"] == "cylinder":  # a tube as long as the scene is wide (at least a radius)
        ring = _circle(np.zeros(3), d, r, 37) / r  # unit radial directions
        along = max(r, 0.5 * size) * np.array([-1.0, 1.0])
        grid = p + r * ring[None, :, :] + along[:, None, None] * d
        return {"surface": grid, "anchor": p}
    ph, th = np.meshgrid(np.linspace(0, np.pi, 19), np.linspace(0, 2 * np.pi, 37))
    unit = np.stack([np.sin(ph) * np.cos(th), np.sin(ph) * np.sin(th), np.cos(ph)], axis=-1)
    return {"surface": p + r * unit, "anchor": p}


class _Scene:
    """Everything drawn at the chosen times (module docstring)."""

    def __init__(self, run: SystemRun, idx: NDArray[np.int64], per_element: int) -> None:
        self.run, self.idx = run, idx
        self.bodies = [run.shapes(int(i), per_element=per_element) for i in idx]
        allp = np.concatenate([p for f in self.bodies for _, p in f])
        self.lo, self.hi = allp.min(axis=0), allp.max(axis=0)
        self.centre = 0.5 * (self.lo + self.hi)
        self.size = 0.5 * max(float(np.max(self.hi - self.lo)), 1e-9)
        self.obstacles, reactions, columns = _contact(run)
        d = run.dim
        self.forces = np.zeros((idx.size, len(self.obstacles), 3))
        for k, ob in enumerate(self.obstacles):
            for part in ("normal", "friction"):
                cols = [columns.index(f"{ob['name']}_{part}_{a}") for a in "xyz"[:d]]
                self.forces[:, k, :d] += reactions[idx][:, cols]
        kinds = {b["name"]: b for b in run.bodies}
        self.drawn = []  # per frame: per obstacle its drawing
        for i in idx:
            row = []
            for ob in self.obstacles:
                x, axes = np.zeros(3), np.eye(3)
                if ob["body"] is not None:
                    x, axes = run.rigid_frame(kinds[ob["body"]], int(i))
                row.append(_obstacle_mesh(ob, d, self.size, self.centre, x, axes))
            self.drawn.append(row)

    def traces(self, f: int) -> list[Any]:
        """The traces of frame ``f``: bodies, obstacles, force arrows (the same order always)."""
        import plotly.graph_objects as go

        out: list[Any] = []
        for k, (name, pts) in enumerate(self.bodies[f]):
            color = BODY_COLORS[k % len(BODY_COLORS)]
            mode = "markers" if len(pts) == 1 else "lines+markers" if len(pts) < 8 else "lines"
            pts = pts.astype(np.float32)  # a screen's precision, half the page's size
            out.append(
                go.Scatter3d(
                    x=pts[:, 0],
                    y=pts[:, 1],
                    z=pts[:, 2],
                    mode=mode,
                    name=name,
                    line={"color": color, "width": 8},
                    marker={"color": color, "size": 4},
                )
            )
        for ob, dr in zip(self.obstacles, self.drawn[f], strict=True):
            if "line" in dr:
                q = dr["line"]
                out.append(
                    go.Scatter3d(
                        x=q[:, 0],
                        y=q[:, 1],
                        z=q[:, 2],
                        mode="lines",
                        name=ob["name"],
                        line={"color": OBSTACLE_COLOR, "width": 5},
                    )
                )
            else:
                g = dr["surface"]
                grey = [[0, OBSTACLE_COLOR], [1, OBSTACLE_COLOR]]
                out.append(
                    go.Surface(
                        x=g[..., 0],
                        y=g[..., 1],
                        z=g[..., 2],
                        name=ob["name"],
                        showscale=False,
                        showlegend=True,
                        opacity=0.4,
                        colorscale=grey,
                    )
                )
        top = float(np.max(np.linalg.norm(self.forces, axis=-1), initial=0.0))
        scale = 0.5 * self.size / top if top > 0 else 0.0
        for k, (ob, dr) in enumerate(zip(self.obstacles, self.drawn[f], strict=True)):
            a = dr["anchor"]
            b = a + scale * self.forces[f, k]
            text = f"{ob['name']}: {np.linalg.norm(self.forces[f, k]):.4g} N"
            out.append(
                go.Scatter3d(
                    x=[a[0], b[0]],
                    y=[a[1], b[1]],
                    z=[a[2], b[2]],
                    mode="lines+markers",
                    name=f"force on {ob['name']}",
                    hovertext=[text, text],
                    hoverinfo="text",
                    line={"color": FORCE_COLOR, "width": 6},
                    marker={"size": [0, 5], "color": FORCE_COLOR, "symbol": "diamond"},
                )
            )
        return out


def _layout(run: SystemRun, scene: _Scene, labels: list[str]) -> dict[str, Any]:
    pad = 0.6 * scene.size
    lo, hi = scene.lo - pad, scene.hi + pad
    axes: dict[str, dict[str, Any]] = {
        f"{a}axis": {"range": [float(lo[k]), float(hi[k])], "title": f"{a} [m]"}
        for k, a in enumerate("xyz")
    }
    if run.dim == 2:
        lo[2], hi[2] = -0.1 * scene.size, 0.1 * scene.size
        axes["zaxis"] = {"range": [float(lo[2]), float(hi[2])], "visible": False}
    span = 1.8 * (hi - lo) / float(np.max(hi - lo))  # equal scales, the widest fills the view
    ratio = {a: float(span[k]) for k, a in enumerate("xyz")}
    camera = (
        {
            "eye": {"x": 0.0, "y": 0.0, "z": 1.0},
            "up": {"x": 0.0, "y": 1.0, "z": 0.0},
            "projection": {"type": "orthographic"},
        }
        if run.dim == 2
        else {"eye": {"x": 1.4, "y": -1.4, "z": 1.0}}
    )
    play = {
        "frame": {"duration": 50, "redraw": True},
        "fromcurrent": True,
        "transition": {"duration": 0},
    }
    pause = {"frame": {"duration": 0, "redraw": False}, "mode": "immediate"}
    steps = [
        {
            "label": lab,
            "method": "animate",
            "args": [[lab], {"mode": "immediate", "frame": {"duration": 0, "redraw": True}}],
        }
        for lab in labels
    ]
    return {
        "title": f"{run.name}: {len(labels)} of {run.t.size} stored times",
        "scene": {
            **axes,
            "aspectmode": "manual",
            "aspectratio": ratio,
            "camera": camera,
            "domain": {"x": [0.0, 1.0], "y": [0.14, 1.0]},
        },  # the controls below it
        "margin": {"l": 0, "r": 0, "t": 40, "b": 0},
        "updatemenus": [
            {
                "type": "buttons",
                "showactive": False,
                "x": 0.02,
                "y": 0.02,
                "xanchor": "left",
                "yanchor": "bottom",
                "direction": "left",
                "buttons": [
                    {"label": "Play", "method": "animate", "args": [None, play]},
                    {"label": "Pause", "method": "animate", "args": [[None], pause]},
                ],
            }
        ],
        "sliders": [
            {
                "active": 0,
                "x": 0.2,
                "len": 0.78,
                "y": 0.02,
                "yanchor": "bottom",
                "currentvalue": {"prefix": ""},
                "steps": steps,
            }
        ],
    }


def view_figure(run: SystemRun, frames: int = DEFAULT_FRAMES, per_element: int = 8) -> Any:
    """The Plotly figure of ``run`` (module docstring): its traces at the first drawn time, one
    animation frame per drawn time (named by its time, ``t = 0.5 s``) and the controls."""
    import plotly.graph_objects as go

    if not (isinstance(per_element, int) and per_element >= 1):
        raise InputError("--samples", per_element, "an integer >= 1")
    idx = view_frames(run.t.size, frames)
    scene = _Scene(run, idx, per_element)
    labels = [run.time_text(float(run.t[i])) for i in idx]
    return go.Figure(
        data=scene.traces(0),
        frames=[go.Frame(data=scene.traces(f), name=lab) for f, lab in enumerate(labels)],
        layout=_layout(run, scene, labels),
    )


def write_view(
    run: SystemRun, path: str | Path, frames: int = DEFAULT_FRAMES, per_element: int = 8
) -> int:
    """Write the page of ``run`` to ``path`` (atomically; the plotting library inlined);
    returns the number of drawn times."""
    figure = view_figure(run, frames, per_element)
    atomic_write(path, figure.to_html(include_plotlyjs=True, full_html=True, auto_play=False))
    return len(figure.frames)
