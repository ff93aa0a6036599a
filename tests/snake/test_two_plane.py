"""Two-plane locomotion of seed 001 ch. 4 (§4.1–§4.5): partition, models against finite differences, the
null-space term, the plant, and short runs of the §4.5 scenarios."""

import math

import numpy as np
import pytest

from shintai.core.runtime import ChannelError, FunctionModule, Loop
from shintai.scenarios.experiment import variant_metric
from shintai.snake import model3d as K
from shintai.snake import two_plane as TP
from shintai.snake import two_plane_runs as S
from shintai.snake.two_plane_plant import TwoPlaneSnake
from shintai.snake.constants import CH4_ROBOT, CONDITION_1, CONDITION_2, TWO_PLANE, TWO_PLANE_SCENE, TwoPlaneSettings

L, N, RW = CH4_ROBOT.l, CH4_ROBOT.n, TWO_PLANE.r_w
H, TOL = 1e-6, 1e-6


def fd(f, x, h=H):
    x = np.asarray(x, float)
    cols = []
    for k in range(len(x)):
        d = np.zeros(len(x))
        d[k] = h
        cols.append((np.asarray(f(x + d)) - np.asarray(f(x - d))) / (2 * h))
    return np.stack(cols, axis=-1)


@pytest.fixture(scope="module")
def world():
    return TP.TwoPlaneWorld.build(CONDITION_1, TWO_PLANE_SCENE, RW)


def straddling_state(world, part, seed=0):
    """A posture of ``part`` whose rear end properly touches the rear plane, front part at ^f y = 0."""
    rng = np.random.default_rng(seed)
    psi = np.zeros(17)
    psi[part.front_yaw] = rng.uniform(-0.5, 0.5, part.n_f)
    psi[part.rear_yaw] = rng.uniform(-0.4, 0.4, len(part.rear_yaw))
    c = part.connection
    psi[c] = np.r_[-0.15, np.zeros(len(c) - 1)]
    psi[c[2]], psi[c[-1]] = 0.8, -0.5  # arch over the edge, steep down, level out
    w_f = np.array([world.edge_x + 0.05 + 2 * L * part.n_f, 0.02, math.pi + rng.uniform(-0.2, 0.2)])
    return w_f, TP.settle_connection(world, part, w_f, psi, L, RW)


# --------------------------------------------------------------------------------------- partition (§4.1)

def test_partition_indices_follow_fig_4_3():
    p = TP.Partition(9, 2, 2)  # wheels 1–2 front, 3–4 lifted, 5–9 rear
    assert p.n_re == 5 and p.n_r == 5
    assert list(p.front_yaw + 1) == [1, 3]  # φ_f: yaw joints 1, 3
    assert list(p.connection + 1) == [4, 5, 6, 7, 8, 9, 10] and len(p.connection) == 2 * (p.n_c + 1) + 1  # m_c
    assert list(p.rear_yaw + 1) == [11, 13, 15, 17]  # φ_r ∈ R^{n_r−1}
    assert list(p.contact) == [TP.FRONT] * 2 + [TP.LIFTED] * 2 + [TP.REAR] * 5
    assert TP.Partition.from_contact(p.contact) == p
    # every joint is an input of exactly one part, except the zero pitch joints inside the plane parts
    inputs = np.r_[p.front_yaw, p.connection, p.rear_yaw]
    assert len(set(inputs)) == len(inputs) and set(range(17)) - set(inputs) == {1, 11, 13, 15}


def test_transition_sequence_after_the_head_transition():
    """Spec §3.2 [derived]: n_h = 3 gives n_f = 1, n_c = 1, n_re = 3; the rear end shifts at once (n_c < 2)."""
    p = TP.Partition(9, 1, TWO_PLANE.n_h - 2)
    assert (p.n_f, p.n_c, p.n_re) == (1, 1, 3)
    p = p.rear_shift()
    assert (p.n_f, p.n_c, p.n_re, len(p.connection)) == (1, 2, 4, 7)
    p = p.front_shift()
    assert (p.n_f, p.n_c, p.n_re) == (2, 1, 4)  # …and the rear-end condition holds again


