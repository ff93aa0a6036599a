"""The load monitor of seed 000 Fig. 7.16: model A (reference waist pose and servo targets) against model B
(measured joints, waist attitude) coincides when the robot is at its reference and separates the hands when
an arm joint is off its target; the force/torque sample and the before/after windows."""

import mujoco
import numpy as np
import pytest

from shintai.humanoid.tricycle.ch4_riding import Rider, build_ch4
from shintai.humanoid.tricycle.constants import BEFORE_S
from shintai.humanoid.tricycle.load_monitor import LoadMonitor, fig4_3_metrics, recovery_windows, window_means


@pytest.fixture(scope="module")
def seated():
    body = build_ch4((), hip="contact", crank_motor=False)
    rider = Rider(body)
    monitor = LoadMonitor(body, rider)
    body.data.ctrl[:] = body.data.qpos[monitor.servo_qadr]  # every servo at its measured angle
    mujoco.mj_forward(body.model, body.data)
    return body, monitor


def test_models_coincide_at_reference_and_separate_when_off(seated):
    body, monitor = seated
    ab = monitor.models({})
    assert ab["hand_ab"] < 1e-9 and ab["waist_ab"] < 1e-9 and ab["waist_ab_rad"] < 1e-9
    adr = body.model.joint("l_shoulder_pitch").qposadr[0]
    body.data.qpos[adr] += 0.1
    mujoco.mj_forward(body.model, body.data)
    off = monitor.models({})
    body.data.qpos[adr] -= 0.1
    mujoco.mj_forward(body.model, body.data)
    # one hand ≈ 0.1 rad × the shoulder-to-grasp distance away; the mean of the two hands is half of it
    assert 0.01 < off["hand_ab"] < 0.05
    # the feet are aligned, so an arm joint moves neither waist
    assert off["waist_ab"] < 1e-9
    # a pure translation of A's waist (the hip lift) moves its feet with it: nothing to see at aligned feet;
    # a chest roll (Eq. 4.9) turns A's waist against B's, and with it the waist relative to the feet
    assert monitor.models({"ref:hip_lift": 0.02})["waist_ab"] < 1e-9
    rolled = monitor.models({"ref:chest_roll": 0.05})
    assert rolled["waist_ab_rad"] == pytest.approx(0.05, abs=1e-6) and rolled["waist_ab"] > 0.01


def test_sample_and_windows(seated):
    body, monitor = seated
    sample = monitor.sample(body.snapshot())
    assert sample["force_norm"] >= sample["hand_force_norm"] >= 0.0 and np.isfinite(sample["torque_norm"])
    t = np.arange(0.0, 10.0, 0.1)
    recovering = (t >= 4.0) & (t < 6.0)
    (b0, b1), (a0, a1) = recovery_windows(t, recovering)
    assert (b0, b1) == pytest.approx((2.0, 4.0)) and (a0, a1) == pytest.approx((7.0, 9.0))
    assert recovery_windows(t, np.zeros_like(t, bool)) is None
    means = window_means(t, {"x": t}, 2.0, 4.0)
    assert means["x"] == pytest.approx(2.95)


def test_fig4_3_reads_the_most_loaded_servo_before_the_first_recovery():
    """Fig. 4.3's metrics (load_monitor.fig4_3_metrics) on a made-up log: the window before the first recovery
    picks the servo with the largest mean |τ|, ranks the wrist rolls, and signs the CoM's side."""
    joints = ("l_knee_pitch", "l_wrist_roll", "r_wrist_roll")
    t = np.arange(0.0, 10.0, 0.1)
    recovering = (t >= 6.0) & (t < 7.0)
    loads = np.where((t < 6.0)[:, None], [1.0, 5.0, 2.0], [9.0, 0.0, 0.0])  # the wrist leads before, the knee after

    class Log:
        def times(self, name):
            return t

        def values(self, name):
            return {"load.joint_loads": loads, "load.joint_errors": np.tile([3.0, 1.0, 0.5], (len(t), 1)),
                    "load.com_y": np.full(len(t), 0.03)}[name]

    m = fig4_3_metrics(Log(), recovering, joints)
    assert m["most_loaded_joint_before"] == "l_wrist_roll" and m["most_loaded_is_wrist_roll_before"] == 1
    assert m["wrist_roll_rank_before"] == 1 and m["largest_error_joint_before"] == "l_knee_pitch"
    assert m["wrist_roll_error_rank_before"] == 2
    assert m["com_y_before_m"] == pytest.approx(0.03) and BEFORE_S < 6.0
