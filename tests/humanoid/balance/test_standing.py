"""The standing stack (humanoid.stabilizer, humanoid.standing): Kajita 2010's LIP tracking, its ZMP
distributor, the foot damping of Eqs. 5.1–5.3 in the loop, standing, pushes and steps in place."""

import math

import numpy as np
import pytest

from shintai.core.runtime import FunctionModule
from shintai.humanoid.balance.foot_attitude import measured_zmp, two_foot_zmp
from shintai.humanoid.balance.preview import hrp2_com_height
from shintai.humanoid.balance.stabilizer import (StabilizerModule, closed_loop_poles, distribute, foot_wrenches,
    lip_feedback)
from shintai.humanoid.balance.standing import (PLATFORM_HEIGHT, FootstepModule, SoleStep, Standing, platform_body,
    platform_steps, push_recovery, swing_point)
from shintai.humanoid.constants import BOARDING_CROUCH, BOARDING_STEP_X, LIP_K, SWING_DELAY, VBOARD
from shintai.humanoid.robots.hrp2 import ft_reaction

FEET = {"l": np.array([0.0, 0.06]), "r": np.array([0.0, -0.06])}
FOOT_X = (-0.105, 0.135)  # the sole box in x (centre 15 mm ahead of the sole point, 240 mm long)
FOOT_Y = 0.138  # |y| of the soles' outer edges: 60 mm + 10 mm outward + 68 mm half width


def _zmp_of(dist, points):
    """The ZMP of the distributed wrenches (two_foot_zmp takes reactions: +f_z, torque = −exerted)."""
    wrenches = {s: (np.array([*points[s], 0.0]), np.array([0.0, 0.0, dist.fz[s]]),
                    np.array([-dist.tau_d[s][0], -dist.tau_d[s][1], 0.0])) for s in points}
    return two_foot_zmp(wrenches, contact_fz=0.0).zmp


@pytest.mark.parametrize("zmp", [(0.0, 0.0), (0.03, 0.02), (-0.05, 0.05), (0.01, -0.09)])
def test_distributor_double_support_sums_to_the_weight_with_its_zmp_at_the_reference(zmp):
    dist = distribute(np.array(zmp), FEET, "lr", 554.0)
    assert dist.fz["l"] + dist.fz["r"] == pytest.approx(554.0)
    assert np.allclose(_zmp_of(dist, FEET), zmp, atol=1e-12)
    # the share follows the ZMP along the segment between the feet, clipped to [0, 1]
    assert dist.alpha == pytest.approx(min(1.0, max(0.0, (zmp[1] + 0.06) / 0.12)))


@pytest.mark.parametrize("stance", ["l", "r"])
def test_distributor_single_support_puts_everything_on_the_stance_foot(stance):
    other = "r" if stance == "l" else "l"
    zmp = FEET[stance] + (0.02, -0.01)
    dist = distribute(zmp, FEET, stance, 554.0)
    assert dist.fz[stance] == pytest.approx(554.0) and dist.fz[other] == 0.0
    assert np.all(dist.tau_d[other] == 0.0)
    # exerted torque about the stance foot's point: (−d_y f, d_x f)
    assert np.allclose(dist.tau_d[stance], (0.01 * 554.0, 0.02 * 554.0))
    assert np.allclose(_zmp_of(dist, FEET), zmp)


def test_distributor_rejects_bad_input():
    with pytest.raises(ValueError, match="support"):
        distribute(np.zeros(2), FEET, "both", 554.0)
    with pytest.raises(ValueError, match="total_fz"):
        distribute(np.zeros(2), FEET, "lr", math.nan)


def test_lip_feedback_moves_the_zmp_ahead_of_a_com_that_is_ahead():
    # Eq. 26 with k1, k2 < 0: a CoM 10 mm ahead of its reference, moving forward → p_d ahead of p_ref
    p = lip_feedback((0.0, 0.0), (0.0, 0.0), (0.0, 0.0), (0.01, 0.0), (0.02, 0.0), (0.0, 0.0))
    assert p[0] == pytest.approx(-LIP_K[0] * 0.01 - LIP_K[1] * 0.02) and p[0] > 0.0 and p[1] == 0.0


def test_hrpsys_gains_are_stable_on_the_model_and_bad_gains_are_not():
    assert np.all(closed_loop_poles(LIP_K, hrp2_com_height()).real < 0)
    assert np.any(closed_loop_poles((0.5, 0.0, 0.0), hrp2_com_height()).real > 0)  # positive k1: falls
    with pytest.raises(ValueError, match="zc"):
        closed_loop_poles(LIP_K, -1.0)
    with pytest.raises(ValueError, match="k"):
        StabilizerModule(Standing().body, k=(1.0, math.nan, 0.0))


