"""The ch. 4 riding rig (seed 000 §4.3–4.4): hip–saddle contact, reference channels, the whole-body
rider on its reference model, the crank motor stand-in; short runs."""

import math

import numpy as np
import pytest

from shintai.core.geometry import roll_of

from shintai.core.runtime import ChannelError, FunctionModule, Loop
from shintai.humanoid.constants import DEG, TRICYCLE
from shintai.humanoid.tricycle import ch4_riding as cr
from shintai.humanoid.tricycle.navigation import crank_rate


def test_reference_channels_are_seen_one_tick_later_and_unknown_ones_rejected():
    """The ref:* channels are the loop's own, declared with a one-tick delay (0 before anything is
    written, and on a tick nobody writes them); an undeclared one is a ChannelError."""
    body = cr.build_ch4(hip="weld")
    seen = []
    writes = FunctionModule(lambda s: {"ref:theta_h": 0.1, "ref:com_shift": 0.02} if s["t"] < 0.002 else None,
                            name="writes")
    reads = FunctionModule(lambda s: seen.append((float(s["ref:theta_h"]), float(s["ref:com_shift"]),
                                                  float(s["ref:hip_lift"]))), name="reads")
    loop = Loop(body, [writes, reads], channels=cr.REF_CHANNELS)
    for _ in range(3):
        loop.step()
    assert seen == [(0.0, 0.0, 0.0), (0.1, 0.02, 0.0), (0.0, 0.0, 0.0)]
    assert "ref:theta_h" not in body.channels  # never sent to the body
    bad = Loop(body, [FunctionModule(lambda s: {"ref:nonsense": 1.0}, name="bad")], channels=cr.REF_CHANNELS)
    with pytest.raises(ChannelError):
        bad.step()


def test_roll_sign_convention():
    c, s = math.cos(0.1), math.sin(0.1)
    rx = np.array([[1, 0, 0], [0, c, -s], [0, s, c]])
    assert roll_of(rx) == pytest.approx(0.1)


def test_rider_waist_turns_about_the_hip_point():
    """Eq. 4.9: the reference waist turned by Δφ_C about the hip–saddle contact keeps the hip point."""
    body = cr.build_ch4(hip="contact")
    rider = cr.Rider(body)
    pos, rot = rider.waist_pose(0.1, 0.0, 0.0)
    hip_in_waist = rider.seat_rot.T @ (rider.hip_point - rider.seat_pos)
    assert pos + rot @ hip_in_waist == pytest.approx(rider.hip_point, abs=1e-12)
    assert roll_of(rot @ rider.seat_rot.T) == pytest.approx(0.1)
    pos2, _ = rider.waist_pose(0.0, 0.03, 0.02)
    assert pos2 - rider.seat_pos == pytest.approx([0.0, 0.03, 0.02])


def test_seated_robot_drives_and_steers_with_the_motor():
    """Sitting on the saddle contact (no weld), the motor turning the crank, the arms steering: the
    tricycle rolls D_c per revolution and turns at v tan θ_h / L (Eq. 4.15), the hip stays seated."""
    body = cr.build_ch4(hip="contact")
    rider = cr.Rider(body)
    refs = FunctionModule(lambda s: {"ref:crank_rate": crank_rate(0.3) if s["t"] > 0.5 else 0.0,
                                     "ref:theta_h": 0.2 if s["t"] > 2.0 else 0.0}, name="refs")
    loop = Loop(body, [refs, rider, cr.CrankMotor()], channels=cr.REF_CHANNELS)
    loop.run(3.5)
    crank0, x0 = body.data.joint("crank").qpos[0], cr.vehicle_pose2d(body)
    loop.run(2.0)
    crank1, x1 = body.data.joint("crank").qpos[0], cr.vehicle_pose2d(body)
    travel = np.hypot(*(x1[:2] - x0[:2]))
    assert travel == pytest.approx(TRICYCLE.travel_per_rev * (crank1 - crank0) / (2 * math.pi), rel=0.05)
    assert travel / 2.0 == pytest.approx(0.3, rel=0.1)
    yaw_rate = (x1[2] - x0[2]) / 2.0
    assert yaw_rate == pytest.approx(0.3 * math.tan(body.data.joint("handle").qpos[0]) / 1.2, rel=0.2)
    assert body.data.joint("handle").qpos[0] == pytest.approx(0.2, abs=2 * DEG)
    # still sitting: the saddle carries the weight less the feet's 2 × 150 N (≈250 N)
    assert body.contact_force("waist")[2] > 150.0
    assert rider.unreachable == 0


