"""HRP2-JSK riding the Ninebot One S2 (seed 000 §7.3.3, Figs. 7.6–7.13, Tables 7.3–7.4): target-ZMP trajectory
correction in parallel with speed-gain learning, for the scenarios ``humanoid.unicycle-*``.

* **Start**: the robot in the riding posture (:func:`build_ninebot_stand`: soles on the footboards, mass centre over
  the axle, i.e. over p⁰) is lowered by :class:`~shintai.humanoid.vboard.ride.Lift` ("人手のサポートを外す" — the
  thesis's human hand lets go, Fig. 7.7 (1)); times are reported from the lift's release.
* **Balance**: the standing stack (:class:`~shintai.humanoid.balance.standing.Standing`: AutoBalancer-like preview
  reference, LIP tracking [55] → p^{d*}, ZMP distributor, foot damping, force difference) at its floor gains (the
  footboards are rigid: the Ninebot has no board to tip, §A.1.3).
* **Fig. 7.8** (``learn`` or fixed gains): e_v = v^d − v (v of Eq. 6.3's filter, :class:`ScooterSensors`);
  :class:`TrajectoryCorrection` — C_traj (PID, Eq. 7.1) → u_traj, the target trajectory ρ = p^{d*} corrected by
  ρ ← ρ − A f with f = −u_traj, A = 1 (Table 7.4), through the derivative filter of Eq. 7.3 (ṗ^{d**} =
  LPF_{T_traj}{u_traj/Δt}), so p^{d**} = p^{d*} + c with ċ = LPF{u_traj}/Δt — the plant of Eq. 7.5; and
  :class:`SpeedPID` — C_v (PID) → u_v → foot-pitch increments (Eq. 6.5 with u_ω = 0: the Ninebot has no yaw
  input), integrated by :class:`~shintai.humanoid.vboard.ride.FootPitch`. Both are :class:`LearnedPID`, each with
  one :class:`~shintai.humanoid.learning.mlc.MLC` (the one implementation, Eqs. 6.17–6.30) updating every T_L = 2 s
  ("ゲインの学習周期は … それぞれ 2[s] 毎"), gains from 0, two modules of one Loop.
* p^{d**} reaches the stabilizer by :class:`ModifiedStabilizer`: the LIP law p^{d*} = p_ref + k1(..) + k2(..) +
  k3 (p_ref − p) is affine in p_ref with slope 1 + k3, so shifting p_ref by c/(1 + k3) gives p^{d*} + c exactly
  (stabilizer.py is left as it is).
* **Roll** (no training wheels, Eq. 7.6): :class:`RollShaping` is the joystick operator and Eq. 7.6:
  φ_C^d := φ_C^d + α ε_joy with ε_joy = clip(φ_vehicle/``JOY_FULL``, −1, 1) (chosen: the operator pushes the
  stick toward the side the unicycle falls, full at ``JOY_FULL``); Eq. 4.8's chest posture control (roll
  component) follows φ_C^d, turning the upper body about the soles' midpoint (:class:`ChestRollIK`).
"""

from __future__ import annotations

import functools
import math

import mujoco
import numpy as np

from shintai.core.geometry import roll_of, rot_x
from shintai.core.runtime import SET, Module, declare
from shintai.humanoid.balance.foot_attitude import quat_to_rot
from shintai.humanoid.balance.scooter import CHANNELS as RIDE_CHANNELS
from shintai.humanoid.balance.scooter import ChestPitchIK, FootPitch, Lift, ScooterSensors, posture_on_pads
from shintai.humanoid.balance.stabilizer import StabilizerModule
from shintai.humanoid.balance.standing import Push, Standing
from shintai.humanoid.constants import CONTROL_PERIOD, SCENE, SIGMA_V, SUBSTEPS
from shintai.humanoid.corrections import ChestPostureControl
from shintai.humanoid.learning.mlc import MLC, MLC_V, MLCParams
from shintai.humanoid.learning.prior_value_integrator import PID
from shintai.humanoid.learning.speed_governing import foot_pitch_increments
from shintai.humanoid.robots.hrp2 import add_hrp2
from shintai.humanoid.unicycle.constants import ETA_TRAJ, JOY_FULL, PLACEMENTS, START_DELAY, T_TRAJ
from shintai.humanoid.unicycle.hand import HumanHand
from shintai.humanoid.unicycle.vehicle import NINEBOT, PAD, NinebotSpec, add_ninebot, install_firmware, ninebot_velocity
from shintai.sim.body import MujocoBody
from shintai.sim.spec import fill_keyframe, scene_spec

