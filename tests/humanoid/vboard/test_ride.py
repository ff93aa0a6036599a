"""The V-BOARD riding rig (seed 000 §6.2, Table 6.1, Eqs. 6.3, 6.5, 6.7) and its scenarios' smoke runs."""

import math

import numpy as np
import pytest

from shintai.core.constants import GRAVITY
from shintai.core.recorder import Recorder
from shintai.core.runtime import Loop
from shintai.humanoid.balance.scooter import ScooterSensors
from shintai.humanoid.constants import V_PERIOD, VO_LATENCY
from shintai.humanoid.vboard.ride import VboardRide
from shintai.humanoid.vboard.vehicle import scooter_velocity
from shintai.scenarios.registry import ParameterError, get

DT = 0.004


def ride_response(inc: float, seconds: float = 0.6):
    """Level 3 (zero gains) standing on the pads; ``inc`` rad per tick added to u_v for 0.1 s from t = 0.5 s."""
    r = VboardRide(level=3, lift=False, noise=False, excite=lambda t: ((inc if 0.5 <= t < 0.6 else 0.0), 0.0))
    loop = Loop(r.body, stages=r.stages, channels=r.channels)
    loop.run(seconds)
    s = r.signals(r.body.snapshot())
    return r, np.array([s["theta_R"], s["theta_L"], s["true_v"], s["x"]])


def test_a_foot_pitch_increment_tilts_the_boards_and_drives_the_scooter_its_way():
    """Eq. 6.5/6.7: u_v > 0 pitches both soles toes-down, the boards follow and the scooter goes forward (Eq. A.1);
    u_v < 0 the other way, symmetrically."""
    _, base = ride_response(0.0)
    r, fwd = ride_response(2e-4)
    _, back = ride_response(-2e-4)
    assert r.foot_pitch.theta == pytest.approx([25 * 2e-4] * 2)  # 25 ticks of increments integrated
    d_fwd, d_back = fwd - base, back - base
    assert d_fwd[0] > 0.05 * math.pi / 180 and d_fwd[1] > 0.05 * math.pi / 180  # both boards tilt forward
    assert d_fwd[2] > 0.01 and d_fwd[3] > 0.0  # faster and further forward
    np.testing.assert_allclose(d_back, -d_fwd, rtol=0.1, atol=1e-4)


def test_level3_governor_output_is_mixed_and_integrated_into_the_soles():
    """The SpeedGovernor's PID (fixed gains, e = 0 − v) writes Eq. 6.5's increments [u_v + u_ω, u_v − u_ω];
    FootPitch sums them (Eq. 6.7) onto the soles' pitch (additive foot_damping channel, beside δ)."""
    gains = ((2e-3, 1e-3, 0.0), (1e-3, 0.0, 0.0))
    r = VboardRide(level=3, lift=False, noise=False, gains=gains)
    rec = Recorder()
    loop = Loop(r.body, stages=r.stages, channels=r.channels, recorder=rec)
    total = np.zeros(2)
    for _ in range(100):
        loop.step()
        total += loop.command["foot_pitch"]
    np.testing.assert_allclose(r.foot_pitch.theta, total, atol=1e-15)
    u_v, u_w = rec.values("speed_governor.u_v"), rec.values("speed_governor.u_omega")
    assert np.abs(u_v).max() > 0 and np.abs(u_w).max() > 0
    np.testing.assert_allclose(total, [np.sum(u_v + u_w), np.sum(u_v - u_w)], atol=1e-15)
    e_v = rec.values("speed_governor.e_v")
    np.testing.assert_allclose(e_v, -rec.values("sensors.v"))  # v_d = 0: stand still (§6.4.1)
    np.testing.assert_allclose(r.governor.pid["v"].gains, gains[0])  # learn=False keeps them


class FakeBody:
    def __init__(self):
        self.x = 0.0

    def site_pos(self, name):
        assert name == "head_camera"
        return np.array([self.x, 0.0, 1.5])


def test_sensors_rates_and_latency():
    """Table 6.1: v is published every 24 ms, 24 ms late; x_VO sampled every 10 ms (+10 ms latency, chosen); ω is
    the gyro's yaw rate every 4 ms. The robot starts moving at 0.5 m/s at t = 0.2 s (seen by the VO only)."""
    body = FakeBody()
    sensors = ScooterSensors(body, scooter_velocity, noise=False)
    still = {"imu_quat": np.array([1.0, 0, 0, 0]), "imu_acc": np.array([0, 0, GRAVITY]),
             "vboard_vel": np.zeros(3), "vboard_heading": np.array([1.0, 0, 0]), "vboard_angvel": np.zeros(3)}
    vs, ws = [], []
    for k in range(700):
        t = round(k * DT, 9)
        body.x = max(0.0, 0.5 * (t - 0.2))
        out = sensors.update({**still, "t": t, "imu_gyro": np.array([0.0, 0.0, 0.1 * k])})
        vs.append(out["v"])
        ws.append(out["omega"])
    vs = np.array(vs)
    assert ws == pytest.approx([0.1 * k for k in range(700)])  # ω every tick, undelayed
    changes = np.flatnonzero(np.diff(vs) != 0.0) + 1
    assert len(changes) > 5 and np.all(changes % round(V_PERIOD / DT) == 0)  # v only on its 24 ms grid
    first = changes[0] * DT
    # the first moving VO frame (t = 0.21) arrives at 0.22; v is then published one 24 ms period later
    assert 0.21 + VO_LATENCY + V_PERIOD - 1e-9 <= first <= 0.21 + VO_LATENCY + 2 * V_PERIOD + 1e-9
    assert vs[-1] == pytest.approx(0.5, rel=0.1)  # Eq. 6.3 settles on the VO velocity


def test_lift_lowers_the_robot_and_lets_go_once_the_boards_carry_it():
    r = VboardRide(level=2)
    loop = Loop(r.body, stages=r.stages, channels=r.channels)
    loop.run(0.3)
    assert not r.lift.released and r.lift.force[2] > 100.0  # still hanging, soles above the pads
    loop.run(1.2)
    assert r.lift.released and 0.5 < r.lift.t_release < 1.5
    assert not r.fallen() and all(r.body.firmware.on.values())  # both contact switches on


def test_bad_parameters_are_one_clear_line():
    with pytest.raises(ValueError, match="level"):
        VboardRide(level=4)
    with pytest.raises(ValueError, match="theta_o_error_deg"):
        VboardRide(theta_o_error_deg=math.nan)
    with pytest.raises(ParameterError):
        get("humanoid.vboard-posture").resolve({"level": "3"})


@pytest.mark.parametrize("sid, keys", [
    ("humanoid.vboard-levels", ("drift_level2_m", "zmp_x_max_early_level1_mm")),
    ("humanoid.vboard-plant-id", ("K_v", "r2_v_board")),
    ("humanoid.vboard-posture", ("max_trunk_pitch_with_deg", "travel_ratio")),
])
def test_scenarios_smoke_runs_give_their_key_metrics_and_pictures(smoke, sid, keys):
    run = smoke(sid)
    for k in keys:
        assert k in run.result["metrics"] and np.isfinite(run.result["metrics"][k]), k
    assert any(p.suffix == ".png" for p in run.out.iterdir())
