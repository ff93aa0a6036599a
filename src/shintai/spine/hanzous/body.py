"""HanzouS as a dynamic MuJoCo body (seed 003 §3.3, §5.7.2): 18 servoed joints, a leaf-spring trunk whose
stiffness the cam changes during the motion (Eqs. 5.4–5.8), horizontal bars and switchable grasps.

* **Joints** (§3.3.2: '18 関節'; the layout is not printed, ours): per arm shoulder pitch, shoulder roll, elbow,
  gripper (8); per leg hip roll, hip pitch, knee, ankle pitch, ankle roll (10). Every joint is an RC-servo
  position actuator (:class:`~shintai.spine.robots.HanzouSSpec` gains and torque limit).
* **Trunk**: one hinge about the pitch axis between chest and pelvis, the leaf spring of §3.3.1. The
  simulator of §5.7.2 changes E and l of a DADS BEAM element during the motion (Eqs. 5.4–5.8); our hinge
  carries Eq. 5.8's bending block condensed to the end rotation, ``E I / l``
  (:meth:`~shintai.spine.robots.HanzouSSpec.rotational_stiffness_nm_rad`), written into ``model.jnt_stiffness``
  between steps as the cam turns (:meth:`Trunk.set_cam`). The hinge sits at the middle of the exposed leaf
  and does not move with l (a choice: a pure end moment bends the leaf into an arc whose end pivots about its
  middle). A force/torque sensor pair at the pelvis end (``trunk_root_force``) measures the trunk root's
  internal force of Fig. 5.24.
* **Bars and grasp**: bars along y at height :data:`BAR_Z`, ``bar_spacing_m`` apart in x. A grasp is a
  connect equality between the gripper's grip point and the bar axis, switched through ``data.eq_active``
  (:class:`Grasps`): it closes when the gripper is commanded closed with the grip point within
  ``grasp_radius_m`` of a bar, holding the grip point where it was caught (inside the gripper's mouth, so the
  closure stops the hand but does not pull it onto the axis: the grasp's impact is the hand's and the body's
  momentum, not a constraint snap), and opens when the gripper is commanded open. The grip pivots about the
  bar (a hook grip; the thesis gives no contact model of the gripper).
* **Planar root** (ours): x, z slides and a pitch hinge. The brachiation of Fig. 3.13 is in the sagittal
  plane and both hands hang from bars along y; the lateral DOF are not simulated.
"""

from __future__ import annotations

import mujoco
import numpy as np

from shintai.spine.hanzous.constants import BAR_Z, GRIPPER_OPEN_RAD, N_BARS
from shintai.spine.robots import HANZOUS, HanzouSSpec

ARM_JOINTS = ("shoulder_pitch", "shoulder_roll", "elbow", "gripper")
LEG_JOINTS = ("hip_roll", "hip_pitch", "knee", "ankle_pitch", "ankle_roll")
JOINTS = tuple(f"{j}_{s}" for s in "LR" for j in ARM_JOINTS) + tuple(f"{j}_{s}" for s in "LR" for j in LEG_JOINTS)
VIDEO_VIEW = {"distance": 1.3, "azimuth": 90.0, "elevation": -3.0, "track": "chest"}  # side view
GRASPS = tuple(f"grasp_{side}_bar{b}" for side in "LR" for b in range(N_BARS))


