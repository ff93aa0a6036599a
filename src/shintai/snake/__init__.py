"""Wheeled snake robot of seed 001 (Nakajima 2020): constraint switching, two-point control, two planes.

Models and plants: constants (thesis parameters with their sources); model (planar kinematics of ch. 2: A, B,
J, modes); model3d (the 3D chain, head-raised and double-arm models, wheel–plane relation, §2.5–2.6); plant
(the kinematic Body); mujoco_plant (the MuJoCo snake, passive wheels lifted by pitch joints); two_plane,
two_plane_plant (ch. 4: the two-plane world, its models and kinematic plant).
Numerics: linalg (LAPACK's SVD and least squares for the 50 ms tick, through NumPy's own gufuncs).
Laws: two_point (ch. 3's controller), two_point_tick (its 50 ms tick compiled); spatial (the two-point law on the 3D models of §2.5); targets (the
piecewise-linear targets (3.21)–(3.23), (3.26)); door_operator, two_plane_phases (guarded phases as Switchers).
Experiments' library: tracking, caging, handcart, door, two_plane_runs, probe; plots, plots_two_plane.
Scenarios: one declaration per file in experiments/, each with its account in notes/; benchmarks.

Modules:

coverage — The experiments of seed 001 (Nakajima 2020, wheeled snake with constraint switching): one row per …
"""
