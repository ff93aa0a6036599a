"""Models of seed 000: HRP2-JSK-like humanoid (App. A.2.1), tricycle (App. A.1.1), Kenshiro's legs (§3.5.5)."""

from __future__ import annotations

import math

import mujoco
import numpy as np
import pytest

from shintai.humanoid.constants import HRP2_HEIGHT, KENSHIRO, TRICYCLE
from shintai.humanoid.robots import hrp2, kenshiro
from shintai.humanoid.tricycle.vehicle import build_tricycle

G = 9.81
MASS = 56.5  # kg, Table A.1

# Table A.2 as printed, mapped to (lower, upper) degrees of the right limb / centre joints with the
# package's signs: forward pitch of shoulder/elbow/hip/ankle negative, of waist/neck positive,
# "out" of the right limb's roll/yaw negative. The left limb mirrors roll and yaw.
TABLE_A2 = {  # joint: (lower, upper) deg, max torque N m
    "neck_pitch": ((-30, 45), 9.6), "neck_yaw": ((-45, 45), 9.6),
    "shoulder_pitch": ((-180, 60), 160.3), "shoulder_roll": ((-95, 10), 100.4), "shoulder_yaw": ((-92, 92), 48.7),
    "elbow_pitch": ((-137, 2), 108.5), "wrist_yaw": ((-92, 92), 13.9), "wrist_roll": ((-90, 90), 18.7),
    "wrist_pitch": ((-90, 90), 16.0), "gripper": ((-16, 60), 13.9),
    "waist_pitch": ((-5, 60), 278.9), "waist_yaw": ((-45, 45), 151.8),
    "hip_pitch": ((-125, 42), 151.4), "hip_roll": ((-35, 20), 175.4), "hip_yaw": ((-45, 30), 86.2),
    "knee_pitch": ((-2, 150), 168.3), "ankle_pitch": ((-75, 42), 131.6), "ankle_roll": ((-20, 35), 73.1),
}
MIRRORED = ("roll", "yaw", "gripper")


@pytest.fixture(scope="module")
def standing():
    body = hrp2.build_hrp2()
    for _ in range(round(2.0 / body.dt)):
        body.step()
    return body


def test_hrp2_has_32_joints_with_servos_and_weighs_56_5_kg():
    body = hrp2.build_hrp2()
    m = body.model
    hinges = [m.joint(j).name for j in range(m.njnt) if m.jnt_type[j] == mujoco.mjtJoint.mjJNT_HINGE]
    assert len(hinges) == 32 == len(hrp2.JOINTS)
    assert sorted(hinges) == sorted(hrp2.JOINTS)
    assert sorted(m.actuator(i).name for i in range(m.nu)) == sorted(hrp2.JOINTS)
    assert m.body_subtreemass[m.body("waist").id] == pytest.approx(MASS)


def test_hrp2_joint_ranges_and_torques_are_table_a2():
    m = hrp2.build_hrp2().model
    for name in hrp2.JOINTS:
        side, base = (name[0], name[2:]) if name[:2] in ("l_", "r_") else ("", name)
        (lo, hi), torque = TABLE_A2[base]
        if side == "l" and base.endswith(MIRRORED):
            lo, hi = -hi, -lo
        assert np.degrees(m.joint(name).range) == pytest.approx([lo, hi]), name
        act = m.actuator(name)
        assert act.forcerange == pytest.approx([-torque, torque]), name
        assert act.forcelimited[0] == 1


def test_hrp2_is_1607_mm_tall_at_zero_posture():
    body = hrp2.build_hrp2()
    body.data.qpos[:] = body.model.qpos0
    body.data.qpos[2] = 0.78  # waist origin above the soles, straight legs
    body.forward()
    assert _top(body) == pytest.approx(HRP2_HEIGHT, abs=1e-3)
    assert body.site_pos("l_sole")[2] == pytest.approx(0.0, abs=1e-9)


def _top(body) -> float:
    """Highest point of the box geoms (the head is a box)."""
    m, d = body.model, body.data
    boxes = np.flatnonzero(m.geom_type == mujoco.mjtGeom.mjGEOM_BOX)
    return max(d.geom_xpos[g, 2] + np.abs(d.geom_xmat[g].reshape(3, 3)[2]) @ m.geom_size[g] for g in boxes)


def test_hrp2_standing_sensors_read_weight_gravity_and_upright(standing):
    snap = standing.snapshot()
    feet = [hrp2.ft_reaction(standing, snap, f"{s}_ankle")[0] for s in "lr"]
    assert feet[0][2] + feet[1][2] == pytest.approx(MASS * G, rel=0.01)
    assert feet[0][2] == pytest.approx(feet[1][2], rel=0.02)
    assert np.abs(feet[0][:2]).max() < 5.0
    for s in "lr":  # free hands: no external force
        force, torque = hrp2.ft_reaction(standing, snap, f"{s}_wrist")
        assert np.abs(force).max() < 0.5 and np.abs(torque).max() < 0.1
    assert snap["imu_acc"] == pytest.approx([0, 0, G], abs=0.15)
    assert np.abs(snap["imu_gyro"]).max() < 1e-2
    assert abs(snap["imu_quat"][0]) > 0.999


