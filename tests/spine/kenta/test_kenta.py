"""Kenta's whole body (seed 003 §3.7) and its two scenarios, run short: the taught postures (Fig. 4.1) and the
tracking loops (Figs. 5.12, 5.14)."""

import math

import mujoco
import numpy as np
import pytest

from shintai.core.constants import KGF_N
from shintai.scenarios.experiment import Rig, run_rig
from shintai.scenarios.registry import ParameterError, get
from shintai.spine.control import SETPOINTS
from shintai.spine.geometry import uniform_posture
from shintai.spine.inverse_model import jacobian_integration
from shintai.spine.kenta.body import KentaBody
from shintai.spine.kenta.constants import TEACHER_GROUP
from shintai.spine.kenta.postures import locked_hold
from shintai.spine.kenta.statics import (
    critical_disc_stiffness,
    lock_reels,
    muscle_span,
    unstretched_bend,
    upright_margin,
    upright_stiffness,
)
from shintai.spine.kenta.tracking import SWUNG, kenta_tracking
from shintai.spine.robots import KENTA, KENTA_DISC_NM_RAD, KENTA_NECK_JOINTS, PINV_RCOND
from shintai.spine.tracking_loops import (
    TRACKING_PERIODS_S,
    ArmSwing,
    GazeLoop,
    concurrent_fraction,
    image_offset,
    measured_period,
    shares,
    tracking_metrics,
    tracking_series,
    tracking_signals,
)


@pytest.fixture(scope="module")
def body():
    return KentaBody()


def test_kenta_body_has_spine_arms_neck_and_eyes(body):
    m = body.model
    assert KENTA.m == 40 and KENTA.n == 10
    for name in ("HIP-BL1", "SHO-FR5", "LIG10-5", "neck_pan", "neck_tilt"):
        assert mujoco.mj_name2id(m, mujoco.mjtObj.mjOBJ_TENDON, name) >= 0
    for name in ("chest_yaw_L", "shoulder_pitch_R", "elbow_pitch_L", "wrist_roll_R", "eye_pan", "eye_tilt"):
        assert mujoco.mj_name2id(m, mujoco.mjtObj.mjOBJ_ACTUATOR, name) >= 0
    assert mujoco.mj_name2id(m, mujoco.mjtObj.mjOBJ_CAMERA, "eye_L") >= 0


def test_neck_wire_is_the_sum_of_the_joint_angles(body):
    """A wire through guides changes length by offset × Σ angles: the pan tendon's length is Σ yaw."""
    q = body.data.qpos
    for i in range(1, KENTA_NECK_JOINTS + 1):
        q[body.model.jnt_qposadr[body.id("joint", f"neck{i}_yaw")]] = 0.01 * i
    body.forward()
    pan = mujoco.mj_name2id(body.model, mujoco.mjtObj.mjOBJ_TENDON, "neck_pan")
    assert body.data.ten_length[pan] == pytest.approx(0.15)
    assert body.gaze()[1, 0] == pytest.approx(0.15)
    body.reset()


def test_teacher_hands_switch_with_the_shape_channel(body):
    body.apply({"shape": np.zeros(3 * KENTA.n)})
    assert not body.model.opt.disableactuator & (1 << TEACHER_GROUP)
    body.apply({})
    assert body.model.opt.disableactuator & (1 << TEACHER_GROUP)


def test_image_offset_signs():
    eye, R = np.zeros(3), np.array([[0, 0, -1], [-1, 0, 0], [0, 1, 0]], dtype=float)  # looks along +x
    (h, v), seen = image_offset(eye, R, [1.0, 0.2, -0.1])
    assert seen and h == pytest.approx(math.atan2(0.2, 1.0)) and v == pytest.approx(math.atan2(-0.1, 1.0))
    assert not image_offset(eye, R, [-1.0, 0.0, 0.0])[1]


def test_gaze_loop_integrates_the_offset_and_keeps_its_period():
    loop = GazeLoop("eyes", 0.033, 0.5, ("eye_pan", "eye_tilt"), +1.0, 0.3)
    loop.reset({"t": 0.0})
    for k in range(3):
        out = loop.update({"t": 0.033 * k, "target_image": np.array([0.1, -0.2])})
    assert out["eye_pan"] == pytest.approx(0.15) and out["eye_tilt"] == pytest.approx(-0.3)  # clipped at 0.3
    assert measured_period(loop.times) == pytest.approx(0.033)
    assert shares(np.array([[[1.0, 0], [3.0, 0]]])) == pytest.approx([0.25, 0.75])


