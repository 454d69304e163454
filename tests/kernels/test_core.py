"""The compiled core as a black box: band LU, Newton variants, input checks, a clean build."""

import os
import shutil
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

from rancf.bodies.flexible import Material, Model, PointLoad, Section, Support
from rancf.geometry.conic import conic_arc
from rancf.kernels import _core
from rancf.mesh.factories import mesh_conic, mesh_line
from rancf.solvers.dynamic import DynamicOptions, GeneralizedAlpha, integrate
from tests.conftest import EXAMPLE1

ROOT = Path(__file__).resolve().parents[2]


def _band(a: np.ndarray, ku: int) -> np.ndarray:
    n = a.shape[0]
    ab = np.zeros((2 * ku + 1, n))
    for i in range(n):
        for j in range(max(0, i - ku), min(n, i + ku + 1)):
            ab[ku + i - j, j] = a[i, j]
    return ab


@pytest.mark.parametrize("seed", range(5))
def test_band_solve_pivots_and_holds_fixed_entries(seed):
    rng = np.random.default_rng(seed)
    n, ku = 40, 5
    a = rng.normal(size=(n, n))
    a[np.abs(np.subtract.outer(np.arange(n), np.arange(n))) > ku] = 0.0
    a[np.arange(n), np.arange(n)] = 0.0  # zero diagonal: fails without row pivoting
    fixed = np.zeros(n, dtype=np.uint8)
    fixed[[0, 7, n - 1]] = 1
    rhs = rng.normal(size=n)
    x = rhs.copy()
    assert _core.band_solve(_band(a, ku), x, fixed)
    free = fixed == 0
    ref = np.zeros(n)
    ref[free] = np.linalg.solve(a[np.ix_(free, free)], rhs[free])
    assert np.abs(x - ref).max() <= 1e-11 * np.abs(ref).max()


@pytest.mark.parametrize("ku", [3, 7, 11, 13])
@pytest.mark.parametrize("shift", [4.0, -1.5, 0.0])
def test_band_solve_symmetric_definite_and_indefinite(ku, shift):
    # symmetric band matrices take the L D L^T path while their pivots are positive (shift 4:
    # positive definite) and go to the pivoted LU at the first that is not (-1.5: indefinite;
    # 0: a zero diagonal, where L D L^T fails at once); the answer is the same either way
    rng = np.random.default_rng(ku)
    n = 60
    b = rng.normal(size=(n, n))
    a = 0.5 * (b + b.T)
    a[np.abs(np.subtract.outer(np.arange(n), np.arange(n))) > ku] = 0.0
    a[np.arange(n), np.arange(n)] = 0.0
    a += shift * np.eye(n) * (np.abs(a).sum(axis=1).max() if shift > 0 else 1.0)
    fixed = np.zeros(n, dtype=np.uint8)
    fixed[[0, 1, 30]] = 1
    rhs = rng.normal(size=n)
    x = rhs.copy()
    assert _core.band_solve(_band(a, ku), x, fixed)
    free = fixed == 0
    ref = np.zeros(n)
    ref[free] = np.linalg.solve(a[np.ix_(free, free)], rhs[free])
    assert np.abs(x - ref).max() <= 1e-10 * np.abs(ref).max()
    assert np.all(x[fixed == 1] == 0.0)