def test_freewheel_backpedalling_does_not_move_the_tricycle():
    """§4.4.3: turning the crank back provides no pedalling force (the hub freewheels); forward it drives."""
    body = cr.build_ch4(hip="weld")
    wheel = cr.Freewheel(body)
    rider = cr.Rider(body)
    rate = {"w": -0.8}
    loop = Loop(body, [FunctionModule(lambda s: {"ref:crank_rate": rate["w"]}, name="refs"), rider, cr.CrankMotor()],
                channels=cr.REF_CHANNELS)
    crank0, x0 = body.data.joint("crank").qpos[0], cr.vehicle_pose2d(body)[0]
    loop.run(2.0)
    assert body.data.joint("crank").qpos[0] < crank0 - 1.0  # the crank went back > 57°
    assert abs(cr.vehicle_pose2d(body)[0] - x0) < 0.02  # the tricycle stayed
    assert wheel.releases >= 1 and not wheel.engaged
    rate["w"] = 0.8
    loop.run(3.0)
    assert wheel.engaged
    assert cr.vehicle_pose2d(body)[0] - x0 > 0.5  # forward pedalling drives again


def test_grip_grasp_holds_both_bar_points():
    """grasp=grip: both point holds per hand are on and satisfied at the start; the hands stay on the grips."""
    body = cr.build_ch4(hip="contact", grasp="grip")
    m = body.model
    for s in ("l", "r"):
        assert body.data.eq_active[m.equality(f"hold_{s}_bar").id] and body.data.eq_active[m.equality(f"hold_{s}").id]
    for _ in range(50):
        body.step()
    for s in ("l", "r"):
        assert np.linalg.norm(body.site_pos(f"{s}_grasp") - body.site_pos(f"grip_{s}")) < 0.01


def test_seat_slip_builds_with_driving_and_restarts_after_lift(monkeypatch):
    """SeatSlip: grows only while the crank turns and the hip sits; zero and restarted once the hip lifts."""
    from shintai.humanoid.tricycle.ch4_drive import SeatSlip
    body = cr.build_ch4(hip="contact")
    seated = {"fz": 300.0}
    monkeypatch.setattr(body, "contact_force", lambda name: np.array([0.0, 0.0, seated["fz"]]))
    slip = SeatSlip(body, rate=10.0, f_max=100.0, start=0.0)
    dof = body.model.joint("crank").dofadr[0]
    slip({"t": 0.0})
    slip({"t": 1.0})
    assert slip.force == 0.0  # the crank stands: no driving, no slip
    body.data.qvel[dof] = 1.0
    slip({"t": 2.0})
    assert slip.force == pytest.approx(10.0)
    waist = body.id("body", "waist")
    assert body.data.xfrc_applied[waist, 1] == pytest.approx(10.0, rel=1e-6)  # +F along the vehicle's y
    seated["fz"] = 0.0  # STAND: the hip leaves the saddle
    slip({"t": 3.0})
    assert slip.force == 0.0 and slip.resets == 1
    seated["fz"] = 300.0
    slip({"t": 4.0})
    assert slip.force == pytest.approx(10.0)  # built up again from zero


def _seat_gaps(body, dy: float) -> dict:
    """Gap of each sit bone above the saddle with the robot moved ``dy`` sideways (no roll)."""
    import mujoco
    m, d = body.model, body.data
    adr = m.joint("root").qposadr[0]
    d.qpos[adr + 1] += dy
    mujoco.mj_forward(m, d)
    ft = np.zeros(6)
    return {s: mujoco.mj_geomDistance(m, d, m.geom(f"sit_bone_{s}").id, m.geom("saddle_seat").id, 0.2, ft)
            for s in ("l", "r")}


def test_hip_sits_on_both_sit_bones_on_a_crowned_saddle():
    """§4.3.1–4.3.2 (the seat model): both sit bones touch the crowned saddle in the riding pose, and
    a sideways slide of the hip without roll lifts the outer bone off the crown — to sit on both the
    pelvis must roll toward the slide, so the y translation shows as an x rotation."""
    from shintai.humanoid.constants import SADDLE_CROWN_RADIUS, SIT_BONE_Y
    body = cr.build_ch4(hip="contact")
    level = _seat_gaps(body, 0.0)
    assert all(abs(g) < 1e-3 for g in level.values())
    slid = _seat_gaps(body, 0.03)  # 3 cm to +y (left)
    assert slid["r"] < 1e-3 < slid["l"]
    # the roll that puts both bones down again is of the order of the crown geometry's d / R
    roll = math.atan2(slid["l"] - slid["r"], 2 * SIT_BONE_Y)
    assert 0.5 * 0.03 / SADDLE_CROWN_RADIUS < roll < 2 * 0.03 / SADDLE_CROWN_RADIUS
