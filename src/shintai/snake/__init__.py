"""Wheeled snake robot of seed 001 (Nakajima 2020): constraint switching and two-point control.

constants — thesis parameters with citations; model — planar kinematics of ch. 2 (A, B, J, modes);
model3d — the 3D chain, head-raised and double-arm models, wheel–plane relation (§2.5–2.6);
two_point — the controller of ch. 3; targets — the ramp (3.21) and angle unwrapping; plant — the
kinematic Body; mujoco_plant — the MuJoCo snake with passive wheels lifted by pitch joints;
two_plane — ch. 4 locomotion across two planes; scenarios_physical — shared pieces of §3.4 (targets,
the two-point law on the 3D models, a kinematic 3D plant); scenarios, scenarios_caging, scenarios_handcart,
scenarios_door, scenarios_two_plane, benchmarks — registered with shintai.scenarios.
"""
