"""HRP2-JSK's hands and feet as the :class:`~shintai.humanoid.tricycle.operation.Limb` the laws of seed 000
§3.4 drive (the robot side of Fig. 3.16 steps 2–3).

* ``point`` — forward kinematics of the grasp centre / sole (sites ``s_grasp`` / ``s_sole``).
* ``force`` — f^msr of Eq. 3.13: the environment's force on the hand / foot from the wrist / ankle
  6-axis F/T sensor (:func:`~shintai.humanoid.robots.hrp2.ft_reaction`; pressing on a pedal gives +z).
* ``command`` — u of Eqs. 3.10–3.11: the IK of that limb's joints (7 arm / 6 leg joints, within
  their Table A.2 ranges) for the target ξ, as joint-servo targets. A foot uses the closed-form leg
  IK (:mod:`shintai.humanoid.robots.leg_ik`, issue 13 item 2) and falls back to the DLS IK
  (:mod:`shintai.sim.ik`) only where the closed form gives no answer inside the limits (see
  :meth:`Hrp2Limb.solve`); a hand, 7 joints for a 5-constraint target, uses the DLS IK, compiled on the arm's chain
  (:mod:`shintai.sim.ik_chain`; the same search as :mod:`shintai.sim.ik`, equal to rounding).
  An unreachable ξ (IK does not converge inside the joint limits, the Reachability-Map stand-in)
  keeps the previous command — the second branch of Eq. 3.14 applied to the joint input; such
  ticks are counted in ``unreachable``.

Frame (chosen): all three live in the **vehicle frame**, fixed to the robot's waist through the
hip–saddle weld (§3.3.2: the waist is bonded to the saddle). The robot knows it from its own waist
pose; the tricycle's nominal model (:mod:`~shintai.humanoid.tricycle.vehicle`), which the active
plans use, is written in it, and it stays valid while the tricycle drives off (E3–E7). On level
ground its z is the vertical of f^trg = (0, 0, 150) N (Table 3.4).

Orientation (Table 3.1; the thesis's impedance is position-only, spec §6 item 3): a sole keeps
its y axis on the crank axis and its pitch at ``PEDAL_SOLE_PITCH`` (level, the riding posture's;
the freely turning pedal lies flat under it, so the vertical f^trg of Table 3.4 is normal to the
pedal — see the constant for why the pitch is not left free); a hand
keeps its x axis on the bar of the nominal handle at the handle angle its own point shows
(method (a), :func:`~shintai.humanoid.tricycle.switching.estimate_handle_angle`), roll about the bar free.
The IK starts from the limb's previous command, not from the measured joints, so the servo target
does not drift with the servo error (as hrpsys solves IK on its reference model).
"""

from __future__ import annotations

import mujoco
import numpy as np

from shintai.humanoid.constants import PEDAL_SOLE_PITCH
from shintai.humanoid.robots.hrp2 import SIDES
from shintai.humanoid.robots.leg_ik import inside_limits, leg_angles
from shintai.humanoid.tricycle.active import R_y
from shintai.humanoid.tricycle.riding import ANKLE_FT, ARM, HAND, LEG, SOLE, WRIST_FT
from shintai.humanoid.tricycle.switching import estimate_handle_angle
from shintai.humanoid.tricycle.vehicle import steer_axis
from shintai.sim import ik
from shintai.sim.body import MujocoBody
from shintai.sim.ik_chain import ChainIK

KINDS = ("hand", "foot")
BAR_IN_HAND = np.array([1.0, 0.0, 0.0])  # the grasped bar runs along the grasp site's x axis (hrp2.py)
CRANK_AXIS_IN_SOLE = np.array([0.0, 1.0, 0.0])  # the pedal axle along the sole's y axis
SOLE_IN_VEHICLE = R_y(PEDAL_SOLE_PITCH)  # the sole frame's orientation in the vehicle frame
_GRIP_Y = np.array([0.0, 1.0, 0.0])  # the grip site's y axis (the bar) at θ_h = 0
_STEER_AXIS = steer_axis()  # the nominal model's steering axis (constant)
_ORIGIN, _EYE = (0.0, 0.0, 0.0), (1.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0)  # the waist frame's own pose


