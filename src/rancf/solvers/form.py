"""Form-finding: the unstretched length of a line that meets its ``[form]`` target in statics
(docs/derivations/form-finding.md).

For every flexible body with a ``[form]`` (:mod:`rancf.scenario.form`: ``sag``,
``horizontal_tension`` or ``end_tension``), :func:`find_form` solves the scalar equation
``m(L) = target``, ``m`` the measure of the static equilibrium (:func:`solve_static`) of the
scenario's system with the body's unstretched length ``L``
(:func:`~rancf.bodies.length.set_unstretched_length` on the body, the system built at that length):

* the sag: the largest vertical distance (against gravity) of the body's centre line below the
  chord between its end nodes, sampled at :data:`SAMPLES` points per element;
* the horizontal tension: the horizontal part of the axial force at the body's end node (its
  nodal forces: :func:`~rancf.bodies.nodal_forces.nodal_axial_forces`);
* the end tension: the axial force at the body's end node.

The start is the elastic catenary's length for the target between the body's installed end
positions (:func:`~rancf.solvers.catenary.catenary_length`: its weight ``ρ A |g|``, its ``EA``),
the second point the catenary's length for the target shifted by the first point's difference
between the body and its catenary; from there the secant method (a system built at every
length tried, so that every record of the body, its fluid loads too, has that length), kept
inside the bracket where one is known, until ``|m - target| <= RTOL target``.  Bodies with a
``[form]`` are found one after the other, in sweeps until all meet their targets.  The lengths
found are stored on the scenario
(:meth:`~rancf.scenario.scenario.Scenario.set_form_length`): every system built from it has
them.
"""

from __future__ import annotations

from typing import Any

import numpy as np
from numpy.typing import NDArray

from rancf.bodies.length import unstretched_length
from rancf.bodies.nodal_forces import nodal_axial_forces, recovers_axial_force
from rancf.errors import ConvergenceError, InputError, ScenarioError
from rancf.kernels.call_records import ResidualOptions, ResidualPoint
from rancf.solvers.catenary import Target, catenary, catenary_length
from rancf.system.seabed import wet_weight

__all__ = ["find_form", "form_lines", "form_summary", "line_measure", "RTOL", "SAMPLES"]

#: Relative tolerance of the target.
RTOL = 1e-8
#: Sample points per element of the sag.
SAMPLES = 32
#: Static solves per body and sweep at most; sweeps at most.
MAX_SOLVES, MAX_SWEEPS = 40, 8


def _up(model: Any) -> NDArray[np.float64]:
    g = np.asarray(model.gravity if model.gravity is not None else 0.0, dtype=float)
    norm = float(np.linalg.norm(g)) if g.ndim else 0.0
    if not norm > 0.0:
        raise InputError("form", "no gravity", "a body under [loads] gravity (its weight)")
    return -g / norm


def _ends(model: Any, y: NDArray) -> tuple[NDArray, NDArray]:
    q = model.q_from_y(y).reshape(model.n_nodes, model.dpn)
    return q[:, : model.dim], q[:, model.dim : 2 * model.dim]


def _span(model: Any, p1: NDArray, p2: NDArray) -> tuple[float, float, NDArray, NDArray]:
    """``(span, rise, horizontal unit, up)`` of the chord from ``p1`` to ``p2``."""
    up = _up(model)
    chord = p2 - p1
    rise = float(chord @ up)
    horiz = chord - rise * up
    span = float(np.linalg.norm(horiz))
    if not span > 1e-9 * float(np.linalg.norm(chord)):
        raise InputError("form", "a vertical chord", "a body whose ends are apart horizontally")
    return span, rise, horiz / span, up


def _sag(model: Any, y: NDArray) -> float:
    pos, _ = _ends(model, y)
    span, rise, ex, up = _span(model, pos[0], pos[-1])
    xi = np.linspace(0.0, 1.0, SAMPLES + 1)
    pts = model.mesh.evaluate(xi, model.q_from_y(y).reshape(model.n_nodes, -1)[:, : 2 * model.dim])
    d = pts.reshape(-1, model.dim) - pos[0]
    return float(np.max(rise * (d @ ex) / span - d @ up))


def _end_force(system: Any, name: str, y: NDArray, load_factor: float) -> tuple[float, float]:
    """The axial force at body ``name``'s end node and its horizontal part."""
    model = system.bodies[name]
    if not recovers_axial_force(model):
        raise InputError(
            "form", "C2 coordinates", 'a body of C1 coordinates (mesh.continuity = "C1")'
        )
    res0 = np.empty(system.n + system.m)
    system.core.residual(
        ResidualPoint(y, np.zeros(system.m), res0),
        ResidualOptions(0.0, load_factor, amplitude=True, dynamic=False, distributed_only=True),
    )
    sl = system.body_slice(name)
    axial = float(nodal_axial_forces(model, y[sl], res0[: system.n][sl])[-1])
    pos, grad = _ends(model, y[sl])
    _, _, ex, up = _span(model, pos[0], pos[-1])
    t = grad[-1] / np.linalg.norm(grad[-1])
    return axial, axial * float(np.linalg.norm(t - (t @ up) * up))