# --- constants ------------------------------------------------------------------------------------------
K_TRAJ = NINEBOT.K0 / CONTROL_PERIOD  # Eq. 7.5: K_traj = K₀/Δt (m/s per m of correction per tick)
MLC_TRAJ = MLCParams(K=K_TRAJ, T=T_TRAJ, eta=ETA_TRAJ, eps=1e-6 / ETA_TRAJ[0], sigma=SIGMA_V)
MLC_SPEED = MLC_V  # the speed loop's plant for Eqs. 6.20–6.29: Table 6.2's (no Ninebot identification is given)
ALPHA = 0.5 * CONTROL_PERIOD  # rad per tick at full stick: φ_C^d moves ≤ 0.5 rad/s (Eq. 7.6's α, not given)
CHANNELS = {**RIDE_CHANNELS, **declare("zmp_mod", "ref:chest_roll", kind=SET)}


def standing_posture(model: mujoco.MjModel, n: NinebotSpec = NINEBOT) -> np.ndarray:
    """qpos with the soles level on the footboards' centres and the mass centre over the axle."""
    return posture_on_pads(model, model.qpos0.copy(), n.board_height, PAD, "ninebot_centre", "on the Ninebot",
                           flat_soles=True)


def build_ninebot_stand(n: NinebotSpec = NINEBOT, training_wheels: bool = True, substeps: int = SUBSTEPS):
    """HRP2 standing on the Ninebot One S2 (keyframe ``stand``), the firmware installed (``body.firmware``)."""
    spec = scene_spec("hrp2-ninebot", *SCENE)
    add_ninebot(spec, spec.worldbody, n=n, training_wheels=training_wheels)
    add_hrp2(spec, spec.worldbody, [0.0, 0.0, 1.0])
    spec.add_key(name="stand")
    model = spec.compile()
    fill_keyframe(model, "stand", standing_posture(model, n))
    body = MujocoBody(model, substeps=substeps, keyframe="stand", spec=spec)
    body.firmware = install_firmware(body, n)
    return body


class ModifiedStabilizer(StabilizerModule):
    """The stabilizer with the correction c = channel ``zmp_mod`` (x, m) (module docstring). ``placement``
    "after_lip": p^{d**} = p^{d*} + c (Eq. 7.2 as written); "reference": c shifts the LIP tracking's references
    (p_ref and x_ref), so that the rider's static ZMP moves by c as Eq. A.9 assumes (ours, see the notes)."""

    def __init__(self, body, placement: str = "after_lip", **kw):
        if placement not in PLACEMENTS:
            raise ValueError(f"placement must be one of {', '.join(PLACEMENTS)}, got {placement!r}")
        super().__init__(body, **kw)
        self.placement = placement

    def update(self, snapshot):
        c = float(snapshot.get("zmp_mod", 0.0))
        if c:
            snapshot = dict(snapshot)
            zr = np.array(snapshot["zmp_ref"], float)
            if self.placement == "reference":
                zr[0] += c
                cr = np.array(snapshot["com_ref"], float)
                cr[0] += c
                snapshot["com_ref"] = cr
            else:
                zr[0] += c / (1.0 + self.k[2]) if self.lip else c
            snapshot["zmp_ref"] = zr
        return super().update(snapshot)


