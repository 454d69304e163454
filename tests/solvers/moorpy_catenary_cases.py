"""MoorPy's catenary test cases as rancf scenarios (shared by the tests and the benchmark).

Inputs and expected values are copied from MoorPy's ``tests/test_catenary.py`` (NREL/MoorPy,
``test_catenary_solutions``, ``test_catenary_symmetricU``, ``test_sloped_mirror``); the
expected values of the U, its half and the sloped pair (whose MoorPy test compares two runs
with each other) are MoorPy 1.3.0's ``catenary`` outputs of those inputs.  ``catenary(x, z, L,
EA, w, CB, alpha)``: the fairlead at ``(x, z)`` from the anchor; ``CB > 0`` the friction
coefficient of a seabed at the anchor's depth, ``CB < 0`` a seabed ``|CB|`` below the anchor;
``alpha`` the seabed's slope [deg]; ``w < 0`` buoyant.  MoorPy's forces are those of the line
on the anchor ``(fAH, fAV)`` and on the fairlead ``(fBH, fBV)``.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

#: Line diameter of every case [m] (MoorPy has none; it sets the seabed's default stiffness
#: k = w / (0.01 D) and the contact offset D / 2).
DIAMETER = 0.1
G = 9.81
#: Density of the seawater [kg/m³].
WATER = 1025.0
#: A line on the seabed with its default stiffness sinks in by this fraction of its diameter
#: (``rancf.system.seabed.SEABED_PENETRATION``): the plane is that much higher than a tube
#: touching it at the bed's depth, so that the resting line lies at MoorPy's seabed depth.
SINK = 0.01
#: Second moment of area of every case [m⁴]: with MoorPy's EA its ``EI`` is negligible for every
#: case but the U and its half (``EI = 127`` N m², a bending length ``sqrt(EI / H) = 0.7`` m at a
#: bend of radius ``H / w = 2.6`` m): their lines come to the heavy elastica's ``H`` 2 % below
#: MoorPy's (0.23 % of the fairlead tension, :func:`grounded_elastica`).  With 1e-14 or 1e-15 the
#: U's static solve fails at 40 to 160 elements (the sagged start's Newton and relaxation too)
#: where it converges to within 0.01 % of MoorPy at 160.
INERTIA = 1.0e-12


@dataclass(frozen=True)
class Case:
    """One MoorPy catenary input and its expected forces (anchor then fairlead, H and V)."""

    name: str
    x: float
    z: float
    length: float
    ea: float
    w: float
    cb: float
    alpha: float
    expected: tuple[float, float, float, float]


#: MoorPy's ``indata`` / ``desired`` (rows 0-9), then the U, its half and the sloped pair.
CASES = [
    Case(
        "seabed-cb5",
        400,
        200,
        500.0,
        7.51e12,
        800.0,
        5.0,
        0.0,
        (0.0, 0.0, -96643.43501616362, -237751.75997440016),
    ),
    Case(
        "seabed-cb0",
        400,
        200,
        500.0,
        7.51e12,
        800.0,
        0.0,
        0.0,
        (96643.42815934008, 0.0, -96643.42815934008, -237751.75535996316),
    ),
    Case(
        "seabed-cb0.1",
        400,
        200,
        500.0,
        7.51e12,
        800.0,
        0.1,
        0.0,
        (80418.60434855078, 0.0, -96643.42877136687, -237751.75577183915),
    ),
    Case(
        "hanging",
        400,
        200,
        500.0,
        7.51e12,
        200.0,
        -372.7,
        0.0,
        (43694.580989249596, -22365.599350216216, -43694.580989249596, -77634.40064978378),
    ),
    Case(
        "hanging-2",
        89.9,
        59.2,
        130.0,
        751000000.0,
        881.05,
        -372.7,
        0.0,
        (31373.229006023103, -26650.341270116318, -31373.229006023103, -87886.15872988368),
    ),
    Case(
        "buoyant",
        37.96888656874307,
        20.49078283711694,
        100.0,
        751000000.0,
        -881.0549577007893,
        -1245.2679469540894,
        0.0,
        (6428.437434537766, 53178.729367882406, -6428.437434537766, 34926.76640219652),
    ),
    Case(
        "near-taut-short",
        246.22420940032947,
        263.55766330843164,
        360.63566262396927 - 0.01,
        700e6,
        3.08735,
        0.0,
        0.0,
        (71116.8, 75567.3, -71116.8, -76680.6),
    ),
    Case(
        "near-taut",
        246.22420940032947,
        263.55766330843164,
        360.63566262396927,
        700e6,
        3.08735,
        0.0,
        0.0,
        (56804.6, 60803.4, -56804.6, -60803.4),
    ),
    Case(
        "near-taut-long",
        246.22420940032947,
        263.55766330843164,
        360.63566262396927 + 0.01,
        700e6,
        3.08735,
        0.0,
        0.0,
        (46077.1, 48765.2, -46077.1, -49878.6),
    ),
    Case(
        "taut-hard-start",
        119.3237383002058,
        52.49668849178113,
        130.36140355177318,
        700000000.0,
        34.91060469991227,
        0.0,
        0.0,
        (72694.145, 29715.173, -72694.145, -34266.168),
    ),
    Case(
        "u-shape",
        100.0,
        0.0,
        130.0,
        1e12,
        100.0,
        -20.0,
        0.0,
        (263.1956523855924, -2247.839540115996, -263.19565238559295, -2247.8405469474887),
    ),
    Case(
        "u-half",
        50.0,
        20.0,
        65.0,
        1e12,
        100.0,
        0.0,
        0.0,
        (263.19523344567386, 0.0, -263.19523344567386, -2247.8391673670126),
    ),
    Case(
        "sloped-up",
        60.0,
        40.0,
        80.0,
        1e12,
        100.0,
        0.0,
        10.0,
        (670.8401720597923, 118.2872220772503, -1309.865537260965, -4494.194286137271),
    ),
    Case(
        "sloped-down",
        60.0,
        -40.0,
        80.0,
        1e12,
        100.0,
        -(40 - 10.5796),
        -10.0,
        (1309.865537260965, -4494.194286137271, -670.8401720597923, 118.2872220772503),
    ),
]


def scenario_text(case: Case, elements: int) -> str:
    """The case as a 2D ``rancf static`` scenario: a cable (round section of DIAMETER,
    INERTIA) drawn straight from the anchor at the origin toward the fairlead with its
    unstretched length, its end pinned at the fairlead; the seabed (if any) a plane on which
    the resting line lies at the anchor's depth (``CB >= 0``) or ``|CB|`` below it
    (:data:`SINK`), sloped by ``alpha``, its friction ``CB`` in statics.  The line weighs
    ``|w|`` in air and is in seawater without hydrodynamic coefficients: its weight stays ``w``
    (MoorPy's wet weight) and the seabed's default stiffness is that of a seabed,
    ``w / (0.01 D)``; a buoyant line (``w < 0``) gets ``[hydro]`` coefficients whose
    diameter displaces water weighing ``2 |w|``, so that its wet weight is ``w``, as a user
    would give it."""
    area = math.pi * DIAMETER**2 / 4.0
    chord = math.hypot(case.x, case.z)
    ux, uz = case.x / chord, case.z / chord
    lines = [
        "[geometry]",
        'kind = "line"',
        "start = [0.0, 0.0]",
        f"end = [{case.length * ux!r}, {case.length * uz!r}]",
        "",
        "[mesh]",
        f"elements = {elements}",
        "",
        "[section]",
        f"area = {area!r}",
        f"inertia = {INERTIA!r}",
        "",
        "[material]",
        f"density = {abs(case.w) / (G * area)!r}",
        f"youngs_modulus = {case.ea / area!r}",
        'axial_strain = "engineering"',
        "",
        "[[supports]]",
        'at = "start"',
        'kind = "pin"',
        "",
        "[[supports]]",
        'at = "end"',
        'kind = "pin"',
        f"position = [{case.x!r}, {case.z!r}]",
        "",
        "[loads]",
        f"gravity = [0.0, {-G!r}]",
        "",
        "[fluid]",
        f"density = {WATER!r}",
        "",
    ]
    if case.w < 0.0:  # buoyancy of twice its weight: a hydrodynamic diameter displacing 2 |w|
        d = math.sqrt(8.0 * abs(case.w) / (math.pi * WATER * G))
        lines += ["[hydro]", f"diameter = {d!r}", ""]
    if case.cb is not None:
        depth = 0.0 if case.cb >= 0.0 else -case.cb
        a = math.radians(case.alpha)
        normal = (-math.sin(a), math.cos(a))
        r = DIAMETER / 2.0 - SINK * DIAMETER  # the resting line's centre at the bed's depth
        point = (-r * normal[0], -depth - r * normal[1])
        lines += [
            "[[obstacles]]",
            'name = "seabed"',
            'kind = "plane"',
            f"point = [{point[0]!r}, {point[1]!r}]",
            f"normal = [{normal[0]!r}, {normal[1]!r}]",
        ]
        if case.cb > 0.0:
            lines += [f"friction = {case.cb!r}", "", "[solver]", "static_friction = true"]
    return "\n".join(lines) + "\n"


def suspended_catenary(case: Case, guess: tuple[float, float]) -> tuple[float, float, float, float]:
    """The exact elastic catenary of a fully suspended line, engineering strain ``T = EA eps``
    (Irvine, *Cable Structures*, 1981, eqs. (2.13)-(2.14) between two points): the fairlead's
    ``(HF, VF)`` solving

        x = HF/w [asinh(VF/HF) - asinh((VF - wL)/HF)] + HF L / EA,
        z = HF/w [sqrt(1 + (VF/HF)²) - sqrt(1 + ((VF - wL)/HF)²)] + (VF L - w L²/2) / EA,

    from ``guess`` (Newton with a numerical Jacobian); returned as MoorPy's
    ``(fAH, fAV, fBH, fBV) = (HF, VF - wL, -HF, -VF)``."""
    import numpy as np
    from scipy.optimize import fsolve

    w, length, ea = case.w, case.length, case.ea

    def gap(hv: np.ndarray) -> list[float]:
        h, v = hv
        va = v - w * length
        x = h / w * (math.asinh(v / h) - math.asinh(va / h)) + h * length / ea
        z = h / w * (math.hypot(1.0, v / h) - math.hypot(1.0, va / h))
        z += (v * length - 0.5 * w * length**2) / ea
        return [(x - case.x) / case.length, (z - case.z) / case.length]

    (h, v), *_ = fsolve(gap, np.array(guess, dtype=float), xtol=1e-13, full_output=True)
    if max(abs(e) for e in gap(np.array([h, v]))) > 1e-12:
        raise ValueError(f"{case.name}: the catenary equations are not solved from {guess}")
    return h, v - w * length, -h, -v


def section_ei(case: Case) -> float:
    """The bending stiffness ``EI`` [N m²] the case's scenario gives the line
    (:func:`scenario_text`: ``inertia`` 1e-12 m⁴ with ``E = EA / A``)."""
    return case.ea / (math.pi * DIAMETER**2 / 4.0) * INERTIA


def grounded_elastica(case: Case, ei: float, nodes: int = 2001) -> tuple[float, float]:
    """The fairlead's ``(H, V)`` of a line lying on a rigid frictionless seabed at the anchor's
    depth (a case whose anchor is on the bed, as the U's half) and rising to the fairlead as an
    inextensible heavy elastica of bending stiffness ``ei`` (MoorPy's catenary is its
    ``EI = 0`` limit), pinned (no moment) at the fairlead.

    On the suspended length ``l`` (arc length ``s`` from the lift-off point, ``θ`` the slope,
    ``H`` the horizontal force, constant without friction, ``V(s) = V0 + w s`` the vertical
    one) the moment balance of the elastica, ``EI θ'' = H sin θ - V(s) cos θ``, with
    ``x' = cos θ``, ``z' = sin θ``; at the lift-off the line leaves the bed flat and straight
    (``z = θ = θ' = 0``, ``x = L - l``: the rest lies on the bed), at the fairlead ``x, z`` are
    the case's and ``θ' = 0``: seven conditions for the four states and ``(H, V0, l)``, solved
    by collocation (:func:`scipy.integrate.solve_bvp`) from the catenary ``a = H / w`` of the
    ``EI = 0`` limit.  Returns ``(H, V0 + w l)``."""
    import numpy as np
    from scipy.integrate import solve_bvp

    w, length = case.w, case.length
    a = case.expected[0] / w
    l0 = math.sqrt(case.z**2 + 2.0 * a * case.z)
    sig = np.linspace(0.0, 1.0, nodes)
    u = np.arcsinh(l0 * sig / a)
    guess = np.vstack(
        [
            length - l0 + a * u,
            a * (np.cosh(u) - 1.0),
            np.arctan(np.sinh(u)),
            1 / (a * np.cosh(u) ** 2),
        ]
    )

    def rates(t: np.ndarray, y: np.ndarray, p: np.ndarray) -> np.ndarray:
        h, v0, l = p
        c, s = np.cos(y[2]), np.sin(y[2])
        return l * np.vstack([c, s, y[3], (h * s - (v0 + w * l * t) * c) / ei])

    def ends(ya: np.ndarray, yb: np.ndarray, p: np.ndarray) -> np.ndarray:
        l = p[2]
        return np.array(
            [ya[0] - (length - l), ya[1], ya[2], ya[3], yb[0] - case.x, yb[1] - case.z, yb[3]]
        )

    sol = solve_bvp(rates, ends, sig, guess, p=[a * w, 0.0, l0], tol=1e-8, max_nodes=100000)
    if sol.status != 0:
        raise ValueError(f"{case.name}: the elastica is not solved ({sol.message})")
    h, v0, l = sol.p
    return float(h), float(v0 + w * l)
