"""The Ninebot One S2 of seed 000 App. A.1.3 (Eqs. A.5–A.9), the trajectory plant of §7.3.3 (Eqs. 7.3–7.5) and the
``humanoid.unicycle-*`` scenarios, short."""

import math

import mujoco
import numpy as np
import pytest

from shintai.core.constants import GRAVITY
from shintai.humanoid.constants import CONTROL_PERIOD, HRP2_MASS, SCENE, SOLE
from shintai.humanoid.learning.speed_governing import SpeedPlant
from shintai.humanoid.unicycle.constants import T_TRAJ
from shintai.humanoid.unicycle.ride import K_TRAJ, MLC_TRAJ, ModifiedStabilizer, TrajectoryCorrection
from shintai.humanoid.unicycle.vehicle import (
    NINEBOT,
    NinebotSpec,
    add_ninebot,
    install_firmware,
    pitch_moment,
    wheel_rate,
    wheel_velocity,
    zmp_velocity,
)
from shintai.scenarios.registry import ParameterError, get
from shintai.sim.body import MujocoBody
from shintai.sim.spec import scene_spec


def test_zmp_to_speed_law_eqs_a5_a9():
    n = NINEBOT
    W = HRP2_MASS * GRAVITY
    assert n.rider_weight == pytest.approx(W)
    p, p0 = 0.06, 0.01
    M = pitch_moment(p, p0)
    assert M == pytest.approx(W * (p - p0))  # A.5
    assert wheel_rate(M) == pytest.approx(n.k * M)  # A.6
    assert wheel_velocity(2.0) == pytest.approx(n.wheel_radius * 2.0)  # A.7
    v = zmp_velocity(p, p0)
    assert v == pytest.approx(n.wheel_radius * n.k * W * (p - p0))  # A.8
    assert n.wheel_radius * n.k * W == pytest.approx(n.K0)  # A.9: K0 = r k W
    assert zmp_velocity(0.06) == pytest.approx(0.3)  # the chosen K0: 60 mm ahead rides at 0.3 m/s
    # A.9 is linear: a change of p^{d**} changes v by K0 times it, whatever p0 (p0 constant)
    assert zmp_velocity(p + 0.01, p0) - v == pytest.approx(n.K0 * 0.01)
    with pytest.raises(ValueError, match="K0"):
        NinebotSpec(K0=float("nan"))


def test_model_rides_at_eq_a8_speed_under_a_static_load():
    """Two 10 kg blocks standing 50 mm ahead of the axle, one on each footboard: the unicycle settles at
    v = r k W (p − p0) with W their weight (Eq. A.8 on the firmware's measured moment), within 3 %."""
    spec = scene_spec("ninebot-load", *SCENE)
    add_ninebot(spec, spec.worldbody, training_wheels=True)
    m, x = 10.0, 0.05
    for side, s in (("l", 1.0), ("r", -1.0)):
        block = spec.worldbody.add_body(name=f"load_{side}", pos=[x, s * NINEBOT.board_y, NINEBOT.board_height + 0.05])
        block.add_freejoint()
        block.add_geom(type=mujoco.mjtGeom.mjGEOM_BOX, size=[0.04, 0.04, 0.05], mass=m, contype=SOLE, conaffinity=0,
                       friction=[1.5, 0.005, 0.0001])
    body = MujocoBody(spec.compile(), substeps=round(CONTROL_PERIOD / spec.option.timestep))
    fw = install_firmware(body)
    for _ in range(round(2.0 / CONTROL_PERIOD)):
        body.step()
    d = body.data
    v = float(d.sensor("ninebot_vel").data @ d.sensor("ninebot_heading").data)
    R = d.body("ninebot").xmat.reshape(3, 3)
    rel = np.mean([(R.T @ (d.body(f"load_{s}").xpos - d.body("ninebot").xpos))[0] for s in "lr"])
    expected = NINEBOT.wheel_radius * NINEBOT.k * 2 * m * GRAVITY * rel
    assert rel == pytest.approx(x, abs=0.01)
    assert v == pytest.approx(expected, rel=0.03)
    assert fw.moment == pytest.approx(2 * m * GRAVITY * rel, rel=0.03)
    assert abs(float(d.sensor("ninebot_roll").data[0])) < 0.01  # the training wheels hold the roll