def test_swing_point_lifts_clear_before_moving_and_lands_on_the_step():
    a, b = np.array([0.0, 0.06, 0.0]), np.array([0.3, 0.06, 0.1])
    assert np.allclose(swing_point(a, b, 0.0), a) and np.allclose(swing_point(a, b, 1.0), b)
    mid = swing_point(a, b, 0.5)
    assert mid[2] == pytest.approx(0.15) and mid[0] == pytest.approx(0.15)
    assert swing_point(a, b, SWING_DELAY)[0] == pytest.approx(0.0)  # no forward motion before SWING_DELAY
    assert swing_point(a, b, SWING_DELAY)[2] > 0.1 + 0.02  # by then 2 cm above the step's top
    assert swing_point(b, a, 1 - SWING_DELAY)[2] > 0.1 + 0.02  # stepping down: over the edge before descending
    deck = np.array([0.3, 0.1175, VBOARD.deck_height])
    assert swing_point(a, deck, SWING_DELAY)[2] > VBOARD.deck_height + 0.02
    assert swing_point(b, a, 1 - SWING_DELAY)[0] == pytest.approx(0.0)


@pytest.fixture(scope="module")
def standing():
    """5 s standing still on the stack, every tick's CoM (relative to ref) and measured ZMP."""
    st = Standing(hold=5.0)
    log = []

    def rec(snap):
        c = st.loop.command
        log.append((snap["t"], st.com(), np.asarray(c["com_ref"]).copy(), np.asarray(c["zmp_act"]).copy()))

    st.run(5.0, every={1: rec})
    return st, log


def test_standing_five_seconds_keeps_the_zmp_in_the_feet_and_the_com_on_its_reference(standing):
    st, log = standing
    assert not st.fallen() and st.ik.unreachable == 0
    t = np.array([r[0] for r in log])
    zmp = np.array([r[3] for r in log])[t > 0.1]  # the feet settle on the floor in the first ticks
    assert np.all(np.isfinite(zmp))
    assert np.all((zmp[:, 0] > FOOT_X[0]) & (zmp[:, 0] < FOOT_X[1])) and np.all(np.abs(zmp[:, 1]) < FOOT_Y)
    err = np.array([np.linalg.norm(r[1][:2] - r[2][:2]) for r in log])
    assert err[t > 1.0].max() < 0.004  # the 7.6 mm start offset (CoM vs the feet's midpoint) is gone in 1 s
    assert err[t > 3.0].max() < 0.0015


def test_measured_zmp_of_the_stabilizer_matches_foot_attitude_measured_zmp(standing):
    st, _ = standing
    snap = st.body.snapshot()
    w = foot_wrenches(st.body, snap)
    assert sum(x.fz for x in w.values()) == pytest.approx(st.stabilizer.weight, rel=0.02)
    ours = two_foot_zmp({s: (x.point, (0, 0, x.fz), (-x.tau[0], -x.tau[1], 0)) for s, x in w.items()}).zmp
    assert np.allclose(ours, measured_zmp(st.body, snap).zmp, atol=2e-3)  # horizontal forces ignored in ours
    for s in "lr":  # the float arithmetic of FootSensors is ft_reaction's, moved to the sole point and negated
        force, torque = ft_reaction(st.body, snap, f"{s}_ankle")
        lever = st.body.site_pos(f"{s}_ankle_ft") - st.body.site_pos(f"{s}_sole")
        assert w[s].fz == pytest.approx(force[2])
        assert np.allclose(w[s].tau, -(torque + np.cross(lever, force))[:2])


def test_a_push_is_recovered_by_the_stack_and_a_much_larger_one_is_not():
    ok = push_recovery((200.0, 0.0, 0.0))
    assert ok["recovered"] and ok["com_error_m"] < 0.01
    assert not push_recovery((600.0, 0.0, 0.0), settle=1.0)["recovered"]


@pytest.fixture(scope="module")
def stepping():
    """Two steps in place with and without the foot damping: ZMP tracking error against the plan."""
    out = {}
    for name, kw in (("stack", {}), ("no_damping", {"damping": False})):
        st = Standing(steps=[("l", 0.0, 0.06), ("r", 0.0, -0.06)], **kw)
        errs, com = [], []

        def rec(snap, st=st, errs=errs, com=com):
            c = st.loop.command
            errs.append(np.linalg.norm(np.asarray(c["zmp_act"]) - np.asarray(c["zmp_ref"])))
            com.append(np.linalg.norm(st.com()[:2] - np.asarray(c["com_ref"])[:2]))

        st.run(st.duration + 0.5, every={1: rec})
        out[name] = (st, np.array(errs), np.array(com))
    return out