def line_measure(
    system: Any, name: str, kind: Target, y: NDArray, load_factor: float = 1.0
) -> float:
    """The sag, horizontal tension or end tension of body ``name`` of ``system`` at its static
    state ``y`` (module docstring)."""
    if kind == "sag":
        return _sag(system.bodies[name], y[system.body_slice(name)])
    axial, horizontal = _end_force(system, name, y, load_factor)
    return horizontal if kind == "horizontal_tension" else axial


class _Search:
    """The static solves of one body's form-finding on one system (module docstring)."""

    def __init__(self, sc: Any, system: Any, key: str, name: str, kind: Target, target: float):
        self.sc, self.system, self.key, self.name = sc, system, key, name
        self.kind, self.target = kind, target
        self.model = system.bodies[name]
        self.tried: list[tuple[float, float]] = []  # (L, m(L) - target)
        self.end_force: dict[float, float] = {}  # L -> the axial force at the end (a sag's)

    def error(self, exc: InputError) -> ScenarioError:
        """``exc`` (a problem of the target) naming the ``[form]`` key."""
        return ScenarioError(
            self.sc.path,
            f"{self.key}form.{self.kind}",
            f"needs {exc.allowed}, got {exc.value:g}"
            if isinstance(exc.value, float)
            else f"needs {exc.allowed}, got {exc.value}",
        )

    def _catenary_data(self) -> tuple[float, float, float]:
        """``(span, rise, w)`` of the body's catenary: its installed ends, its weight per
        length less the buoyancy of its ``[hydro]`` diameter in the ``[fluid]``."""
        m, s = self.model, self.system
        pos, _ = _ends(m, m.y_installed)
        span, rise, _, _ = _span(m, pos[0], pos[-1])
        wet = wet_weight(s, self.name)  # along gravity: the weight less the buoyancy
        g = np.r_[np.asarray(m.gravity, float), np.zeros(3 - len(m.gravity))]
        w = float(wet @ g / np.linalg.norm(g)) if g.any() else 0.0
        return span, rise, w

    def estimate(self, shift: float = 0.0) -> float:
        """The elastic catenary's length for ``target - shift`` between the installed ends
        (a body that touches an obstacle, where the catenary meets no such target: 1.02 times
        its reference length, the secant's start)."""
        key = f"{self.key}form.{self.kind}"
        try:
            span, rise, w = self._catenary_data()
            if not w > 0.0:
                raise InputError(key, "a buoyant line", "a line heavier than the fluid")
            ea = self.model.props.ea
            return catenary_length(self.kind, self.target - shift, span, rise, w, ea, key)
        except InputError as exc:
            if shift == 0.0 and self.touches and exc.parameter == key:
                return 1.02 * unstretched_length(self.model)
            raise self.error(exc) from None

    @property
    def touches(self) -> bool:
        """Whether the body is in contact with an obstacle (its catenary is no bound)."""
        return any(b == self.name for b, _ in getattr(self.system, "contact_pairs", ()))

    def catenary_measure(self, length: float) -> float:
        span, rise, w = self._catenary_data()
        return catenary(span, rise, length, w, self.model.props.ea).measure(self.kind)

    def residual(self, length: float) -> float:
        """``m(L) - target`` of the static equilibrium at the unstretched length ``L``."""
        from rancf.scenario.system_build import scenario_keys
        from rancf.solvers.static import solve_static

        self.sc.set_form_length(self.name, length)  # a system of its own: every record at L
        system = self.sc.build_system()
        with scenario_keys(self.sc):
            res = solve_static(system, **self.sc.static_options())
        try:
            value = line_measure(system, self.name, self.kind, res.y, res.load_factors[-1])
        except InputError as exc:
            raise self.error(exc) from None
        if self.kind == "sag" and recovers_axial_force(system.bodies[self.name]):
            force = _end_force(system, self.name, res.y, res.load_factors[-1])[0]
            self.end_force[length] = force
        self.tried.append((length, value - self.target))
        return value - self.target

    def check_tension(self, length: float) -> None:
        """Refuse a sag met by a body in compression at ``length`` (a section so stiff that it
        holds the sag up as a buckled beam: no line is strung so; often a radius or area in
        millimetres), naming the ``[form]`` key."""
        force = self.end_force.get(length)
        if force is None or force >= 0.0:
            return
        ei = self.model.props.ei
        raise ScenarioError(
            self.sc.path,
            f"{self.key}form.sag",
            f"needs a line in tension, got {self.target:g}: the length that meets it "
            f"({length:.6g} m) is in compression (end axial force {force:.4g} N), a beam "
            f"pushed into its span (EI = {ei:.3g} N m^2); check the units of section.radius "
            "or section.area (metres)",
        )

    def solve(self) -> float:
        """The length meeting the target (module docstring).

        Raises
        ------
        ConvergenceError
            The secant iteration finds none within :data:`MAX_SOLVES` static solves.
        """
        tol = RTOL * self.target
        l0 = self.estimate()
        g0 = self.residual(l0)
        if abs(g0) <= tol:
            return l0
        try:  # the catenary's length for the target less the body's offset from it
            l1 = self.estimate(g0 + self.target - self.catenary_measure(l0))
        except (ScenarioError, ConvergenceError):  # no catenary meets the shifted target
            l1 = l0 * (1.0 + 1e-3)
        if not abs(l1 - l0) > 1e-12 * l0:
            l1 = l0 * (1.0 + 1e-6)
        pts = [(l0, g0), (l1, self.residual(l1))]
        for _ in range(MAX_SOLVES):
            (la, ga), (lb, gb) = pts[-2], pts[-1]
            if abs(gb) <= tol or abs(lb - la) <= 1e-13 * lb:
                return lb
            step = -gb * (lb - la) / (gb - ga) if gb != ga else 1e-6 * lb
            length = lb + max(min(step, 0.25 * lb), -0.25 * lb)
            lo, hi = _bracket(self.tried)
            if lo is not None and hi is not None and not min(lo, hi) < length < max(lo, hi):
                length = 0.5 * (lo + hi)
            pts.append((length, self.residual(length)))
        best = min(self.tried, key=lambda p: abs(p[1]))
        raise ConvergenceError(
            f"form-finding of {self.name!r}: no unstretched length meets {self.kind} = "
            f"{self.target:g} within {MAX_SOLVES} static solves (the closest: {best[0]:.9g} m, "
            f"off by {best[1]:.3g})"
        )


