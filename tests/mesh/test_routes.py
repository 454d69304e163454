"""The rope over a pulley (:func:`rancf.mesh.routes.rope_over_pulley`): exact geometry, tested to
round-off: the arc elements lie on the circle, the spans on their vertical lines, the tangent is
continuous and the length is two spans plus the half turn."""

from __future__ import annotations

import numpy as np
import pytest

from rancf.errors import InputError
from rancf.mesh.routes import rope_over_pulley

R, SPAN, CENTER = 0.202, 0.3, np.array([0.5, -1.0])


def test_the_route_is_exact_to_round_off():
    n_arc, n_span = 7, 3
    mesh = rope_over_pulley(R, SPAN, n_arc, n_span, CENTER)
    assert mesh.n_elements == n_arc + 2 * n_span
    xi = np.linspace(0.0, 1.0, 11)
    p = mesh.evaluate(xi)
    arcs = p[n_span : n_span + n_arc] - CENTER
    assert np.abs(np.linalg.norm(arcs, axis=-1) / R - 1.0).max() <= 1e-12
    assert np.all(arcs[..., 1] >= -1e-12 * R)  # the top half
    left, right = p[:n_span], p[n_span + n_arc :]
    assert np.abs(left[..., 0] - (CENTER[0] - R)).max() <= 1e-12
    assert np.abs(right[..., 0] - (CENTER[0] + R)).max() <= 1e-12
    d = mesh.evaluate([0.0, 1.0], order=1)
    t0, t1 = d[1:, 0], d[:-1, 1]  # tangents meeting at the inner nodes
    unit = t0 / np.linalg.norm(t0, axis=1)[:, None] - t1 / np.linalg.norm(t1, axis=1)[:, None]
    assert np.abs(unit).max() <= 1e-12
    assert mesh.arc_lengths().sum() == pytest.approx(2 * SPAN + np.pi * R, rel=1e-12)


@pytest.mark.parametrize(
    ("key", "args"), [("radius", (0.0, SPAN, 4, 2)), ("span", (R, -1.0, 4, 2))]
)
def test_bad_lengths_are_refused(key, args):
    with pytest.raises(InputError) as err:
        rope_over_pulley(*args)
    assert key in str(err.value)