def test_rear_end_at_the_tail_and_release():
    p = TP.Partition(9, 6, 2)
    assert p.n_re == 9 and len(p.connection) == 6 and len(p.rear_yaw) == 0  # no pitch joint at the tail tip
    released = p.front_shift().rear_shift()  # n_c = 1 < n_c_max with no wheel behind: the tail is lifted
    assert released.released and released.n_re is None and released.n_r == 0
    assert list(released.connection_wheels) == [8, 9] and list(released.connection + 1) == [14, 15, 16, 17]
    assert list(released.contact) == [TP.FRONT] * 7 + [TP.LIFTED] * 2
    done = released.front_shift().front_shift()
    assert done.n_f == 9 and len(done.connection) == 0 and (done.contact == TP.FRONT).all()
    with pytest.raises(ValueError, match="already left"):
        released.rear_shift()


def test_bad_contact_patterns_are_rejected():
    for c in ([0, 1, 2, 2, 2, 2, 2, 2, 2], [1, 2, 0, 2, 2, 2, 2, 2, 2], [1, 0, 2, 2, 0, 2, 2, 2, 2]):
        with pytest.raises(ValueError, match="FRONT…, LIFTED…, REAR…"):
            TP.Partition.from_contact(c)


# ------------------------------------------------------------------------------------------------- world

def test_world_geometry_hand_computed():
    """Condition 2 (pitch −0.0609): edge line, signed d_e, edge distance; Σ_f embedding round trip."""
    w = TP.TwoPlaneWorld.build(CONDITION_2, TWO_PLANE_SCENE, RW)
    a = 0.0609
    edge_x = 0.593 + TWO_PLANE_SCENE.edge_x * math.cos(a)  # R_y(−a) [edge_x, 0, 0] = edge_x [cos a, 0, sin a]
    assert w.d_e([edge_x - 0.05, 0.3, 0.2]) == pytest.approx(0.05)
    assert w.d_e([edge_x + 0.02, -0.4, 0.0]) == pytest.approx(-0.02)
    assert w.rear_edge_x == pytest.approx(edge_x - TWO_PLANE_SCENE.gap)
    corner = w.p_f + w.R_f @ [w.edge_x, 0.3, 0.0]
    normal = w.R_f[:, 2]
    dist = w.edge_distance(np.array([corner + 0.04 * normal, corner - 0.01 * w.R_f[:, 0] + 0.03 * normal,
                                     corner + 0.02 * w.R_f[:, 0] - 0.005 * normal]))
    assert np.allclose(dist, [0.04, math.hypot(0.01, 0.03), -0.005])  # last one inside the front block
    w_f = np.array([0.3, -0.2, 2.5])
    p_h, R_h = w.embed(w_f)
    assert np.allclose(w.planar(p_h, R_h), w_f)
    assert K.contact_relation(p_h, R_h, w.front) == pytest.approx([RW, 0.0, 0.0], abs=1e-12)
    G = w.head_map
    twist_fd = fd(lambda q: np.r_[w.embed(q)[0], K.euler_zyx(w.embed(q)[1])], w_f)
    assert np.abs(K.head_euler_map(K.euler_zyx(R_h)) @ twist_fd - G).max() <= TOL


# ------------------------------------------------------------------------------- models (§4.3) against FD