def _bracket(tried: list[tuple[float, float]]) -> tuple[float | None, float | None]:
    """The nearest lengths on either side of the root among ``tried`` (None: none there)."""
    neg = [p for p in tried if p[1] < 0.0]
    pos = [p for p in tried if p[1] > 0.0]
    if not neg or not pos:
        return None, None
    a = min(neg, key=lambda p: -p[1])
    b = min(pos, key=lambda p: p[1])
    return a[0], b[0]


def find_form(sc: Any) -> None:
    """Find the unstretched length of every body of scenario ``sc`` with a ``[form]`` (module
    docstring) and store it on ``sc``; nothing to do when there is none or all are found.

    Raises
    ------
    ScenarioError
        A target no length meets (one line naming the key, the value and what is allowed).
    ConvergenceError
        The static solve or the secant iteration fails.
    """
    todo = [(k, n, f) for k, n, f in sc.forms() if sc.form_length(n) is None]
    if not todo:
        return
    with sc.form_search():
        system = sc.build_system()
    searches = [_Search(sc, system, k, n, *f.target) for k, n, f in todo]
    try:
        for s in searches:  # every body at its catenary's length while the others are found
            sc.set_form_length(s.name, s.estimate())
        _sweeps(sc, searches)
    except BaseException:
        for s in searches:
            sc.set_form_length(s.name, None)
        raise


def _sweeps(sc: Any, searches: list[_Search]) -> None:
    """Each body's length found with the others' held, in sweeps until all meet their
    targets together (one sweep for one body)."""
    for _ in range(MAX_SWEEPS):
        for s in searches:
            length = s.solve()
            s.check_tension(length)
            sc.set_form_length(s.name, length)
        if len(searches) == 1 or all(
            abs(s.residual(sc.form_length(s.name))) <= RTOL * s.target for s in searches
        ):
            return
    raise ConvergenceError("form-finding: the bodies' targets were not met together")


def form_summary(sc: Any) -> dict[str, Any]:
    """``{"unstretched_length": L}`` of the body with a ``[form]`` (several: ``{body: L}``),
    found; empty without one."""
    found = {n: sc.form_length(n) for _, n, _ in sc.forms()}
    if not found or any(v is None for v in found.values()):
        return {}
    return {"unstretched_length": next(iter(found.values())) if len(found) == 1 else found}


def form_lines(sc: Any) -> list[str]:
    """One line per body with a ``[form]``: the length found and its target."""
    out = []
    for _, n, f in sc.forms():
        length = sc.form_length(n)
        if length is not None:
            kind, value = f.target
            unit = "m" if kind == "sag" else "N"
            out.append(
                f"body {n!r}: unstretched length {length:.9g} m (form: {kind} = {value:g} {unit})"
            )
    return out