def _arm(spec: HanzouSSpec, side: str, y: float, z: float) -> str:
    ua, fa, hd = spec.upper_arm_m, spec.forearm_m, spec.hand_m
    mu, mf, mh = spec.arm_masses_kg
    kv = spec.servo_kv_nms_rad
    return f"""
      <body name="upper_arm_{side}" pos="0 {y} {z}">
        <joint name="shoulder_pitch_{side}" axis="0 1 0" range="-3.0 3.0" damping="{kv}"/>
        <joint name="shoulder_roll_{side}" axis="1 0 0" range="-0.5 0.5" damping="{kv}"/>
        <geom type="capsule" fromto="0 0 0 0 0 {ua}" size="0.012" mass="{mu}" rgba=".3 .5 .8 1"/>
        <body name="forearm_{side}" pos="0 0 {ua}">
          <joint name="elbow_{side}" axis="0 1 0" range="-2.4 2.4" damping="{kv}"/>
          <geom type="capsule" fromto="0 0 0 0 0 {fa}" size="0.011" mass="{mf}" rgba=".3 .5 .8 1"/>
          <body name="hand_{side}" pos="0 0 {fa}">
            <geom type="box" pos="0 0 {hd / 2}" size="0.012 0.012 {hd / 2}" mass="{mh * 0.8}" rgba=".2 .2 .2 1"/>
            <site name="grip_{side}" pos="0 0 {hd}" size="0.006"/>
            <body name="finger_{side}" pos="0.012 0 {hd * 0.4}">
              <joint name="gripper_{side}" axis="0 1 0" range="0 {GRIPPER_OPEN_RAD}" damping="0.02"/>
              <geom type="capsule" fromto="0 0 0 0 0 {hd * 0.7}" size="0.005" mass="{mh * 0.2}" rgba=".9 .6 .1 1"/>
            </body>
          </body>
        </body>
      </body>"""


def _leg(spec: HanzouSSpec, side: str, y: float, z: float) -> str:
    th, sh = spec.thigh_m, spec.shank_m
    mt, ms, mfoot = spec.leg_masses_kg
    kv = spec.servo_kv_nms_rad
    return f"""
        <body name="thigh_{side}" pos="0 {y} {z}">
          <joint name="hip_roll_{side}" axis="1 0 0" range="-0.5 0.5" damping="{kv}"/>
          <joint name="hip_pitch_{side}" axis="0 1 0" range="-2.0 2.0" damping="{kv}"/>
          <geom type="capsule" fromto="0 0 0 0 0 {-th}" size="0.015" mass="{mt}" rgba=".3 .5 .8 1"/>
          <body name="shank_{side}" pos="0 0 {-th}">
            <joint name="knee_{side}" axis="0 1 0" range="-0.1 2.4" damping="{kv}"/>
            <geom type="capsule" fromto="0 0 0 0 0 {-sh}" size="0.013" mass="{ms}" rgba=".3 .5 .8 1"/>
            <body name="foot_{side}" pos="0 0 {-sh}">
              <joint name="ankle_pitch_{side}" axis="0 1 0" range="-1.0 1.0" damping="{kv}"/>
              <joint name="ankle_roll_{side}" axis="1 0 0" range="-0.5 0.5" damping="{kv}"/>
              <geom type="box" pos="0.015 0 -0.008" size="0.035 0.02 0.008" mass="{mfoot}" rgba=".2 .2 .2 1"/>
            </body>
          </body>
        </body>"""