def _split_case(kind: str, ku: int) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    rng = np.random.default_rng(ku)
    n = _core.band_split_from(ku) + 17
    b = rng.normal(size=(n, n))
    a = 0.5 * (b + b.T) if kind != "dynamic" else b
    a[np.abs(np.subtract.outer(np.arange(n), np.arange(n))) > ku] = 0.0
    # spd: diagonally dominant; dynamic: unsymmetric with a strong diagonal (a step's
    # Jacobian); indefinite: symmetric, its L D L^T fails, its LU pivots
    a += {"spd": 4.0 * ku, "dynamic": 3.0 * np.sqrt(ku), "indefinite": -1.5}[kind] * np.eye(n)
    fixed = np.zeros(n, dtype=np.uint8)
    fixed[[0, 1, n // 2, n // 2 + 1, n - 1]] = 1  # the separator's rows among them
    return a, fixed, rng.normal(size=n)


@pytest.mark.parametrize("ku", [3, 7, 11, 13])
@pytest.mark.parametrize(
    ("kind", "path"),
    [("spd", "split ldl"), ("dynamic", "split lu"), ("indefinite", "split lu")],
)
def test_a_large_band_is_split_and_solved_to_round_off(ku, kind, path):
    # two halves and a separator (linalg/band.hpp): the solution of the dense solver and of
    # the band factored as one to round-off, the same bit for bit on two threads
    a, fixed, rhs = _split_case(kind, ku)
    ab = _band(a, ku)
    assert _core.band_factorization(ab, fixed) == path
    assert _core.band_factorization(ab, fixed, split=False) == path.removeprefix("split ")
    free = fixed == 0
    ref = np.zeros(a.shape[0])
    ref[free] = np.linalg.solve(a[np.ix_(free, free)], rhs[free])
    x, one = rhs.copy(), rhs.copy()
    assert _core.band_solve(ab, x, fixed) and _core.band_solve(ab, one, fixed, split=False)
    assert np.abs(x - ref).max() <= 1e-13 * np.abs(ref).max()
    assert np.abs(x - one).max() <= 1e-13 * np.abs(ref).max()
    assert np.all(x[fixed == 1] == 0.0)
    before = _core.assembly_threads()
    _core.set_assembly_threads(2)
    try:
        two = rhs.copy()
        assert _core.band_solve(ab, two, fixed)
    finally:
        _core.set_assembly_threads(before)
    assert np.array_equal(x, two)


def test_a_split_band_without_good_pivots_in_a_half_is_factored_as_one():
    # the separator's first row outweighs every candidate of the top half's last pivot (its
    # own rows): that half would take a pivot under a tenth of the column's largest entry
    ku = 3
    n = _core.band_split_from(ku)
    rng = np.random.default_rng(1)
    a = rng.normal(size=(n, n))
    a[np.abs(np.subtract.outer(np.arange(n), np.arange(n))) > ku] = 0.0
    a += 3.0 * np.eye(n)
    m = (n - ku) // 2
    a[m, m - 1] = 1e3
    ab = _band(a, ku)
    fixed = np.zeros(n, dtype=np.uint8)
    assert _core.band_factorization(ab, fixed) == "lu"
    rhs = rng.normal(size=n)
    x = rhs.copy()
    assert _core.band_solve(ab, x, fixed)
    assert np.abs(x - np.linalg.solve(a, rhs)).max() <= 1e-12 * np.abs(x).max()


def test_band_solve_reports_a_singular_matrix():
    ab = _band(np.zeros((6, 6)), 1)
    assert not _core.band_solve(ab, np.ones(6), np.zeros(6, dtype=np.uint8))


def _pendulum(n_el=8, **kw):
    return Model(
        mesh_line([0, 0], [1.2, 0], n_el),
        "ancf",
        Section(0.0018, 1.215e-8),
        Material(5540.0, 0.7e6),
        [Support(0, "pin")],
        gravity=[0, -9.81],
        **kw,
    )


def test_chord_newton_is_full_newton_to_far_below_the_tolerance():
    # chord (the default): one exact tangent a step, the step's further iterations on its
    # factors; the soft pendulum's 20 % strain makes the tangent change within a step
    m = _pendulum()
    base = dict(t_end=0.3, step=1e-3, output_step=0.05)
    full = integrate(m, DynamicOptions(newton="full", **base))
    chord = integrate(m, DynamicOptions(**base))
    assert DynamicOptions(**base).newton == "chord"
    assert full.n_factorizations == full.n_newton + 1  # the mass matrix's at t = 0
    assert chord.n_factorizations < 0.75 * full.n_factorizations
    assert chord.n_factorizations >= chord.n_steps
    assert chord.n_rejected == full.n_rejected == 0
    tol = 1e-10 * 1.2  # newton_tol times the model size
    assert np.abs(chord.q - full.q).max() < 2e-3 * tol


def test_modified_newton_gives_the_same_answer():
    m = _pendulum()
    base = dict(t_end=0.3, step=1e-3, output_step=0.05)
    full = integrate(m, DynamicOptions(newton="full", **base))
    mod = integrate(m, DynamicOptions(newton="modified", **base))
    assert mod.n_factorizations < 0.1 * full.n_factorizations
    assert mod.n_rejected == 0
    assert np.abs(mod.q - full.q).max() < 3e-8  # measured 1.6e-8 (20 % strain amplifies)


def test_fixed_step_loop_equals_single_steps():
    """The core's loop and step-by-step stepping (the adaptive path's primitive) agree."""
    m = Model(
        mesh_conic(conic_arc(*EXAMPLE1), 4),
        "rancf",
        Section.circular(0.02),
        Material(6000.0, 2e6),
        [Support(0, "clamp")],
        gravity=[0, -9.81],
        point_loads=[PointLoad(-1, (0.05, 0.05), 2.0)],
        damping=0.3,
    )
    integ = GeneralizedAlpha(m, 0.8, 1e-10, 12)
    y, v = m.y0.copy(), m.v0.copy()
    a = integ.initial_acceleration(y, v, 0.0)
    w = a.copy()
    ys, vs, as_, ws = y.copy(), v.copy(), a.copy(), a.copy()
    h = 2e-3
    done, ok, _, stored, oy, _, oe, _, _, err, t_err = integ.run_steps(y, v, a, w, 0.0, h, 20, 5)
    assert (done, ok, stored) == (20, 1, 4)
    largest = (0.0, 0.0)
    for k in range(20):
        conv, ys, vs, as_, ws, e = integ.step(ys, vs, as_, ws, k * h, h)
        assert conv
        largest = max(largest, (e, (k + 1) * h))
        if (k + 1) % 5 == 0:
            assert np.array_equal(ys, oy[(k + 1) // 5 - 1])
    assert np.array_equal(ys, y) and np.array_equal(vs, v) and np.array_equal(as_, a)
    assert np.array_equal(ws, w)
    assert (err, t_err) == pytest.approx(largest, rel=1e-14) and err > 0.0
    assert oe[-1, 1] == m.strain_energy(y)
    assert oe[-1, 0] == pytest.approx(m.kinetic_energy(v), rel=1e-13)


def test_bad_sizes_are_value_errors_not_crashes():
    m = _pendulum(2)
    with pytest.raises(ValueError, match="y: expected"):
        m.core.internal_force(np.zeros(3), np.empty(m.n))
    with pytest.raises(TypeError):  # an output array of the wrong dtype is never copied
        m.core.internal_force(m.y0, np.empty(m.n, dtype=np.float32))


def test_core_sources_compile_without_warnings():
    """The core (every file but the bindings) is warning-free under strict flags."""
    cxx = shutil.which(os.environ.get("CXX", "c++")) or shutil.which("g++")
    if cxx is None:
        pytest.skip("no C++ compiler")
    src = sorted((ROOT / "src" / "cpp").rglob("*.cpp"))
    if not src:
        pytest.skip("C++ sources not in this checkout")
    flags = ["-std=c++17", "-fsyntax-only", "-Wall", "-Wextra", "-Wpedantic", "-Wshadow"]
    flags += ["-Wconversion", "-Werror", f"-I{ROOT / 'src' / 'cpp'}"]
    for f in src:
        if f.name.startswith("bindings"):  # need the nanobind headers (built by pip)
            continue
        p = subprocess.run([cxx, *flags, str(f)], capture_output=True, text=True)
        assert p.returncode == 0, p.stderr


def test_core_sources_are_formatted():
    """C++ formatted consistently: clang-format (style in .clang-format) changes nothing."""
    exe = shutil.which("clang-format") or str(Path(sys.executable).parent / "clang-format")
    if not Path(exe).exists():
        pytest.skip("clang-format not installed (it comes with the test extra)")
    src = sorted((ROOT / "src" / "cpp").rglob("*.[ch]pp"))
    if not src:
        pytest.skip("C++ sources not in this checkout")
    p = subprocess.run(
        [exe, "--dry-run", "--Werror", f"--style=file:{ROOT / '.clang-format'}", *map(str, src)],
        capture_output=True,
        text=True,
    )
    assert p.returncode == 0, p.stderr[:2000]


def test_consistent_acceleration_with_kept_mass_factors_is_a_fresh_one():
    # outputs ask for M a = F at state after state: the mass matrix's factors are kept from the
    # first call (constant M: no joints, rigid bodies, rotary inertia or contact); every later
    # answer is that of a new integrator, which factors M again
    m = _pendulum(4)
    integ = GeneralizedAlpha(m, 0.9, 1e-10, 12)
    sys_ = integ.system
    rng = np.random.default_rng(3)
    first = integ.initial_acceleration(sys_.y0.copy(), np.zeros(sys_.n), 0.0)
    assert np.all(np.isfinite(first))
    for k in range(3):
        y = sys_.y0 + 1e-3 * rng.normal(size=sys_.n)
        v = rng.normal(size=sys_.n)
        kept = integ.initial_acceleration(y, v, 0.1 * k)
        fresh = GeneralizedAlpha(m, 0.9, 1e-10, 12).initial_acceleration(y, v, 0.1 * k)
        assert np.abs(kept - fresh).max() <= 1e-12 * np.abs(fresh).max()
    assert integ.n_factorizations == 1