class LearnedPID(Module):
    """One PID of Eq. 7.1 on e_v = v^d − v with its MLC (Eqs. 6.17–6.30); off (u = 0, no learning) until
    ``start(snapshot)`` first holds (``t_start``). ``output(u)`` → the module's contribution."""

    def __init__(self, params: MLCParams, name: str, start, gains0=(0.0, 0.0, 0.0), learn: bool = True):
        super().__init__(name, params.dt)
        self.params, self.start, self.learn = params, start, learn
        self.pid = PID(params.dt, gains0)
        self.mlc = MLC(params, gains0)
        self.t_start = None
        self.u = 0.0

    def output(self, u: float) -> dict:
        raise NotImplementedError

    def update(self, snapshot):
        t = float(snapshot["t"])
        if self.t_start is None and self.start(snapshot):
            self.t_start = t
        e = float(snapshot.get("v_d", 0.0)) - float(snapshot["v"])
        if self.t_start is None:
            return self.output(0.0)
        self.u = self.pid.step(e)
        if self.learn and self.mlc.observe(e, t):
            self.pid.set_gains(self.mlc.gains)
        self.log(t, **{f"{self.name}.e": e, f"{self.name}.u": self.u, f"{self.name}.gains": self.pid.gains})
        return self.output(self.u)


class TrajectoryCorrection(LearnedPID):
    """C_traj → u_traj → c (Eq. 7.3: ċ = LPF_{T_traj}{u_traj/Δt}) → ``zmp_mod`` (module docstring)."""

    def __init__(self, start, T_traj: float = T_TRAJ, **kw):
        super().__init__(kw.pop("params", MLC_TRAJ), kw.pop("name", "traj"), start, **kw)
        self._a = math.exp(-self.params.dt / T_traj)
        self.rate, self.c = 0.0, 0.0  # LPF{u_traj/Δt}, the correction p^{d**} − p^{d*}

    def output(self, u: float) -> dict:
        dt = self.params.dt
        self.rate = u / dt + (self.rate - u / dt) * self._a  # Eq. 7.3's low-pass filter
        self.c += self.rate * dt
        return {"zmp_mod": self.c}


class SpeedPID(LearnedPID):
    """C_v → u_v → foot-pitch increments [Δθ_R, Δθ_L] = [u_v, u_v] (Eq. 6.5 with u_ω = 0)."""

    def __init__(self, start, **kw):
        super().__init__(kw.pop("params", MLC_SPEED), kw.pop("name", "speed"), start, **kw)

    def output(self, u: float) -> dict:
        return {"foot_pitch": foot_pitch_increments(u, 0.0)}


def chest_roll(snapshot) -> float:
    """φ_C, the chest's roll from its IMU (about +x)."""
    return roll_of(quat_to_rot(snapshot["imu_quat"]))


class RollShaping(ChestPostureControl):
    """Eq. 7.6 with the joystick operator (module docstring), then Eq. 4.8 on the chest roll: ``ref:chest_roll``."""

    def __init__(self, alpha: float = ALPHA, full: float = JOY_FULL, **kw):
        super().__init__(chest_roll, name="roll", **kw)
        self.alpha, self.full = alpha, full

    def update(self, snapshot):
        roll = float(snapshot["ninebot_roll"][0])
        joy = max(-1.0, min(1.0, roll / self.full))  # ε_joy ∈ [−1, 1]
        self.target += self.alpha * joy  # Eq. 7.6
        delta = self.step(chest_roll(snapshot))
        self.log(snapshot["t"], **{"roll.joy": joy, "roll.target": self.target, "roll.delta": delta,
                                   "roll.vehicle": roll})
        return {"ref:chest_roll": delta}


class ChestRollIK(ChestPitchIK):
    """The leg IK turning the upper body by Δφ_C (roll) about the soles' midpoint (Eq. 4.9)."""

    channel = "ref:chest_roll"
    rotation = staticmethod(rot_x)