def test_tracking_loops_short_run():
    """Kenta's three loops run at their three periods in one Loop and keep the ball in view over 0.25 s."""
    body, stages, run = kenta_tracking(("eyes", "neck", "spine"), 0.3, 8.0, zeroing_s=0.2, arm_swing_rad=0.5,
                                       arm_period_s=0.5)
    rig = Rig(body, stages=stages, channels=SETPOINTS, duration=0.25, record={10: lambda s: tracking_signals(s, run)})
    log = run_rig(rig).log
    m = tracking_metrics(log, run, 0.25, 0.3, SWUNG)
    assert m["arm_following_error_deg"] < 10.0 and m["arm_swing_deg"] > 5.0 and "arms_period_s" not in m
    for name in ("eyes", "neck", "spine"):
        assert abs(m[f"{name}_period_s"] - TRACKING_PERIODS_S[name]) < 1e-6
    assert m["eyes_period_s"] < m["neck_period_s"] < m["spine_period_s"]
    assert m["visible_fraction"] == 1.0 and m["rms_tracking_error_deg"] < 15.0
    assert tracking_series(log, run)["gaze"].shape[1:] == (3, 2)
    assert sum(m[f"{n}_share"] for n in ("eyes", "neck", "spine")) == pytest.approx(1.0)


def test_length_estimate_ill_conditioned_off_straight():
    """Why Kenta's spine-loop estimate runs away (notes/tracking-loops.md): J_m (40 × 30) has rank 24 at the
    basic posture, but 0.2° off it one of the six lost directions comes back with a singular value ≈ 1e-4 of the
    largest — above PINV_RCOND, so eq. 4.27's J_m⁺ keeps it: 0.01 mm of length error along it moves a joint by
    degrees in one step (along the largest direction: 0.0003°), and the step leaves q(θ) off by more than the
    error was."""
    model = KENTA.model
    assert muscle_span(model, np.zeros(3 * model.n))["rank"] == 24
    prev = np.radians(0.2) * np.random.default_rng(0).uniform(-1, 1, 3 * model.n)
    U, s, _ = np.linalg.svd(model.jacobian_fd(prev))
    assert 1e-5 < s[24] / s[0] < 1e-3 and s[25] / s[0] < PINV_RCOND
    steps = []
    for u in (U[:, 24], U[:, 0]):
        r = jacobian_integration(model, model.lengths(prev) + 1e-5 * u, theta0=prev)
        steps.append(np.degrees(np.abs(r.theta - prev).max()))
    assert steps[0] > 1.0 and steps[1] < 1e-3
    assert r.length_residual_m < 1e-6  # the well-conditioned step lands on q
    assert jacobian_integration(model, model.lengths(prev) + 1e-5 * U[:, 24], theta0=prev).length_residual_m > 1e-5


def test_taught_postures_short_run(smoke):
    """Three postures taught and replayed once (the smoke run): every metric computed, the picture written."""
    run = smoke("spine.kenta-taught-postures")
    result = run.result
    assert "error" not in result
    m = result["metrics"]
    assert all(math.isfinite(m[f"posture_{k}_error_deg"]) for k in (1, 2, 3))
    assert 0.0 <= m["nearest_taught_fraction"] <= 1.0
    assert m["cycle_period_s"] == pytest.approx(3 * result["params"]["period_s"])  # three postures a cycle
    assert (run.out / "replay.png").exists()
    assert m["muscle_rank"] == 24 and m["balanced_tension_exists"] == 0.0 and m["locked_taut_muscles"] <= 40


def test_bad_settings_are_one_clear_error():
    with pytest.raises(ParameterError):
        get("spine.tracking-loops").resolve({"robots": "bebe"})
    with pytest.raises(ParameterError):
        get("spine.kenta-taught-postures").resolve({"move_s": "3", "period_s": "2"})


def test_kenta_muscles_cannot_hold_every_direction():
    """§3.7.2's routing (muscles only to the blocks and vertebrae 2, 4, 6, 8): J_m has rank 24 of 30, no strictly
    positive tension set balances, and a forward bend exists that lengthens no muscle — what holds it is only
    the discs and ligaments ('復元力を持つ脊椎なので筋の本数が足りなくても姿勢は定まる')."""
    attached = {link for path in KENTA.model.muscles.paths for link, _ in path}
    assert attached == {0, 2, 4, 6, 8, 10}
    theta = uniform_posture(np.radians([0.0, 21.0, 0.0]), KENTA.n)
    span = muscle_span(KENTA.model, theta)
    assert span["rank"] == 24 and not span["balanced"] and len(span["unresisted"]) > 30
    rate, motion = unstretched_bend(KENTA.model, theta)
    assert rate > 1.0 and np.all(KENTA.model.jacobian(theta) @ motion <= 1e-9)