def test_trajectory_plant_eqs_7_3_to_7_5():
    """c of TrajectoryCorrection (Eq. 7.3: ċ = LPF_T{u/Δt}) times K0 is P_traj(s) u = K_traj/(s(1+T s)) u (Eq. 7.5),
    the form of Eq. 6.13: a step u and a sine u against SpeedPlant(K_traj, T_traj)."""
    assert K_TRAJ == pytest.approx(NINEBOT.K0 / CONTROL_PERIOD) and MLC_TRAJ.K == K_TRAJ and MLC_TRAJ.T == T_TRAJ
    for u_of in (lambda k: 1e-5, lambda k: 1e-5 * math.sin(2 * math.pi * k * CONTROL_PERIOD)):
        traj = TrajectoryCorrection(start=lambda s: True, learn=False)
        plant = SpeedPlant(K_TRAJ, T_TRAJ)
        got, want = [], []
        for k in range(500):
            got.append(NINEBOT.K0 * traj.output(u_of(k))["zmp_mod"])
            want.append(plant.step(u_of(k)))
        err = np.max(np.abs(np.array(got) - want)) / np.max(np.abs(want))
        assert err < 0.03, err  # the two discretisations of the same 1/(s(1+Ts)) (4 ms of 50 ms)
    # at steady ramp: c grows by u per tick (Eq. 7.3 with the filter settled: p^{d**}(t) − p^{d**}(t−Δt) = u)
    traj = TrajectoryCorrection(start=lambda s: True, learn=False)
    cs = [traj.output(2e-5)["zmp_mod"] for _ in range(500)]
    assert cs[-1] - cs[-2] == pytest.approx(2e-5, rel=1e-6)


def test_modified_stabilizer_adds_c_to_p_d_star():
    """'after_lip': p^{d**} = p^{d*} + c exactly (Eq. 7.2); the bad placement is one error line."""
    from shintai.humanoid.unicycle.ride import build_ninebot_stand

    body = build_ninebot_stand()
    for _ in range(25):  # the soles take the load (the F/T sensors' ZMP exists: the LIP tracking is on)
        body.step()
    snap = body.snapshot()
    snap.update({"com_ref": np.array([0.01, 0.0, 0.8]), "zmp_ref": np.array([0.0, 0.0]), "support": 0.0,
                 "sole_ref": np.array([[0.0, 0.1, 0.14], [0.0, -0.1, 0.14]])})
    outs = []
    for c in (0.0, 0.02):
        st = ModifiedStabilizer(body, "after_lip")
        st.reset(snap)
        out = st.update(dict(snap, zmp_mod=c))
        assert np.all(np.isfinite(out["zmp_act"]))
        outs.append(out["zmp_d"])
    assert outs[1][0] - outs[0][0] == pytest.approx(0.02, abs=1e-12) and outs[1][1] == pytest.approx(outs[0][1])
    with pytest.raises(ValueError, match="^placement must be"):
        ModifiedStabilizer(body, "before")


def test_lip_tracking_reverses_a_static_correction_of_p_d_star():
    """Why ``humanoid.unicycle-learning``'s as-written variant runs away (its notes): at rest (p = x, ẋ = 0) the LIP law
    p* = p_ref + k1 (x_ref − x) + k3 (p_ref − p) + c with p* = x has x = c / (1 + k1 + k3), of the opposite sign for
    hrpsys's gains, while shifting both references by c ('reference') gives x = c."""
    from shintai.humanoid.constants import LIP_K

    k1, _, k3 = LIP_K
    c = 0.01
    x_after = c / (1 + k1 + k3)
    assert x_after == pytest.approx(c + k1 * (0 - x_after) + k3 * (0 - x_after))  # the equilibrium
    assert x_after < 0 and x_after == pytest.approx(-2.3 * c, rel=0.02)
    x_ref = c  # references shifted by c: p* = c + k1 (c − x) + k3 (c − x) = x at x = c
    assert c + k1 * (c - x_ref) + k3 * (c - x_ref) == pytest.approx(x_ref)


def test_a_short_ride_without_learning_stays_up_and_slow(smoke):
    """The smoke run of humanoid.unicycle-no-learning: it rides the whole duration, upright and slow."""
    out = smoke("humanoid.unicycle-no-learning").result
    assert "error" not in out, out.get("error")
    m, duration = out["metrics"], out["params"]["duration_s"]
    assert m["fallen"] == 0 and m["speed_diverged"] == 0 and m["max_abs_v_mps"] < 0.1
    assert duration <= m["ride_s"] < duration + 0.1


def test_one_mini_batch_of_learning_updates_both_gain_sets(smoke):
    """The smoke run of humanoid.unicycle-learning, 2.05 s: one mini-batch (every 2 s) of C_traj and C_v, in both
    placements of the correction."""
    run = smoke("humanoid.unicycle-learning")
    assert "error" not in run.result, run.result.get("error")
    m = run.result["metrics"]
    for v in ("as_written", "reference"):
        assert m[f"traj_batches_{v}"] == 1 and m[f"v_batches_{v}"] == 1 and m[f"fallen_{v}"] == 0
        assert m[f"traj_K_P_{v}"] + m[f"traj_K_I_{v}"] + m[f"traj_K_D_{v}"] > 0
    assert (run.out / "fig7_9_7_10.png").exists()


def test_a_bad_placement_is_a_one_line_parameter_error():
    with pytest.raises(ParameterError) as info:
        get("humanoid.unicycle-free").resolve({"placement": "x"})
    assert "\n" not in str(info.value)