class NinebotRide:
    """HRP2 lowered onto the Ninebot and riding with the stack, C_traj and C_v (module docstring).

    ``control``: "stabilizer" (Fig. 7.7: no C_traj, no C_v) or "parallel" (Fig. 7.8); ``learn``: MLC on;
    ``gains`` ((traj), (v)) initial gains; ``v_d(t)`` the target speed from the learning start;
    ``training_wheels``; ``roll_shaping`` Eq. 7.6 (for the run without training wheels); ``placement`` of the
    correction (:class:`ModifiedStabilizer`); ``push`` (force (3,), t0, duration) on the chest; ``hand``: the person
    of Fig. 7.12 (a6) who catches the roll (:class:`~shintai.humanoid.unicycle.hand.HumanHand`)."""

    def __init__(self, control: str = "parallel", learn: bool = True, gains=((0.0,) * 3,) * 2, v_d=None,
                 training_wheels: bool = True, roll_shaping: bool = False, n: NinebotSpec = NINEBOT,
                 start_delay: float = START_DELAY, seed: int = 0, placement: str = "after_lip", push=None,
                 hand: bool = False):
        if control not in ("stabilizer", "parallel"):
            raise ValueError(f"control must be 'stabilizer' or 'parallel', got {control!r}")
        body = build_ninebot_stand(n, training_wheels)
        root = body.model.joint("root").qposadr[0]
        body.model.key("stand").qpos[root + 2] += 0.02
        self.lift = Lift(body)
        body.before_physics.insert(0, self.lift)
        body.reset("stand")
        self.lift.hold()
        self.standing = Standing(body=body, stabilizer=functools.partial(ModifiedStabilizer, placement=placement),
                                 ik=ChestRollIK if roll_shaping else None)
        if push is not None:  # on the chest, before every physics step (the lift owns the waist's xfrc_applied)
            body.before_physics.append(Push(body, *push, link="chest"))
        self.hand = HumanHand(body) if hand else None
        if self.hand is not None:
            body.before_physics.append(self.hand)
        self.body, self.n = body, n
        self.lift.lowering = True
        lift = self.lift

        def start(snapshot) -> bool:
            return lift.released and float(snapshot["t"]) >= lift.t_release + start_delay

        self.sensors = ScooterSensors(body, ninebot_velocity, seed=seed)
        self.traj = self.speed = self.foot_pitch = None
        if control == "parallel":
            self.traj = TrajectoryCorrection(start, gains0=gains[0], learn=learn)
            self.speed = SpeedPID(start, gains0=gains[1], learn=learn)
            self.foot_pitch = FootPitch()
        self.roll = RollShaping() if roll_shaping else None
        self.v_d = v_d
        target = _Target(v_d, lambda: self.t0) if v_d is not None else None
        self.stages = self.standing.stages(
            references=[m for m in (self.sensors, self.roll, target) if m is not None],
            governor=[self.traj, self.speed] if self.traj else (),
            beside_damping=[self.foot_pitch] if self.foot_pitch else ())
        self.channels = list(CHANNELS.values()) + list(declare("v_d", kind=SET).values())

    @property
    def t0(self) -> float:
        """The lift's release (t = 0 of the figures), NaN before it."""
        return self.lift.t_release

    def fallen(self) -> bool:
        return self.standing.fallen()

    def zmp_x(self, snapshot) -> float:
        """The measured ZMP's x in the vehicle frame (from p⁰), from the firmware's measured moment: M_y⁰ / W."""
        return self.body.firmware.moment / self.n.rider_weight

    def signals(self, snapshot) -> dict:
        v, w = ninebot_velocity(snapshot)
        c = self.traj.c if self.traj is not None else 0.0
        return {"true_v": v, "true_omega": w, "x": float(self.body.site_pos("ninebot_centre")[0]),
                "zmp_act_x": self.zmp_x(snapshot), "zmp_mod": c, "roll": float(snapshot["ninebot_roll"][0]),
                "omega_ref": self.body.firmware.omega_ref,
                "hand_n": float(np.linalg.norm(self.hand.force())) if self.hand is not None else 0.0}


class _Target(Module):
    """v^d(t − t0) on channel ``v_d`` (0 before the release)."""

    def __init__(self, v_d, t0):
        super().__init__("target", CONTROL_PERIOD)
        self.v_d, self.t0 = v_d, t0

    def update(self, snapshot):
        t0 = self.t0()
        return {"v_d": 0.0 if not math.isfinite(t0) else float(self.v_d(float(snapshot["t"]) - t0))}


