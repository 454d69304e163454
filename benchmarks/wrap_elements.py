"""How many elements a frictional wrap needs: an Atwood machine on a turning pulley.

    python benchmarks/wrap_elements.py [--t-end 0.6]

A weightless rope (radius 2 mm, E = 10 GPa) over a pulley (a disc of 2 kg, radius 0.2 m,
pinned to the ground, friction 0.5: the rope sticks) carries 1.2 kg and 1 kg.  The masses
accelerate at a = (m1 - m2) g / (m1 + m2 + J / R_c^2 + m_rope).  The half turn of the wrap is
``n_arc`` exact-arc elements (the spans 12 elements of 25 mm); over the run the rope moves about
0.11 m over the pulley, so elements pass from the spans onto the wrap and off it.  The table is
the acceleration fitted after 0.05 s against the formula, per element angle on the wrap: the
numbers behind the wrap warning of ``rancf.post.contact_checks`` (docs/guide/contact.md).
"""

from __future__ import annotations

import argparse

import numpy as np

from rancf.bodies.flexible import Material, Model, Section
from rancf.bodies.rigid import PointMass, RigidBody
from rancf.mesh.routes import rope_over_pulley
from rancf.solvers.dynamic import DynamicOptions, integrate
from rancf.system import Joint, Obstacle, System

RP, RT, SPAN, G = 0.2, 0.002, 0.3, 9.81
RC = RP + RT
SECTION = Section(np.pi * RT**2, 1e-3 * np.pi * RT**4 / 4)


def atwood(n_arc: int, t_end: float, n_span: int = 12) -> tuple[float, float]:
    """(fitted acceleration, the formula's) of the machine with ``n_arc`` elements on the wrap."""
    mesh = rope_over_pulley(RC, SPAN, n_arc, n_span)
    rope = Model(mesh, "rancf", SECTION, Material(100.0, 1e10), gravity=(0.0, 0.0))
    j = 0.5 * 2.0 * RP**2
    bodies = {
        "rope": rope,
        "heavy": PointMass(2, 1.2, (-RC, -SPAN)),
        "light": PointMass(2, 1.0, (RC, -SPAN)),
        "pulley": RigidBody(2, 2.0, j, (0.0, 0.0), 0.0),
    }
    joints = [
        Joint("pin", ("rope:start", "heavy")),
        Joint("pin", ("rope:end", "light")),
        Joint("pin", ("pulley", "ground")),
    ]
    wheel = Obstacle("cylinder", center=(0, 0), radius=RP, friction=0.5, body="pulley")
    s = System(bodies, joints, gravity=[0, -G], obstacles=[wheel])
    opts = DynamicOptions(t_end=t_end, step=1e-3, rho_inf=0.5, max_newton=25, output_step=0.01)
    res = integrate(s, opts)
    m_rope = 100.0 * SECTION.area * rope.mesh.arc_lengths().sum()
    late = res.t >= 0.05
    v = -res.v[late][:, s.body_slice("heavy")][:, 1]
    return float(np.polyfit(res.t[late], v, 1)[0]), (1.2 - 1.0) * G / (
        1.2 + 1.0 + j / RC**2 + m_rope
    )


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--t-end", type=float, default=0.6)
    args = ap.parse_args()
    print("elements on the wrap  angle each  acceleration  formula  low by")
    for n in (4, 6, 8, 12, 16, 32):
        a, exact = atwood(n, args.t_end)
        print(f"{n:20d}  {180 / n:9.3g}°  {a:12.6f}  {exact:7.5f}  {100 * (1 - a / exact):5.2f} %")


if __name__ == "__main__":
    main()
