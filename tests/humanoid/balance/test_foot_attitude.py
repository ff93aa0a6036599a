"""Eq. 6.1's foot attitude and the two-foot measured ZMP on the hrp2 model."""

import math

import mujoco
import numpy as np
import pytest

from shintai.humanoid.balance.foot_attitude import (
    CONTACT_FZ,
    feet_attitude,
    measured_zmp,
    pitch,
    quat_to_rot,
    two_foot_zmp,
)
from shintai.humanoid.robots.hrp2 import build_hrp2
from shintai.humanoid.robots.leg_ik import JOINT_NAMES


def test_eq_6_1_gives_the_true_foot_attitude_of_a_tilted_robot():
    body = build_hrp2()
    model, data = body.model, body.data
    rng = np.random.default_rng(61)
    for _ in range(10):
        quat = rng.normal(size=4)
        data.qpos[3:7] = quat / np.linalg.norm(quat)  # any pelvis attitude: the IMU sees it through the chest
        for name in ("waist_yaw", "waist_pitch") + tuple(f"{s}_{j}" for s in "lr" for j in JOINT_NAMES):
            data.qpos[model.joint(name).qposadr[0]] = rng.uniform(-0.5, 0.5)
        mujoco.mj_forward(model, data)
        feet = feet_attitude(body.snapshot())
        for s in "lr":
            assert np.allclose(feet[s], body.site_xmat(f"{s}_sole"), atol=1e-9)


def test_pitch_is_the_rpy_pitch_toe_down_positive():
    for theta in (-0.3, -0.0312, 0.0, 0.2):
        c, s = math.cos(theta), math.sin(theta)
        ry = np.array([[c, 0, s], [0, 1, 0], [-s, 0, c]])
        assert pitch(ry) == pytest.approx(theta, abs=1e-15)
        yawed = quat_to_rot([math.cos(0.4), 0, 0, math.sin(0.4)]) @ ry  # a yawed foot keeps its pitch
        assert pitch(yawed) == pytest.approx(theta, abs=1e-15)
    assert np.allclose(ry @ [1, 0, 0], [c, 0, -s])  # + pitch: the toe goes down


def test_two_foot_zmp_formula_on_known_wrenches():
    # a foot pressing 300 N at (0.1, 0.05) on z0 = 0, its sensor 0.07 m above: the torque about the
    # sensor of a pure vertical force through (0.1, 0.05) seen from s = (0.08, 0.06, 0.07)
    point, f = np.array([0.1, 0.05, 0.0]), np.array([10.0, -5.0, 300.0])  # with some shear
    s = np.array([0.08, 0.06, 0.07])
    tau = np.cross(point - s, f)
    zmp = two_foot_zmp({"l": (s, f, tau)})
    assert np.allclose(zmp.zmp, point[:2], atol=1e-15) and zmp.contacts == ("l",)
    # the other foot at (0.1, −0.15) with 100 N: the ZMP is the force-weighted mean
    s2, f2 = np.array([0.1, -0.16, 0.07]), np.array([0.0, 0.0, 100.0])
    both = two_foot_zmp({"l": (s, f, tau), "r": (s2, f2, np.cross([0.1, -0.15, 0.0] - s2, f2))})
    assert np.allclose(both.zmp, (0.1, (0.05 * 300 - 0.15 * 100) / 400), atol=1e-15) and both.fz == 400.0
    # a foot under the contact threshold does not count; no contact at all gives NaN
    light = two_foot_zmp({"l": (s, f, tau), "r": (s2, [0, 0, CONTACT_FZ], [0, 0, 0])})
    assert light.contacts == ("l",) and np.allclose(light.zmp, point[:2])
    assert np.all(np.isnan(two_foot_zmp({"r": (s2, [0, 0, 1.0], [0, 0, 0])}).zmp))


def test_standing_model_zmp_lies_under_its_com():
    body = build_hrp2()
    for _ in range(1250):  # 5 s: the sway of the servoed posture has died out
        body.step()
    snap = body.snapshot()
    zmp = measured_zmp(body, snap)
    model, data = body.model, body.data
    mujoco.mj_comPos(model, data)
    com = data.subtree_com[model.body("waist").id]
    assert zmp.contacts == ("l", "r")
    assert zmp.fz == pytest.approx(model.body_subtreemass[model.body("waist").id] * 9.81, rel=2e-3)
    assert np.abs(zmp.zmp - com[:2]).max() < 3e-3
    # the same point as the floor's contact forces give (the F/T conventions are right)
    num, fz, c6 = np.zeros(2), 0.0, np.zeros(6)
    for i in range(data.ncon):
        mujoco.mj_contactForce(model, data, i, c6)
        normal_z = abs(data.contact[i].frame[2] * c6[0])  # floor contacts: the normal is ±z
        num += data.contact[i].pos[:2] * normal_z
        fz += normal_z
    assert np.abs(zmp.zmp - num / fz).max() < 2e-4


def test_bad_inputs_raise_value_error():
    with pytest.raises(ValueError, match="quaternion"):
        quat_to_rot([0, 0, 0, 0])
    with pytest.raises(ValueError, match="non-finite"):
        two_foot_zmp({"l": ([0, 0, math.nan], [0, 0, 100], [0, 0, 0])})
    with pytest.raises(ValueError, match="contact_fz"):
        two_foot_zmp({}, contact_fz=-1.0)