def mjcf(spec: HanzouSSpec = HANZOUS) -> str:
    """The HanzouS scene as MJCF: both hands on bar 0, arms straight up, everything else at zero."""
    cx, cy, cz = spec.chest_size_m
    px, py, pz = spec.pelvis_size_m
    reach = spec.upper_arm_m + spec.forearm_m + spec.hand_m
    chest_z = BAR_Z - reach - cz / 2
    gap = spec.leaf_gap_m
    pelvis_z = -cz / 2 - gap - pz / 2
    hinge_z = pz / 2 + gap / 2  # in the pelvis frame: the middle of the exposed leaf
    bars = "".join(f'<geom name="bar{b}" type="cylinder" fromto="{b * spec.bar_spacing_m} -0.1 {BAR_Z} '
                   f'{b * spec.bar_spacing_m} 0.1 {BAR_Z}" size="{spec.bar_radius_m}" rgba=".6 .6 .6 1"/>'
                   for b in range(N_BARS))
    grasps = "".join(f'<connect name="grasp_{s}_bar{b}" body1="hand_{s}" body2="world" anchor="0 0 {spec.hand_m}" '
                     f'active="{"true" if b == 0 else "false"}" solref="0.01 1"/>'
                     for s in "LR" for b in range(N_BARS))
    kp, tau = spec.servo_kp_nm_rad, spec.servo_torque_nm
    actuators = "".join(f'<position name="{j}" joint="{j}" kp="{kp}" forcerange="{-tau} {tau}"/>' for j in JOINTS)
    return f"""<mujoco model="hanzous">
  <compiler angle="radian" autolimits="true"/>
  <option timestep="0.001" integrator="implicitfast"/>
  <default><geom contype="0" conaffinity="0"/><joint armature="0.002"/></default>
  <visual><global offwidth="640" offheight="480"/></visual>
  <asset><texture name="grid" type="2d" builtin="checker" rgb1=".2 .3 .4" rgb2=".3 .4 .5" width="64" height="64"/>
    <material name="grid" texture="grid" texrepeat="8 8"/></asset>
  <worldbody>
    <light pos="0.2 -1 2" dir="0 0.5 -1"/>
    <geom name="floor" type="plane" size="2 2 0.1" pos="0 0 0" material="grid"/>
    {bars}
    <body name="chest" pos="0 0 {chest_z}">
      <joint name="root_x" type="slide" axis="1 0 0"/>
      <joint name="root_z" type="slide" axis="0 0 1"/>
      <joint name="root_pitch" axis="0 1 0"/>
      <geom type="box" size="{cx / 2} {cy / 2} {cz / 2}" mass="{spec.chest_mass_kg}" rgba=".8 .8 .8 1"/>
      <geom type="box" pos="0 0 {-cz / 2 - gap / 4}" size="0.001 {spec.leaf_width_m / 2} {gap / 4}" mass="0"
            rgba=".9 .2 .2 1"/>
      <site name="chest" pos="0 0 0" size="0.01"/>
      {_arm(spec, "L", spec.shoulder_y_m, cz / 2)}
      {_arm(spec, "R", -spec.shoulder_y_m, cz / 2)}
      <body name="pelvis" pos="0 0 {pelvis_z}">
        <joint name="trunk" axis="0 1 0" pos="0 0 {hinge_z}" stiffness="{spec.rotational_stiffness_nm_rad(0.0):.6g}"/>
        <geom type="box" size="{px / 2} {py / 2} {pz / 2}" mass="{spec.pelvis_mass_kg}" rgba=".8 .8 .8 1"/>
        <geom type="box" pos="0 0 {pz / 2 + gap / 4}" size="0.001 {spec.leaf_width_m / 2} {gap / 4}" mass="0"
              rgba=".9 .2 .2 1"/>
        <site name="trunk_root" pos="0 0 {hinge_z}" size="0.008"/>
        {_leg(spec, "L", spec.hip_y_m, -pz / 2)}
        {_leg(spec, "R", -spec.hip_y_m, -pz / 2)}
      </body>
    </body>
  </worldbody>
  <equality>{grasps}</equality>
  <actuator>{actuators}</actuator>
  <sensor><force name="trunk_root_force" site="trunk_root"/><torque name="trunk_root_torque" site="trunk_root"/>
  </sensor>
</mujoco>"""


def build_spec(spec: HanzouSSpec = HANZOUS) -> mujoco.MjSpec:
    return mujoco.MjSpec.from_string(mjcf(spec))