def test_steps_in_place_end_standing_with_the_zmp_following_the_plan(stepping):
    st, zmp_err, com_err = stepping["stack"]
    assert not st.fallen() and st.ik.unreachable == 0
    assert np.sqrt(np.nanmean(zmp_err**2)) < 0.03  # measured ≈ 20 mm rms (the plan's ZMP jumps 60 mm)
    assert com_err.max() < 0.03
    for i, s in enumerate("lr"):  # both feet back down where they stood (world, within 2 cm)
        assert np.linalg.norm(st.body.site_pos(f"{s}_sole") - st.soles[s]) < 0.02


def test_without_the_foot_damping_the_zmp_follows_the_plan_measurably_worse(stepping):
    stack = np.sqrt(np.nanmean(stepping["stack"][1] ** 2))
    bare = np.sqrt(np.nanmean(stepping["no_damping"][1] ** 2))
    assert bare > 1.5 * stack


def test_footsteps_follow_the_plan_and_reject_a_mismatched_step_list():
    st = Standing(steps=[SoleStep("l", 0.1, 0.06)])
    fs = st.footsteps
    k_land = fs.runs[0][1]
    assert np.allclose(fs.soles_at(0), [st.soles["l"], st.soles["r"]])
    assert np.allclose(fs.soles_at(k_land)[0], (0.1, 0.06, 0.0)) and np.allclose(fs.soles_at(k_land)[1], st.soles["r"])
    with pytest.raises(ValueError, match="single-support"):
        FootstepModule(st.plan, st.soles, [])


def test_stance_heights_rise_only_after_the_lower_foot_has_lifted():
    st = Standing(steps=[SoleStep("l", 0.3, 0.06, 0.1), SoleStep("r", 0.3, -0.06, 0.1)])
    h, support = st.heights, st.plan.support
    # flat: only the soles' 0.5 mm settling into the floor (the steps land at z = 0)
    assert np.allclose(Standing(steps=[("l", 0.0, 0.06), ("r", 0.0, -0.06)]).heights, 0.0, atol=1e-3)
    second = [k for k, s in enumerate(support) if s == "l"]  # the right foot's swing (the left on the box)
    assert np.abs(h[:second[0]]).max() < 1e-9
    assert h[second[-1]] == pytest.approx(0.1, abs=1e-3) and h[-1] == pytest.approx(0.1, abs=1e-3)
    assert np.all(np.diff(h) >= 0) and np.abs(np.diff(h, 2)).max() / st.plan.dt**2 < 1.1  # ≤ ≈1 m/s²


def test_boarding_a_rigid_platform_left_foot_first_ends_standing_on_it():
    """Item 5 of the brief: the boarding's steps (§5.4, Fig. 5.6) on a rigid box of the V-BOARD's deck
    height (0.12 m), onto its pad positions (±0.1175 m)."""
    body = platform_body()
    assert body.model.geom("platform").size[2] == pytest.approx(VBOARD.deck_height / 2)
    steps = platform_steps({"l": (0.0, 0.06, 0.0), "r": (0.0, -0.06, 0.0)})
    assert [s.side for s in steps] == ["l", "r"] and all(s.z == pytest.approx(PLATFORM_HEIGHT) for s in steps)
    st = Standing(steps=steps, body=body, crouch=BOARDING_CROUCH)
    errs = []
    st.run(st.duration + 1.0, every={1: lambda snap: errs.append(
        np.linalg.norm(np.asarray(st.loop.command["zmp_act"]) - np.asarray(st.loop.command["zmp_ref"])))})
    assert not st.fallen() and st.ik.unreachable == 0
    for s, y in (("l", VBOARD.pad_y), ("r", -VBOARD.pad_y)):
        assert np.allclose(st.body.site_pos(f"{s}_sole"), (BOARDING_STEP_X, y, PLATFORM_HEIGHT), atol=0.01)
    errs = np.array(errs)
    assert np.sqrt(np.nanmean(errs[-250:] ** 2)) < 0.01  # settled on the box (measured ≈3 mm; no damping ≈38 mm)