def test_locked_reels_hold_only_with_stiff_discs():
    """With every reel locked (a stiff two-sided stop, slip < 0.05 mm) a taught forward bend sinks with 3 N m/rad
    discs (our old choice) and holds with KENTA's (2 × k*, robots.KENTA_DISC_NM_RAD): the discs, not the lock,
    decide."""
    soft = locked_hold(1.0, 0.8, 0.4, zeroing_s=0.2, disc_nm_rad=3.0)
    stiff = locked_hold(1.0, 0.8, 0.4, zeroing_s=0.2)
    assert soft["locked_end_pitch_deg"] - soft["locked_taught_pitch_deg"] > 20.0 and soft["muscle_rank"] == 24
    assert abs(stiff["locked_end_pitch_deg"] - stiff["locked_taught_pitch_deg"]) < 5.0


def test_upright_is_stable_with_kentas_discs():
    """The criterion behind KENTA_DISC_NM_RAD (seed 003 §7.1.1 "直立した姿勢を基本姿勢とすると…基本姿勢に向かう場合に
    …復元力が生じる", §4.6.2: all muscles at one tension leave only the discs' restoring force): upright, under
    gravity with every muscle at 1 kgf, is stable (the stiffness about it positive definite) with KENTA's discs
    and unstable with half of k*; the chosen value keeps the factor 2 over k*, and slack muscles need less."""
    b = KentaBody()
    k_star = critical_disc_stiffness(b, KGF_N, tol_nm_rad=1.0)
    assert KENTA.disc.k_bend_nm_rad == KENTA.disc.k_twist_nm_rad == KENTA_DISC_NM_RAD >= 2 * k_star - 1.0
    assert upright_margin(b, KGF_N, KENTA_DISC_NM_RAD) > 0.0 > upright_margin(b, KGF_N, 0.5 * k_star)
    assert upright_margin(b, KGF_N, k_star - 1.0) < 0.0 < upright_margin(b, KGF_N, k_star + 1.0)
    assert upright_margin(b, 0.0, 0.5 * k_star) > upright_margin(b, KGF_N, 0.5 * k_star)
    K, names = upright_stiffness(b, KGF_N, 0.0)
    assert np.allclose(K, K.T) and len(names) == 3 * KENTA.n + 20 + 15 + 2  # spine, arms, neck, eyes


def test_lock_reels_is_a_stiff_lock():
    """lock_reels: two-sided stops at the present winding, stiff and the motors off."""
    b = KentaBody()
    lock_reels(b)
    j = b.id("joint", f"{KENTA.muscle_names[0]}:reel")
    lo, hi = b.model.jnt_range[j]
    assert hi - lo <= 2.1e-6 and b.model.jnt_solref[j][0] <= 1e-3


def test_arm_swing_and_concurrency():
    """Fig. 5.13's arms: antiphase shoulders, elbows bent with them; a part counts as moving in a window when one
    of its angles spans more than the threshold there."""
    swing = ArmSwing(0.5, 2.0)
    q = swing.at(0.5)
    assert q["shoulder_pitch_L"] == pytest.approx(0.5) and q["shoulder_pitch_R"] == pytest.approx(-0.5)
    assert q["elbow_pitch_L"] == q["elbow_pitch_R"] == pytest.approx(0.25)
    t = np.arange(0.0, 2.0, 0.01)
    moving, still = np.sin(2 * np.pi * t), np.zeros_like(t)
    assert concurrent_fraction(t, [moving, np.c_[still, moving]], 0.5, 0.1) == 1.0
    assert concurrent_fraction(t, [moving, still], 0.5, 0.1) == 0.0


def test_kenta_export_lengths_are_eq_4_25():
    """The MuJoCo export puts every muscle where the geometric model does (no wrong sign or vertebra): without the
    interference sphere its path lengths equal eq. 4.25 at random postures."""
    from shintai.spine.bodies_mujoco import SpineBody
    from shintai.spine.robots import KENTA_LIGAMENTS

    b = SpineBody(KENTA, loads=(), interference=False, ligaments=KENTA_LIGAMENTS)
    for theta in np.random.default_rng(0).uniform(-0.17, 0.17, (10, 3 * KENTA.n)):
        b.set_theta(theta)
        assert np.abs(b.path_lengths() - KENTA.model.lengths(theta)).max() < 1e-9