def waist_pose(body: MujocoBody) -> tuple[np.ndarray, np.ndarray]:
    """(position, rotation) of the robot's waist, world frame."""
    waist = body.id("body", "waist")
    return body.data.xpos[waist].copy(), body.data.xmat[waist].reshape(3, 3).copy()


class VehicleFrame:
    """The vehicle frame as the robot knows it: the waist pose composed with the waist → vehicle
    transform of the hip–saddle weld, taken once at the start (``body`` seated, kinematics done)."""

    def __init__(self, body: MujocoBody):
        self.body = body
        self.waist = body.id("body", "waist")
        p_w, r_w = waist_pose(body)
        p_v, r_v = body.body_pos("tricycle"), body.data.body("tricycle").xmat.reshape(3, 3)
        self.offset, self.rot_in_waist = r_w.T @ (p_v - p_w), r_w.T @ r_v
        self._key, self._pose = None, None
        self._data = None

    def pose(self) -> tuple[np.ndarray, np.ndarray]:
        """(position, rotation) of the vehicle frame, world (read-only arrays: computed once per waist
        pose, which several limbs and laws ask for every tick)."""
        if self._data is not self.body.data:  # the waist's rows of the data, as views taken once
            d = self._data = self.body.data
            self._xpos, self._xmat = d.xpos[self.waist], d.xmat[self.waist]
        key = (self._xpos.tobytes(), self._xmat.tobytes())
        if key != self._key:
            p_w, r_w = self._xpos, self._xmat.reshape(3, 3)
            p, r = p_w + r_w.dot(self.offset), r_w.dot(self.rot_in_waist)  # .dot: @'s BLAS call, without the ufunc
            p.setflags(write=False), r.setflags(write=False)
            self._key, self._pose = key, (p, r)
        return self._pose

    # the 3-vector maths below as ndarray.dot (the same BLAS products as @, bit for bit, at a third of the call's
    # cost: these run several times a control tick)

    def to_vehicle(self, world_point) -> np.ndarray:
        p, r = self.pose()
        return r.T.dot(np.subtract(world_point, p))  # = rᵀ (x − p)

    def to_world(self, vehicle_point) -> np.ndarray:
        p, r = self.pose()
        return p + r.dot(np.asarray(vehicle_point, dtype=float))

    def rotate_to_vehicle(self, world_vector) -> np.ndarray:
        return self.pose()[1].T.dot(np.asarray(world_vector, dtype=float))