def test_tricycle_dimensions_are_appendix_a11():
    body = build_tricycle()
    t = TRICYCLE
    grip_l, grip_r = body.site_pos("grip_l"), body.site_pos("grip_r")
    crank, saddle = body.site_pos("crank_centre"), body.site_pos("saddle_top")
    assert grip_l[2] == pytest.approx(0.900) and grip_r[2] == pytest.approx(0.900)
    assert np.linalg.norm(grip_l - grip_r) == pytest.approx(0.480)
    assert saddle[2] - crank[2] == pytest.approx(0.450)
    assert grip_l[0] - saddle[0] == pytest.approx(0.350)
    assert np.linalg.norm(body.site_pos("pedal_l_top") - crank - [0, 0.135, 0.01]) == pytest.approx(t.crank_radius)
    m = body.model
    wheels = {n: body.body_pos(n) for n in ("front_wheel", "rear_l_wheel", "rear_r_wheel")}
    assert wheels["front_wheel"][0] - crank[0] == pytest.approx(0.600)
    assert crank[0] - wheels["rear_l_wheel"][0] == pytest.approx(0.600)
    assert wheels["rear_l_wheel"][1] - wheels["rear_r_wheel"][1] == pytest.approx(0.400)
    assert m.geom("front_wheel").size[0] == pytest.approx(0.250)
    assert m.geom("rear_l_wheel").size[0] == pytest.approx(0.200)


def _crank_ramp(body, turns: float, seconds: float, handle: float = 0.0) -> None:
    """Drive the crank servo through ``turns`` revolutions with zero start/end speed."""
    for _ in range(round(0.5 / body.dt)):  # settle on the tyres
        body.step()
    start = body.joint_qpos("crank")
    n = round(seconds / body.dt)
    for i in range(n + round(0.5 / body.dt)):
        s = min(1.0, (i + 1) / n)
        body.apply({"crank": start + 2 * math.pi * turns * (s - math.sin(2 * math.pi * s) / (2 * math.pi)),
                    "handle": handle})
        body.step()


def test_one_crank_revolution_moves_the_tricycle_2_45_m():
    body = build_tricycle()
    start = body.body_pos("tricycle")
    _crank_ramp(body, 1.0, 6.0)  # gentle: only the left back wheel drives, on ~1/3 of 21.5 kg
    travel = body.body_pos("tricycle") - start
    assert travel[0] == pytest.approx(TRICYCLE.travel_per_rev, rel=0.005)  # D_c, App. A.1.1
    assert abs(travel[1]) < 0.01
    assert body.joint_qpos("rear_l_wheel") == pytest.approx(TRICYCLE.gear_ratio * 2 * math.pi, rel=1e-3)


@pytest.mark.parametrize("theta_h", [math.radians(20), -math.radians(20)])
def test_the_handle_turns_the_front_wheel_and_steers(theta_h):
    body = build_tricycle(theta_h=theta_h)
    _crank_ramp(body, 1.0, 4.0, handle=theta_h)
    w, x, y, z = body.data.body("tricycle").xquat
    yaw = math.atan2(2 * (w * z + x * y), 1 - 2 * (y * y + z * z))
    wheelbase = TRICYCLE.crank_to_front + TRICYCLE.crank_to_back
    ground_steer = math.atan(math.tan(theta_h) * math.cos(TRICYCLE.steer_rake))  # raked axis
    expected = TRICYCLE.travel_per_rev / wheelbase * math.tan(ground_steer)  # kinematic tricycle
    assert body.joint_qpos("handle") == pytest.approx(theta_h, abs=1e-3)
    assert yaw == pytest.approx(expected, rel=0.2)


def test_crank_load_is_a_parameter_and_pedals_turn_freely():
    m = build_tricycle(crank_damping=3.0, crank_friction=0.5).model
    crank = m.joint("crank")
    assert m.dof_damping[crank.dofadr[0]] == 3.0 and m.dof_frictionloss[crank.dofadr[0]] == 0.5
    for side in "lr":
        pedal = m.joint(f"pedal_{side}")
        assert not pedal.limited[0] and pedal.stiffness[0] == 0
        sole_only = m.geom(f"pedal_{side}")  # touched by soles, nothing else: unilateral, no binding
        assert sole_only.contype[0] == 0 and sole_only.conaffinity[0] != 0


def test_kenshiro_model_matches_fig_3_31_and_its_planar_helpers():
    body = kenshiro.build_kenshiro(theta_c=0.3)
    assert KENSHIRO.d_th == pytest.approx(0.0151, abs=1e-4)  # Eq. 3.23
    hip = np.array([0.0, kenshiro.HIP_HEIGHT])
    crank = body.site_pos("crank_centre")[[0, 2]] - hip
    assert crank == pytest.approx([0.080, -0.605])
    rng = np.random.default_rng(0)
    for _ in range(5):
        q = rng.uniform([-1.2, 0.2, -0.5], [0.2, 2.0, 0.5])
        for name, value in zip(kenshiro.JOINTS, q):
            body.data.qpos[body.model.joint(f"l_{name}").qposadr[0]] = value
        body.forward()
        contact, psi = kenshiro.leg_fk(q)
        assert body.site_pos("l_contact")[[0, 2]] - hip == pytest.approx(contact, abs=1e-9)
        assert kenshiro.leg_ik(contact, psi) == pytest.approx(q, abs=1e-9)
    assert kenshiro.leg_ik([0.0, -1.0], 0.0) is None  # beyond L1 + L2


def test_kenshiro_sits_with_its_feet_on_the_pedals():
    body = kenshiro.build_kenshiro()
    for side in "lr":
        assert body.site_pos(f"{side}_contact") == pytest.approx(body.site_pos(f"pedal_{side}_top"), abs=1e-9)
    for _ in range(round(1.0 / body.dt)):
        body.step()
    snap = body.snapshot()
    assert abs(snap["q:crank"]) < 0.01
    for side in "lr":
        assert body.contact_force(f"{side}_foot")[2] > 5.0
        assert f"{side}_foot_force" in snap and f"{side}_foot_torque" in snap