@pytest.mark.parametrize("part", [TP.Partition(9, 1, 2), TP.Partition(9, 3, 2), TP.Partition(9, 6, 2)])
def test_straddle_jacobians_match_finite_differences(world, part):
    """J_{r,1..3} (4.5) and J_{c,1..3} (4.11) against central differences of the 3D forward kinematics."""
    w_f, psi = straddling_state(world, part, seed=part.n_f)
    m = TP.straddle_model(world, part, w_f, psi, L)
    i = part.n_re

    def rear_pose(w, p):
        ch = K.forward_kinematics(*world.embed(w), p, L)
        return K.planar_pose(ch, 2 * i, ch.wheel_link(i))

    def r(w, p):
        ch = K.forward_kinematics(*world.embed(w), p, L)
        return K.contact_relation(ch.wheel_position(i), ch.wheel_frame(i), world.rear)[: len(m.r)]

    assert np.abs(m.Jr_h - fd(lambda w: rear_pose(w, psi), w_f)).max() <= TOL
    assert np.abs(m.Jr_psi - fd(lambda p: rear_pose(w_f, p), psi)).max() <= TOL
    assert np.abs(m.Jc_h - fd(lambda w: r(w, psi), w_f)).max() <= TOL
    assert np.abs(m.Jc_psi - fd(lambda p: r(w_f, p), psi)).max() <= TOL
    assert np.allclose(m.r, [RW, 0.0, 0.0][: len(m.r)], atol=1e-12)  # the settled posture
    assert len(m.r) == (2 if i == N else 3)  # a lone tail wheel: r = [d, κ]
    assert m.A_p().shape == (part.n_f + part.n_r, 3)


def test_plane_part_model_means_no_side_slip(world):
    """(4.9): A_p ^f ẇ̃_h − B_p ψ̇ = lateral speeds (2.6) of the front wheels, then of the rear wheels n_re..n,
    from finite differences of the forward kinematics (rear part properly on the rear plane)."""
    part = TP.Partition(9, 3, 2)
    w_f, psi = straddling_state(world, part, seed=3)
    rng = np.random.default_rng(5)
    w_dot = rng.normal(size=3)
    psi_dot = np.zeros(17)
    for idx in (part.front_yaw, part.connection, part.rear_yaw):
        psi_dot[idx] = rng.normal(size=len(idx))
    wheels = list(range(1, part.n_f + 1)) + list(range(part.n_re, N + 1))

    def positions(s):
        ch = K.forward_kinematics(*world.embed(w_f + s[0] * w_dot), psi + s[0] * psi_dot, L)
        return np.concatenate([ch.wheel_position(i) for i in wheels])

    rates = fd(positions, [0.0])[:, 0].reshape(-1, 3)
    ch = K.forward_kinematics(*world.embed(w_f), psi, L)
    lateral = [-(ch.wheel_frame(i)[:, 1] @ v) for i, v in zip(wheels, rates)]
    m = TP.straddle_model(world, part, w_f, psi, L)
    assert np.abs(m.A_p() @ w_dot - m.B_p() @ psi_dot - lateral).max() <= TOL


def test_head_part_jacobian_matches_finite_differences_with_the_base_fixed(world):
    """J_h of (4.1): r_1 = [d_1,f, κ_1,f, λ'_1,f] against FD of the head part with wheel n_h (and the base) fixed."""
    p_h, R_h, psi = TP.initial_posture(world)
    ch = K.forward_kinematics(p_h, R_h, psi, L)
    n_h = TWO_PLANE.n_h
    anchor = ch.wheel_position(n_h), ch.wheel_frame(n_h)

    def r_1(head):
        p = psi.copy()
        p[: 2 * n_h] = head
        return TP.head_relation(K.chain_from_wheel(p, L, n_h, *anchor), world)

    J_h = TP.head_part_jacobian(ch, world, n_h)
    assert J_h.shape == (3, 2 * n_h)
    assert np.abs(J_h - fd(r_1, psi[: 2 * n_h])).max() <= TOL


# ------------------------------------------------------------------------------- null space (§4.4.2)

