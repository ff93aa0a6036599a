"""The tricycle's feet on the closed-form leg IK (issue 13 item 2): the same joints as the DLS IK they
used before on the riding postures, exact in the vehicle frame whatever the waist's pose, and the DLS
IK's answer kept where the closed form gives none inside the limits."""

import math

import mujoco
import numpy as np
import pytest

from shintai.humanoid.constants import DEG, HRP2_LINKS, THETA_C_INIT
from shintai.humanoid.robots.leg_ik import hip_point
from shintai.humanoid.tricycle import riding
from shintai.humanoid.tricycle.hrp2_limbs import SOLE_IN_VEHICLE, riding_limbs
from shintai.humanoid.tricycle.vehicle import pedal_position
from shintai.sim import ik

CRANK = [THETA_C_INIT + k * 30 * DEG for k in range(12)]  # the pedals all round the crank


@pytest.fixture(scope="module")
def seated():
    body = riding.build_riding(theta_c=THETA_C_INIT)
    return body, riding_limbs(body, "foot")


def _sole_in_vehicle(body, limb, q):
    """FK of the full qpos ``q``: the sole's (position, orientation) in the vehicle frame."""
    data = mujoco.MjData(body.model)
    data.qpos[:] = q
    mujoco.mj_kinematics(body.model, data)
    f = limb.frame
    waist_p, waist_r = data.xpos[f.waist], data.xmat[f.waist].reshape(3, 3)
    p_v, r_v = waist_p + waist_r @ f.offset, waist_r @ f.rot_in_waist
    site = data.site(limb.site)
    return r_v.T @ (site.xpos - p_v), r_v.T @ site.xmat.reshape(3, 3)


def test_feet_agree_with_the_dls_ik_on_the_riding_postures(seated):
    """All round the crank, both feet: the closed form meets ξ exactly; the DLS solution (from the seated
    command, as the feet used it) meets it within its tolerance and lies within ~4e-4 rad of it."""
    body, feet = seated
    for side, limb in feet.items():
        before = limb.fallbacks
        for theta in CRANK:
            xi = pedal_position(theta, side[0])
            exact, dls = limb.solve(xi), limb.dls_solve(xi)
            assert exact.ok and dls.ok and exact.residual == (0.0, 0.0)
            pos, rot = _sole_in_vehicle(body, limb, exact.q)
            assert pos == pytest.approx(xi, abs=1e-9)
            assert np.abs(rot - SOLE_IN_VEHICLE).max() < 1e-9
            pos_d, rot_d = _sole_in_vehicle(body, limb, dls.q)
            assert np.linalg.norm(pos_d - pos) <= 1e-4  # ik.solve's tol
            assert np.linalg.norm(ik.rotation_error(rot, rot_d)) <= 1e-3  # its rot_tol
            assert np.abs(exact.q[limb.qadr] - dls.q[limb.qadr]).max() < 1e-3
            others = np.setdiff1d(np.arange(body.model.nq), limb.qadr)
            assert np.array_equal(exact.q[others], body.data.qpos[others])  # only this leg moves
        assert limb.fallbacks == before  # every riding posture inside the closed form's answer


def test_the_closed_form_answer_does_not_depend_on_the_waist_pose():
    """ξ lives in the vehicle frame welded to the waist: moving and turning the whole robot (and the
    tricycle) leaves the feet's joint command unchanged, to rounding."""
    body = riding.build_riding(theta_c=THETA_C_INIT)
    limb = riding_limbs(body, "foot")["left"]
    xi = pedal_position(THETA_C_INIT + 100 * DEG, "l")
    q_here = limb.solve(xi).q[limb.qadr]
    for joint in ("root", "tricycle_root"):  # both free bodies: shift 0.3 m, turn 40° about z
        a = body.model.joint(joint).qposadr[0]
        body.data.qpos[a:a + 3] += [0.3, -0.2, 0.0]
        quat = body.data.qpos[a + 3:a + 7].copy()
        mujoco.mju_mulQuat(body.data.qpos[a + 3:a + 7], np.array([math.cos(0.35), 0.0, 0.0, math.sin(0.35)]), quat)
    body.forward()
    assert not np.allclose(limb.frame.pose()[0], 0.0)
    assert np.abs(limb.solve(xi).q[limb.qadr] - q_here).max() < 1e-12


def test_the_dls_ik_decides_where_the_closed_form_has_no_answer(seated):
    """Just beyond the leg's reach (2e-5 m) the closed form says no, but the DLS IK meets ξ within its
    1e-4 m tolerance: the foot is still commanded there, as before (a fallback). A centimetre beyond,
    neither reaches: Eq. 3.14 holds the previous command and counts the tick."""
    body, feet = seated
    limb = feet["right"]
    f = limb.frame
    xi = pedal_position(THETA_C_INIT, "r")
    rot = f.pose()[1] @ SOLE_IN_VEHICLE
    sole = f.to_world(xi)
    ankle = sole + rot[:, 2] * HRP2_LINKS.ankle_height
    hip = hip_point("r", body.data.xpos[f.waist], body.data.xmat[f.waist].reshape(3, 3))
    away = (ankle - hip) / np.linalg.norm(ankle - hip)
    stretch = HRP2_LINKS.thigh + HRP2_LINKS.shank - np.linalg.norm(ankle - hip)  # to the straight knee

    before = limb.fallbacks
    near = f.to_vehicle(sole + (stretch + 2e-5) * away)
    result = limb.solve(near)
    assert limb.fallbacks == before + 1 and result.ok and 1.9e-5 < result.residual[0] <= 1e-4

    far = f.to_vehicle(sole + (stretch + 1e-2) * away)
    held, unreachable = limb.q.copy(), limb.unreachable
    command = limb.command(far, body.snapshot())
    assert limb.fallbacks == before + 2 and limb.unreachable == unreachable + 1
    assert list(command.values()) == pytest.approx(held)