class Trunk:
    """The leaf-spring trunk's stiffness on a compiled model: the cam angle → l → ``E I / l`` (Eqs. 5.4–5.8),
    written into ``model.jnt_stiffness`` (and a damping of ``leaf_damping_ratio``) between steps."""

    def __init__(self, model: mujoco.MjModel, spec: HanzouSSpec = HANZOUS):
        self.model, self.spec = model, spec
        self.joint = model.joint("trunk").id
        self.dof = int(model.jnt_dofadr[self.joint])
        self.inertia = self._lower_body_inertia(model)
        self.cam_deg = 0.0
        self.set_cam(0.0)

    def _lower_body_inertia(self, model) -> float:
        """The pelvis-and-legs' moment of inertia about the trunk hinge at the zero posture [kg m²]."""
        data = mujoco.MjData(model)
        mujoco.mj_forward(model, data)
        pelvis = model.body("pelvis").id
        axis_point = data.site("trunk_root").xpos
        total = 0.0
        for b in range(model.nbody):
            a, chain = b, False
            while a:
                if a == pelvis:
                    chain = True
                    break
                a = model.body_parentid[a]
            if chain:
                r = data.xipos[b] - axis_point
                total += model.body_mass[b] * (r[0] ** 2 + r[2] ** 2) + model.body_inertia[b].max()
        return total

    def stiffness(self, cam_deg: float) -> float:
        return float(self.spec.rotational_stiffness_nm_rad(cam_deg))

    def set_cam(self, cam_deg: float) -> None:
        self.cam_deg = float(cam_deg)
        k = self.stiffness(cam_deg)
        self.model.jnt_stiffness[self.joint] = k
        self.model.dof_damping[self.dof] = 2 * self.spec.leaf_damping_ratio * np.sqrt(k * self.inertia)


class Grasps:
    """The switchable grasps: connect equalities hand ↔ bar toggled in ``data.eq_active``."""

    def __init__(self, model: mujoco.MjModel, data: mujoco.MjData, spec: HanzouSSpec = HANZOUS):
        self.model, self.data, self.spec = model, data, spec
        self.eq = {(s, b): model.equality(f"grasp_{s}_bar{b}").id for s in "LR" for b in range(N_BARS)}
        self.grip = {s: model.site(f"grip_{s}").id for s in "LR"}
        self.bar_x = np.arange(N_BARS) * spec.bar_spacing_m
        for (s, b), e in self.eq.items():  # the bar end of each grasp: on the bar axis, at the hand's y
            model.eq_data[e, 3:6] = (self.bar_x[b], spec.shoulder_y_m * (1 if s == "L" else -1), BAR_Z)

    def held(self, side: str) -> int | None:
        """The bar ``side``'s hand holds, or None."""
        for b in range(N_BARS):
            if self.data.eq_active[self.eq[(side, b)]]:
                return b
        return None

    def distance(self, side: str, bar: int) -> float:
        """The grip point's distance from ``bar``'s axis (in the x–z plane) [m]."""
        p = self.data.site_xpos[self.grip[side]]
        return float(np.hypot(p[0] - self.bar_x[bar], p[2] - BAR_Z))

    def update(self, side: str, closed: bool) -> None:
        """Open the hand's grasp if the gripper is commanded open; close it on the nearest bar within the
        gripper's mouth if it is commanded closed and holds nothing."""
        held = self.held(side)
        if not closed:
            if held is not None:
                self.data.eq_active[self.eq[(side, held)]] = 0
            return
        if held is not None:
            return
        d = [self.distance(side, b) for b in range(N_BARS)]
        b = int(np.argmin(d))
        if d[b] <= self.spec.grasp_radius_m:
            e = self.eq[(side, b)]
            self.model.eq_data[e, 3:6] = self.data.site_xpos[self.grip[side]]  # caught where it is: no snap
            self.data.eq_active[e] = 1

    def force_n(self, side: str) -> float:
        """The magnitude of the force the held bar exerts on the hand (the connect constraint's force) [N]."""
        held = self.held(side)
        if held is None:
            return 0.0
        d = self.data
        rows = (d.efc_type[: d.nefc] == mujoco.mjtConstraint.mjCNSTR_EQUALITY) & (d.efc_id[: d.nefc] == self.eq[(side, held)])
        return float(np.linalg.norm(d.efc_force[: d.nefc][rows]))