class Hrp2Limb:
    """One hand (on its grip) or foot (on its pedal) of the seated HRP2 as a ``Limb``.

    ``side`` is "left" or "right", ``kind`` "hand" or "foot"; ``frame`` a shared
    :class:`VehicleFrame`. ``name`` is e.g. ``left_foot`` (the LimbPair logs under it).
    """

    def __init__(self, body: MujocoBody, side: str, kind: str, frame: VehicleFrame | None = None):
        if side not in ("left", "right") or kind not in KINDS:
            raise ValueError(f"a limb is side 'left'/'right' and kind {KINDS}, got {side!r}, {kind!r}")
        s = side[0]
        self.body, self.side, self.kind, self.name = body, side, kind, f"{side}_{kind}"
        self.frame = frame or VehicleFrame(body)
        self.site = HAND[s] if kind == "hand" else SOLE[s]
        self.sensor = WRIST_FT[s] if kind == "hand" else ANKLE_FT[s]
        self.joints = ARM[s] if kind == "hand" else LEG[s]
        self.q = np.array([body.joint_qpos(j) for j in self.joints])
        self.qadr = np.array([body.model.joint(j).qposadr[0] for j in self.joints])
        # the same entries as a slice where they run consecutively (HRP2's limbs do): no fancy indexing a tick
        first = int(self.qadr[0])
        consecutive = np.array_equal(self.qadr, np.arange(first, first + len(self.qadr)))
        self._coords = slice(first, first + len(self.qadr)) if consecutive else self.qadr
        self.unreachable = 0
        # the feet's closed-form IK works in the waist frame: ξ's transform (offset, flat rotation) and the
        # sole's target orientation there, as Python floats (formed once; the weld does not move)
        self._to_waist = (self.frame.offset.tolist(), self.frame.rot_in_waist.ravel().tolist())
        self._sole_in_waist = tuple((self.frame.rot_in_waist @ SOLE_IN_VEHICLE).ravel().tolist())
        self.fallbacks = 0  # foot solves the closed form could not give inside the limits (DLS used)
        # ft_reaction's force, with its per-call look-ups done once (the torque is not needed here)
        self._ft_site = body.id("site", f"{self.sensor}_ft")
        self._ft_key = f"{self.sensor}_force"
        self._ft_weight = body.model.body_subtreemass[body.model.site_bodyid[self._ft_site]] * body.model.opt.gravity
        self._site_id = body.id("site", self.site)
        # the contact site's and the F/T site's rows of the data, as views taken once (MujocoBody keeps its data)
        self._site_xpos = body.data.site_xpos[self._site_id]
        self.site_rot = body.data.site_xmat[self._site_id].reshape(3, 3)
        self._ft_rot = body.data.site_xmat[self._ft_site].reshape(3, 3)
        # One FK / F/T reading per snapshot (the laws and the logging ask several times a tick); the
        # snapshot object is the key (kept referenced, so a new tick's snapshot is never mistaken for it).
        self._point = self._force = (None, None)
        self._bar, self._turn = np.zeros(3), np.zeros(4)  # a hand's target: scratch vector and quaternion
        # a hand's DLS IK: the arm's seven hinges are one serial chain (sim.ik_chain, issue 30: 2.4x faster a solve)
        self._chain = ChainIK(body.model, self.site, self.joints) if kind == "hand" else None

    def point(self, snapshot) -> np.ndarray:
        """Contact point (grasp centre / sole) from the robot's FK, vehicle frame [m]."""
        snap, value = self._point
        if snap is not snapshot:
            value = self.frame.to_vehicle(self._site_xpos)
            self._point = (snapshot, value)
        return value.copy()

    def force(self, snapshot) -> np.ndarray:
        """f^msr: the environment's force on the hand / foot, vehicle frame [N] (Eq. 3.13)."""
        snap, value = self._force
        if snap is not snapshot:
            # = ft_reaction(...)[0], faster: −R f − m g, with −(R f) for (−R) f (negation is exact)
            value = self.frame.rotate_to_vehicle(-self._ft_rot.dot(snapshot[self._ft_key]) - self._ft_weight)
            self._force = (snapshot, value)
        return value.copy()

    def target(self, xi) -> ik.Target:
        """The world-frame IK target of the contact point at ξ (vehicle frame), with its axis rule."""
        rot = self.frame.pose()[1]
        if self.kind == "foot":
            return ik.Target(pos=self.frame.to_world(xi), rot=rot.dot(SOLE_IN_VEHICLE))
        theta_h = estimate_handle_angle({self.side: xi})
        bar, turn = self._bar, self._turn  # the grip's bar (y of grip site) turned with the handle, pointing to the stem
        mujoco.mju_axisAngle2Quat(turn, _STEER_AXIS, theta_h)  # = sim.spec.quat_axis, into a buffer
        mujoco.mju_rotVecQuat(bar, _GRIP_Y, turn)
        # −s R bar, s = ±1 (exact: (−s R) bar, as written before, is the same numbers)
        return ik.Target(pos=self.frame.to_world(xi), axis=(BAR_IN_HAND, rot.dot(bar) * -SIDES[self.side[0]]))

    def solve(self, xi) -> ik.IKResult:
        """IK of this limb's joints for ξ (the rest of the body as measured).

        A foot: the closed-form leg IK (:func:`~shintai.humanoid.robots.leg_ik.leg_ik`) for the sole at ξ with
        orientation ``SOLE_IN_VEHICLE``, solved in the **waist frame** (ξ → waist through the weld's
        fixed transform), so the answer depends on ξ only, not on the waist's world pose; exact (FK to
        1e-9), residual (0, 0). Where it gives no answer inside Table A.2's ranges (out of reach, or a
        joint beyond a limit) the DLS IK below decides as before: clamped at a limit it may still meet
        the target within its tolerance (1e-4 m, 1e-3 rad), and its ``ok`` is the Eq. 3.14 gate.
        Such solves are counted in ``fallbacks``.

        The DLS IK (a hand; a foot's fallback) starts from the limb's previous command."""
        leg = self.closed_form(xi) if self.kind == "foot" else None
        if leg is None:
            return self.dls_solve(xi)
        q = self.body.data.qpos.copy()
        q[self._coords] = leg
        return ik.IKResult(q, True, (0.0, 0.0))

    def closed_form(self, xi) -> np.ndarray | None:
        """A foot's six leg angles for ξ by the closed-form leg IK in the waist frame (:meth:`solve`); None
        where it gives no answer inside the limits (counted in ``fallbacks``)."""
        x, y, z = xi.tolist() if isinstance(xi, np.ndarray) else (float(v) for v in xi)
        (o0, o1, o2), (r0, r1, r2, r3, r4, r5, r6, r7, r8) = self._to_waist  # ξ → waist, on Python floats
        pos = (o0 + r0 * x + r1 * y + r2 * z, o1 + r3 * x + r4 * y + r5 * z, o2 + r6 * x + r7 * y + r8 * z)
        q, reach_error = leg_angles(self.side[0], _ORIGIN, _EYE, pos, self._sole_in_waist)
        if reach_error == 0.0 and inside_limits(self.side[0], q):  # = leg_ik_floats(...).ok, without its result
            return np.array(q)
        self.fallbacks += 1
        return None

    def dls_solve(self, xi) -> ik.IKResult:
        """The DLS IK (:func:`shintai.sim.ik.solve`) of this limb's joints for ξ, from its previous command
        (the rest of the body as measured; the tricycle's feet used it alone before issue 13); a hand's as
        :class:`~shintai.sim.ik_chain.ChainIK`, the same search compiled on the arm's chain."""
        q0 = self.body.data.qpos.copy()
        q0[self._coords] = self.q
        if self._chain is not None:  # a hand: sim.ik's search on the arm's chain, compiled (equal to rounding)
            target = self.target(xi)
            return self._chain.solve(q0, target.pos, target.axis)
        return ik.solve(self.body, {self.site: self.target(xi)}, q0, self.joints)

    def reachable(self, xi) -> bool:
        """Eq. 3.14's gate: ξ is inside the limb's reachable set (IK converges within the joint limits)."""
        return self.solve(xi).ok

    def command(self, xi, snapshot) -> dict:
        """Joint-servo targets putting the contact point at ξ; the previous ones if ξ is unreachable. A foot's
        closed form gives its six angles directly (no whole qpos to fill); the targets are Python floats."""
        leg = self.closed_form(xi) if self.kind == "foot" else None
        if leg is not None:
            self.q = leg
        else:
            result = self.dls_solve(xi)
            if result.ok:
                self.q = result.q[self._coords].copy()
            else:
                self.unreachable += 1
        return dict(zip(self.joints, self.q.tolist()))


def riding_limbs(body: MujocoBody, kind: str) -> dict[str, Hrp2Limb]:
    """Both hands or both feet of the seated robot, keyed "left"/"right", sharing one vehicle frame."""
    frame = VehicleFrame(body)
    return {side: Hrp2Limb(body, side, kind, frame) for side in ("left", "right")}