def test_sign_convention_toe_down_raises_the_exerted_pitch_torque_so_eq_5_1_is_negative_feedback():
    """δ_pitch > 0 (toe down) moves the pressure forward: τ_pitch (exerted) rises, ∂τ/∂δ > 0 (likewise roll)."""

    def tau_after(delta):
        st = Standing(damping=False, lip=False, force_difference=False)
        push = FunctionModule(lambda snap: {"foot_damping": np.array(delta)}, name="delta")
        stages = [list(s) for s in st.loop.stages]
        stages[1].append(push)
        st.loop.restage(stages)
        st.run(0.5)
        return np.asarray(st.loop.command["tau_L"]).copy()

    base = tau_after([0.0, 0.0, 0.0, 0.0])
    assert tau_after([0.0, 0.01, 0.0, 0.0])[1] > base[1] + 1.0  # N·m
    assert tau_after([0.01, 0.0, 0.0, 0.0])[0] > base[0] + 1.0


def test_the_rig_rejects_bad_parameters():
    with pytest.raises(ValueError, match="crouch"):
        Standing(crouch=-0.01)
    with pytest.raises(ValueError, match="push duration"):
        Standing(push=((100.0, 0.0, 0.0), 0.5, -0.1))
    with pytest.raises(ValueError, match="force"):
        Standing(push=((math.nan, 0.0, 0.0), 0.5, 0.1))
    with pytest.raises(ValueError, match="side"):
        Standing(steps=[("x", 0.0, 0.0)])


def test_push_on_a_named_link_as_a_before_physics_hook():
    """Push on ``link`` (here "chest"), run before every physics step by body time: on over [t0, t0 + duration)."""
    from shintai.humanoid.balance.standing import Push
    from shintai.sim.body import MujocoBody

    body = MujocoBody("""<mujoco><option timestep="0.001" gravity="0 0 0"/><worldbody>
      <body name="waist"><freejoint/><geom type="box" size=".1 .1 .1" mass="1"/></body>
      <body name="chest" pos="1 0 0"><freejoint/><geom type="box" size=".1 .1 .1" mass="1"/></body>
      </worldbody></mujoco>""")
    body.before_physics.append(Push(body, (2.0, 0.0, 0.0), 0.01, 0.02, link="chest"))
    for _ in range(50):
        body.step()
    chest, waist = body.id("body", "chest"), body.id("body", "waist")
    assert body.data.qvel[0] == 0.0  # the waist is not pushed
    assert body.data.qvel[6] == pytest.approx(2.0 * 0.02, rel=0.06)  # impulse / mass, on for 20 steps
    assert not body.data.xfrc_applied[[chest, waist]].any()  # off again after t0 + duration
    with pytest.raises(ValueError, match="push: force"):
        Push(body, (1.0, math.nan, 0.0), 0.0, 0.1)


def test_the_leg_ik_module_commands_what_leg_ik_solves_for_its_references():
    """LegIKModule's compiled path (legs_upright, rot_xy_flat) gives the leg joints leg_ik gives for the waist under
    the CoM reference and the soles turned by δ and raised by the force difference, to the bit."""
    from shintai.core.geometry import rot_xy
    from shintai.humanoid.robots.leg_ik import JOINT_NAMES, leg_ik, rot_xy_flat

    for roll, pitch in ((0.0, 0.0), (0.03, -0.02), (-0.1, 0.2)):
        assert rot_xy_flat(roll, pitch) == tuple(rot_xy(roll, pitch).ravel().tolist())
    st = Standing()
    com_ref = st.body.data.subtree_com[st.body.id("body", "waist")] + np.array([0.01, -0.005, -0.01])
    soles = np.array([st.soles["l"], st.soles["r"]]) + np.array([[0.02, 0.0, 0.0], [-0.01, 0.0, 0.005]])
    delta, dz = np.array([0.02, -0.03, -0.01, 0.04]), np.array([0.003, -0.003])
    ctrl = st.ik.update({"com_ref": com_ref, "sole_ref": soles, "foot_damping": delta, "sole_dz": dz})["ctrl"]
    waist = com_ref - st.ik.com_offset
    for i, s in enumerate("lr"):
        res = leg_ik(s, waist, np.eye(3), soles[i] + (0.0, 0.0, dz[i]), rot_xy(delta[2 * i], delta[2 * i + 1]))
        assert res.reachable and np.array_equal(ctrl[[st.body.id("actuator", f"{s}_{j}") for j in JOINT_NAMES]], res.q)
    others = np.setdiff1d(np.arange(len(ctrl)), st.ik._legs)
    assert np.array_equal(ctrl[others], st.ik.ctrl0[others])