def test_objective_gradient_matches_finite_differences(world):
    part = TP.Partition(9, 2, 2)
    w_f, psi = straddling_state(world, part, seed=7)
    m = TP.straddle_model(world, part, w_f, psi, L)
    V, eta = TP.objective(m, CONDITION_1, CH4_ROBOT.joint_limit)

    def V_of(x):
        p = psi.copy()
        p[part.connection] = x
        return TP.objective(TP.straddle_model(world, part, w_f, p, L), CONDITION_1, CH4_ROBOT.joint_limit)[0]

    assert V == pytest.approx(V_of(psi[part.connection]))
    assert np.abs(eta - fd(V_of, psi[part.connection])).max() <= TOL
    assert len(eta) == 2 * (part.n_c + 1) + 1  # η has m_c entries, not n_c (A22)


@pytest.mark.parametrize("shifting_front", [False, True])
def test_null_space_term_leaves_every_controlled_variable_alone(world, shifting_front):
    """u_{c2} = k_v (I − H_3^† H_3) η (4.19)/(4.29) changes no controlled rate: the head (through (4.9)), ṙ (4.11),
    ψ̇_{c,1} while shifting, the (4.6) row; and it does not decrease V (4.32)."""
    part = TP.Partition(9, 2, 2)
    w_f, psi = straddling_state(world, part, seed=11)
    m = TP.straddle_model(world, part, w_f, psi, L)
    w_d, w_d_dot = w_f + [0.01, -0.02, 0.05], np.array([0.01, 0.015, 0.0])
    args = (m, w_f, w_d, w_d_dot, CONDITION_1, RW, CH4_ROBOT.joint_limit)
    on, off = (TP.straddle_input(*args, k_v, shifting_front) for k_v in (CONDITION_1.k_v, 0.0))
    delta = on.psi_dot - off.psi_dot
    assert np.abs(delta[part.connection]).max() > 1e-3  # the term does something…
    assert abs(m.Jc_psi @ delta).max() < 1e-12  # …but not to r
    assert abs(m.D_psi @ delta).max() < 1e-12  # …nor to the rear front-end wheel's no-slip row
    if shifting_front:
        assert abs(delta[part.connection[0]]) < 1e-12
    head = [np.linalg.lstsq(m.A_p(), m.B_p() @ s.psi_dot, rcond=None)[0] for s in (on, off)]
    assert np.allclose(head[0], head[1], atol=1e-12) and np.allclose(head[0], on.xi, atol=1e-9)  # (4.23)–(4.24)
    _, eta = TP.objective(m, CONDITION_1, CH4_ROBOT.joint_limit)
    assert eta @ delta[part.connection] >= 0.0  # k_v η(I − H^†H)η ≥ 0


# ------------------------------------------------------------------------------------------------- plant

def test_plant_follows_the_model_without_slip_and_rk4_is_converged(world):
    """A consistent straddling input: no residual slip, and 4 RK4 steps per δt agree with 40 to 1e−6 m."""
    part = TP.Partition(9, 3, 2)
    w_f, psi = straddling_state(world, part, seed=13)
    m = TP.straddle_model(world, part, w_f, psi, L)
    step = TP.straddle_input(m, w_f, w_f + [0.02, 0.03, 0.1], [0.01, 0.02, 0.0], CONDITION_1, RW,
                             CH4_ROBOT.joint_limit, CONDITION_1.k_v, False)
    bodies = []
    for rk4 in (4, 40):
        body = TwoPlaneSnake(world, *world.embed(w_f), psi, part.contact, settings=TwoPlaneSettings(rk4_steps=rk4))
        body.apply({"psi_dot": step.psi_dot, "contact": part.contact.astype(float)})
        body.step()
        bodies.append(body)
    assert bodies[0].slip < 1e-12
    assert np.abs(bodies[0].ch.P - bodies[1].ch.P).max() < 1e-6
    assert bodies[0].t == TWO_PLANE.dt


