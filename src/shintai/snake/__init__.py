"""Wheeled snake robot of seed 001 (Nakajima 2020): constraint switching and two-point control.

constants — thesis parameters with citations; model — planar kinematics of ch. 2 (A, B, J, modes);
two_point — the controller of ch. 3; targets — the ramp (3.21) and angle unwrapping; plant — the
kinematic Body; scenarios / benchmarks — registered with shintai.scenarios.
"""
