"""A hand on three position-servoed slide axes in a wall corner: the smallest physical rig of the online
control index (seed 000 §2.4.1, §3.4.3; spec 000-part1 §5.4 checks 2 and 10), for ``sim.wall-force``.

The probe of the sign matrix sgn[ρ, f_msr] (§2.4.1, "acquired by trial"), the update rule
ρ ← ρ − A sgn (f_msr − f_trg) (Eq. 2.14) as a module with A = a·E from the probed slope, and the wall
that moves toward the hand.
"""

from __future__ import annotations

import numpy as np

from shintai.core.constants import GRAVITY
from shintai.core.runtime import Loop
from shintai.core.search_index import SearchIndex, SearchIndexModule, estimate_sign_matrix
from shintai.sim.body import MujocoBody

SERVO_KP = 3000.0  # N/m: K_p of the active limbs, seed 000 Table 3.4
SERVO_KV = 150.0  # N s/m: chosen, about critical damping of the 1.5 kg moving mass
HAND_RADIUS = 0.03  # m, chosen
WALL = 0.25  # m: the x and y walls' faces; the floor is z = 0
# The contacts are frictionless (condim="1" on every geom; MuJoCo uses the larger of a pair): Eq. 3.17's "different axes are independent"
# holds only without tangential coupling; with friction, static friction makes the probed forces
# path-dependent (sticking) and couples the axes — a limitation of the claim, not of the probe.
AXES = ("x", "y", "z")

CORNER_XML = f"""
<mujoco model="wall-force">
  <option timestep="0.001" integrator="implicitfast"/>
  <visual><global offwidth="640" offheight="480"/></visual>
  <worldbody>
    <light pos="0.3 -0.5 1.0" dir="-0.3 0.5 -1"/>
    <geom name="floor" type="plane" size="1 1 0.05" rgba=".85 .85 .85 1" solref="0.004 1" condim="1"/>
    <body name="xwall" mocap="true" pos="{WALL + 0.01} 0 0.15">
      <geom type="box" size="0.01 0.4 0.15" rgba=".8 .35 .3 .6" solref="0.004 1" condim="1"/>
    </body>
    <geom name="ywall" type="box" pos="0 {WALL + 0.01} 0.15" size="0.4 0.01 0.15" rgba=".3 .5 .8 .6" solref="0.004 1" condim="1"/>
    <body name="carriage_x" pos="0 0 0">
      <joint name="x" type="slide" axis="1 0 0"/>
      <inertial pos="0 0 0" mass="0.25" diaginertia="1e-3 1e-3 1e-3"/>
      <body name="carriage_y">
        <joint name="y" type="slide" axis="0 1 0"/>
        <inertial pos="0 0 0" mass="0.25" diaginertia="1e-3 1e-3 1e-3"/>
        <body name="carriage_z">
          <joint name="z" type="slide" axis="0 0 1"/>
          <inertial pos="0 0 0" mass="0.25" diaginertia="1e-3 1e-3 1e-3"/>
          <body name="hand">
            <geom type="sphere" size="{HAND_RADIUS}" mass="1.0" rgba=".2 .7 .3 1" solref="0.004 1" condim="1"/>
            <site name="wrist" pos="0 0 0"/>
          </body>
        </body>
      </body>
    </body>
  </worldbody>
  <actuator>
    <position name="x_servo" joint="x" kp="{SERVO_KP}" kv="{SERVO_KV}"/>
    <position name="y_servo" joint="y" kp="{SERVO_KP}" kv="{SERVO_KV}"/>
    <position name="z_servo" joint="z" kp="{SERVO_KP}" kv="{SERVO_KV}"/>
  </actuator>
  <sensor><force name="wrist_force" site="wrist"/></sensor>
</mujoco>
"""


CONTROL_STEP = 0.004  # s: the hrpsys control period, seed 000 App. A.2.1 (4 physics steps of 1 ms)


def build_corner() -> MujocoBody:
    """The hand and the corner, stepped every :data:`CONTROL_STEP`."""
    return MujocoBody(CORNER_XML, substeps=4)


def reaction_on_hand(body: MujocoBody, snapshot) -> np.ndarray:
    """f_msr: the environment's force on the hand from the wrist sensor, tool mass compensated.

    MuJoCo's force sensor gives the force the hand's parent exerts on it (site frame = world here);
    quasi-statically parent + environment + gravity balance: f_env = −f_sensor − m g.
    """
    m_hand = body.model.body_mass[body.id("body", "hand")]
    return -snapshot["wrist_force"] - m_hand * np.array([0.0, 0.0, -GRAVITY])


def settle(body: MujocoBody, rho: np.ndarray, seconds: float) -> np.ndarray:
    """Command reference ρ, let the physics settle, return the reaction on the hand."""
    Loop(body, [], base={f"{a}_servo": r for a, r in zip(AXES, rho)}).run(seconds)
    return reaction_on_hand(body, body.snapshot())


def contact_start() -> np.ndarray:
    """A reference 2 mm into each wall and the floor: every axis starts in (weak) contact."""
    inside = WALL - HAND_RADIUS + 0.002
    return np.array([inside, inside, HAND_RADIUS - 0.002])


def probe_sign(settle_s: float) -> tuple[np.ndarray, np.ndarray]:
    """Probe sgn[ρ, f_msr] at two contact points, and the mean slope ∂f/∂ρ per axis (for A)."""
    body = build_corner()
    slopes = []

    def plant(rho):
        return settle(body, rho, settle_s)

    base = [contact_start(), contact_start() + np.array([0.002, 0.002, -0.001])]
    sgn = estimate_sign_matrix(plant, base, step=1e-3, tol=0.05)
    for rho in base:
        f0 = plant(rho)
        slopes.append([(plant(rho + 1e-3 * np.eye(3)[i]) - f0)[i] / 1e-3 for i in range(3)])
    return sgn, np.mean(slopes, axis=0)


def shift_wall(body: MujocoBody, dx: float) -> None:
    """Move the x wall by ``dx`` along x (negative: toward the hand)."""
    body.data.mocap_pos[body.model.body_mocapid[body.id("body", "xwall")], 0] += dx


def passive_loop(body, sgn, slope, f_trg, step_fraction, update_s, recorder=None):
    """The update rule as a module in the Loop; A = a·E removes ``step_fraction`` of the error per
    update given the probed slope (the static limit of Table 3.3's A)."""
    settle(body, contact_start(), 0.5)
    law = SearchIndex(contact_start(), np.diag(step_fraction / np.abs(slope)), sgn=sgn, x_d=f_trg)
    module = SearchIndexModule(law, lambda s: reaction_on_hand(body, s), "ctrl", name="passive", period=update_s)
    return Loop(body, [module], recorder=recorder), law


def press(sgn, slope, f_trg, step_fraction, update_s, updates, wall_shift, recorder=None):
    """``updates`` updates, then the wall moves by ``wall_shift`` toward the hand, and as many again."""
    body = build_corner()
    loop, law = passive_loop(body, sgn, slope, f_trg, step_fraction, update_s, recorder)
    errors, refs, forces_ft, forces_contact = [], [], [], []
    for k in range(2 * updates):
        if k == updates:
            shift_wall(body, -wall_shift)
        loop.run(update_s)
        f = reaction_on_hand(body, body.snapshot())
        errors.append(f - f_trg)
        refs.append(law.rho.copy())
        forces_ft.append(f)
        forces_contact.append(body.contact_force("hand"))
    return np.array(errors), np.array(refs), np.array(forces_ft), np.array(forces_contact), body.t