def test_head_transition_moves_only_the_head_part(world):
    p_h, R_h, psi = TP.initial_posture(world)
    body = TwoPlaneSnake(world, p_h, R_h, psi, TP.head_raised_contact(N, TWO_PLANE.n_h))
    before = body.ch.P.copy()
    u, _ = TP.head_input(body.ch, world, TWO_PLANE.n_h, TWO_PLANE.k_h)
    body.apply({"psi_dot": u, "contact": TP.head_raised_contact(N, TWO_PLANE.n_h).astype(float)})
    body.step()
    assert np.abs(body.ch.P[2 * TWO_PLANE.n_h:] - before[2 * TWO_PLANE.n_h:]).max() < 1e-12  # base still
    assert np.abs(body.ch.P[:2 * TWO_PLANE.n_h] - before[:2 * TWO_PLANE.n_h]).max() > 1e-4


def test_plant_rejects_bad_commands(world):
    p_h, R_h, psi = TP.initial_posture(world)
    body = TwoPlaneSnake(world, p_h, R_h, psi, TP.head_raised_contact(N, 3))
    with pytest.raises(ChannelError, match="undeclared channel 'phi_dot'"):
        Loop(body, [FunctionModule(lambda s: {"phi_dot": np.zeros(9)})]).step()
    with pytest.raises(ValueError, match="psi_dot"):
        body.apply({"psi_dot": np.zeros(9)})


# ------------------------------------------------------------------------------------------- short runs

@pytest.fixture(scope="module")
def short_run():
    return S.simulate_two_plane(CONDITION_1, 20.0)


def test_short_run_head_transition_then_first_landing(short_run):
    """§4.5 condition 1 for 20 s: r_1 → [r_w, 0, 0], straddling starts, the rear end shifts, wheel 2 lands."""
    run = short_run
    kinds = [e[1] for e in run.events]
    assert kinds == ["head_done", "rear_shift", "front_shift_start", "front_shift", "rear_shift"]
    t1, r1 = run.c["r1"]
    assert run.t_0 < 10.0 and np.abs(r1[-1] - [RW, 0.0, 0.0]).max() < TWO_PLANE.eps_1
    assert abs(r1[0][2]) > 0.1  # it started tilted (TwoPlaneScene.head_offset)
    assert run.shift_order_ok()
    m = run.metrics()
    assert m["head_error_after_transient_m"] < 0.005 and m["contact_d_error_max_m"] < 0.002
    assert m["max_abs_tilt_rad"] < 0.02 and m["min_edge_clearance_m"] > 0.0
    assert m["max_slip_m_s"] < 1e-12 and m["landing_margin_min_m"] > 0.0  # wheel 2 landed on the plane
    assert m["max_connection_wheels"] == TWO_PLANE.n_c_max


def test_scenario_writes_metrics_checks_and_pictures(smoke):
    run = smoke("snake.two-plane-pitch")  # 18 s, with and without the null space
    out, result = run.out, run.result
    assert "error" not in result and result["sim_time_s"] == pytest.approx(36.0)
    m = result["metrics"]
    assert m["min_edge_clearance_m"] > m["min_edge_clearance_no_nullspace_m"]
    assert m["front_shifts"] == 1 and m["all_wheels_on_front"] == 0
    checks = {c["name"]: c["ok"] for c in result["checks"]}
    assert not checks["all_wheels_on_front"] and checks["max_abs_joint_rad"] and checks["head_error_after_transient_m"]
    for png in ("motion", "contact", "head", "redundancy", "edge", "motion_no_null_space"):
        assert (out / f"{png}.png").stat().st_size > 10_000
    assert result["thesis"]["table_4_1"]["where"] == "seed 001 Table 4.1"


def test_suffix_keeps_the_unit_last():
    assert variant_metric("min_edge_clearance_m", "no_nullspace") == "min_edge_clearance_no_nullspace_m"
    assert variant_metric("max_slip_m_s", "no_nullspace") == "max_slip_no_nullspace_m_s"
    assert variant_metric("all_wheels_on_front", "no_nullspace") == "all_wheels_on_front_no_nullspace"
