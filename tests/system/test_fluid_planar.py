"""A planar problem in water on a seabed is the same in 2D and in 3D: a chain from an anchor on
the seabed to a fairlead surging in its plane (fluid: buoyancy, Morison drag and added mass;
the seabed a plane obstacle), simulated as a 2D line in the x-z plane and as a 3D line, gives
the same motion and the same fairlead reaction, and the 3D line never leaves its plane.

The chain has no bending stiffness to speak of (inertia 1e-13 m^4): the 2D cable bends by its
signed curvature, the 3D cable by its size (src/cpp/elements/cable.cpp), which differ where the
curvature
changes sign against the reference's; with the benchmark chain's EI = 3.4 kN m^2 that moves the
fairlead reaction by 1e-5 (the same without fluid and seabed), without it by 1e-11."""

from __future__ import annotations

import numpy as np

from rancf.cli import main


def _scenario(dim: int) -> str:
    def v(x: float, z: float) -> str:
        return f"[{x!r}, {z!r}]" if dim == 2 else f"[{x!r}, 0.0, {z!r}]"

    return f"""
[geometry]
kind = "conic"
start = {v(-300.0, -100.0)}
end = {v(0.0, 0.0)}
angles_deg = [18.43494882292201, 71.56505117707799]
point = {v(-96.55665347288583, -67.81444884237139)}
[mesh]
elements = 8
quadrature_points = 5
[section]
area = 0.03668789808917197
inertia = 1.0e-13
[material]
density = 7850.0
youngs_modulus = 33596909722.222225
axial_strain = "engineering"
[fluid]
density = 1025.0
[hydro]
diameter = 0.216
drag_normal = 1.333
drag_axial = 0.639
added_mass_normal = 1.0
added_mass_axial = 0.5
[[supports]]
at = "start"
[[supports]]
at = "end"
motion = {{ harmonic = 0.05, amplitude = {v(5.0, 0.0)}, build_up = 0.0 }}
[[obstacles]]
name = "seabed"
kind = "plane"
point = {v(0.0, -100.10806535367585)}
normal = {v(0.0, 1.0)}
stiffness = 648000.0
[loads]
gravity = {v(0.0, -9.81)}
[solver]
initial_state = "reference"
newton = "modified"
rho_inf = 0.5
t_end = 4.0
step = 0.1
output_step = 0.5
[[sensors]]
name = "fairlead"
kind = "reaction"
at = "end"
"""


def test_planar_surge_in_water_is_the_same_in_2d_and_3d(tmp_path):
    """The fairlead reaction (x, z) and the nodal coordinates of the 2D run equal the 3D run's
    to 1e-9 of their size (measured 5e-12), the 3D run's out-of-plane reaction and coordinates
    stay zero (1e-9), and the seabed carries the chain."""
    runs = {}
    for dim in (2, 3):
        path = tmp_path / f"surge{dim}.toml"
        path.write_text(_scenario(dim))
        assert main(["simulate", str(path), "--out", str(tmp_path / f"run{dim}"), "--quiet"]) == 0
        runs[dim] = np.load(tmp_path / f"run{dim}" / "results.npz")
    r2, r3 = runs[2], runs[3]
    np.testing.assert_array_equal(r2["t"], r3["t"])
    f2, f3 = r2["sensors"], r3["sensors"]  # fairlead x, z (2D); x, y, z (3D)
    scale = np.abs(f2).max()
    assert np.abs(f2 - f3[:, [0, 2]]).max() <= 1e-9 * scale
    assert np.abs(f3[:, 1]).max() <= 1e-9 * scale
    q2 = r2["q"].reshape(len(r2["t"]), -1, 4)  # (x, z, x', z') a node
    q3 = r3["q"].reshape(len(r3["t"]), -1, 6)
    size = np.abs(q2).max()
    assert np.abs(q2 - q3[:, :, [0, 2, 3, 5]]).max() <= 1e-9 * size
    assert np.abs(q3[:, :, [1, 4]]).max() <= 1e-9 * size
    # reactions: start (x, z), end (x, z), then the seabed's normal force (x, z), ...
    assert r2["reactions"][1:, 5].min() > 0.0
