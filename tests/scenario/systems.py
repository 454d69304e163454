"""Scenario files of systems for the scenario tests."""

SLIDER_CRANK = """
[[bodies]]
name = "crank"
kind = "rigid"
mass = 0.1
inertia = 1.0e-4
position = [0.075, 0.0]
points = { pivot = [-0.075, 0.0], tip = [0.075, 0.0] }

[[bodies]]
name = "rod"
[bodies.geometry]
kind = "line"
start = [0.15, 0.0]
end = [0.45, 0.0]
[bodies.mesh]
elements = 8
element = "ancf"
[bodies.section]
radius = 0.003
[bodies.material]
density = 7870.0
youngs_modulus = 2.0e11

[[bodies]]
name = "slider"
kind = "mass"
mass = 0.033
position = [0.45, 0.0]

[[joints]]
name = "motor"
kind = "pin"
between = ["crank:pivot", "ground"]
angle = { spin_up = 0.05, rate = 150.0 }

[[joints]]
name = "crank_rod"
kind = "pin"
between = ["crank:tip", "rod:start"]

[[joints]]
name = "rod_slider"
kind = "pin"
between = ["rod:end", "slider"]

[[joints]]
name = "guide"
kind = "slider"
between = ["slider", "ground"]
axis = [1.0, 0.0]

[solver]
t_end = 0.2
step = 1.0e-4

[[sensors]]
name = "x"
kind = "position"
at = "slider"

[[sensors]]
name = "guide_force"
kind = "reaction"
joint = "guide"

[[sensors]]
name = "theta"
kind = "angle"
body = "crank"

[[sensors]]
name = "N"
kind = "axial_force"
at = "rod:4"

[[sensors]]
name = "p"
kind = "momentum"
"""

TETHER_3D = """
[[bodies]]
name = "cable"
[bodies.geometry]
kind = "line"
start = [0.0, 0.0, 0.0]
end = [0.5, 0.0, -0.866025403784]
[bodies.mesh]
elements = 10
element = "rod"
[bodies.section]
radius = 0.002
[bodies.material]
density = 7800.0
youngs_modulus = 2.0e11
poisson_ratio = 0.3
[bodies.initial_motion]
angular_velocity = [0.0, 0.1, 0.0]

[[bodies]]
name = "payload"
kind = "mass"
mass = 2.0
position = [0.5, 0.0, -0.866025403784]

[[bodies]]
name = "box"
kind = "rigid"
mass = 1.0
inertia = [0.1, 0.2, 0.25]
position = [1.0, 0.0, 0.0]
orientation = [[0.0, -1.0, 0.0], [1.0, 0.0, 0.0], [0.0, 0.0, 1.0]]
angular_velocity = [0.0, 0.0, 1.0]
points = { hook = [0.0, 0.1, 0.0] }

[[supports]]
at = "cable:start"
kind = "pin"
[supports.motion]
table = [[0.0, 0.0, 0.0, 0.0], [1.0, 0.1, 0.0, 0.0], [2.0, 0.1, 0.1, 0.0]]
interpolation = "cubic"

[[joints]]
name = "end"
kind = "pin"
between = ["cable:end", "payload"]

[[joints]]
name = "hinge"
kind = "revolute"
between = ["box:hook", "ground"]
axis = [0.0, 0.0, 1.0]
angle = { harmonic = 0.5, amplitude = 0.2, phase_deg = 90.0 }

[[springs]]
between = ["payload", "box"]
stiffness = 100.0
damping = 0.5

[loads]
gravity = [0.0, 0.0, -9.81]
[[loads.point]]
at = "box"
force = [0.0, 1.0, 0.0]
moment = [0.0, 0.0, 0.1]
time = { ramp = 0.5, value = 1.0 }

[[sensors]]
name = "com"
kind = "center_of_mass"
[[sensors]]
name = "R"
kind = "reaction"
at = "cable:start"
"""
