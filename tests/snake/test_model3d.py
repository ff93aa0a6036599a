"""3D model of seed 001 ch. 2 (§2.1, §2.5, §2.6) against finite differences of the 3D forward kinematics."""

import math

import numpy as np
import pytest

from shintai.core.geometry import rot_y, rot_z
from shintai.snake import model as M
from shintai.snake import model3d as K

L = 0.0905
H = 1e-6  # central differences: truncation ~h², round-off ~eps/h
TOL = 1e-6  # the brief's bound for analytic vs. finite-difference Jacobians


def fd(f, x, h=H):
    """Central-difference Jacobian of f at x (columns = components of x)."""
    x = np.asarray(x, float)
    cols = []
    for k in range(len(x)):
        d = np.zeros(len(x))
        d[k] = h
        cols.append((np.asarray(f(x + d)) - np.asarray(f(x - d))) / (2 * h))
    return np.stack(cols, axis=-1)


def random_pose(rng, n=9, pitch=0.6):
    w_h = np.r_[rng.normal(size=3), rng.uniform(-0.5, 0.5), rng.uniform(-pitch, pitch), rng.uniform(-3, 3)]
    return w_h, rng.uniform(-1.0, 1.0, 2 * n - 1)


def flat_state(rng, n, n_h, n_last=None, r_w=0.029):
    """A state on the model's manifold: wheels n_h..n_last flat on z = r_w (base pitch joints 0)."""
    n_last = n if n_last is None else n_last
    psi = rng.uniform(-0.8, 0.8, 2 * n - 1)
    psi[2 * n_h + 1:2 * n_last - 1:2] = 0.0  # base pitch joints 2n_h+2, …, 2n_last−2 (0-based odd)
    ch = K.chain_from_wheel(psi, L, n_h, [rng.normal(), rng.normal(), r_w], rot_z(rng.uniform(-3, 3)))
    return ch.head_pose(), psi


def test_zero_pitch_chain_is_the_planar_model():
    """With a level head and all pitch joints 0 the 3D chain gives (2.3)–(2.5)."""
    rng = np.random.default_rng(0)
    phi = rng.uniform(-1, 1, 9)
    w = np.array([0.3, -0.2, 2.0])
    psi = np.zeros(17)
    psi[::2] = phi
    ch = K.chain_from_pose([w[0], w[1], 0.05, 0, 0, w[2]], psi, L)
    planar = M.wheel_poses(M.configuration(w, phi, L))
    for i in range(1, 10):
        pose = ch.wheel_pose(i)
        assert np.allclose(pose[:2], planar[i - 1, :2], atol=1e-12) and pose[2] == pytest.approx(0.05)
        assert math.remainder(pose[5] - planar[i - 1, 2], 2 * math.pi) == pytest.approx(0.0, abs=1e-12)
        assert abs(pose[3]) < 1e-12 and abs(pose[4]) < 1e-12
    assert np.allclose(ch.P[:, :2], M.body_points(M.configuration(w, phi, L)), atol=1e-12)


def test_links_have_length_l_and_euler_angles_round_trip():
    rng = np.random.default_rng(1)
    w_h, psi = random_pose(rng)
    ch = K.chain_from_pose(w_h, psi, L)
    assert np.allclose(np.linalg.norm(np.diff(ch.P, axis=0), axis=1), L)
    assert np.allclose(ch.head_pose(), w_h)
    for R in ch.R:
        assert np.allclose(K.rot_zyx(K.euler_zyx(R)), R, atol=1e-12)


@pytest.mark.parametrize("seed", range(3))
def test_wheel_pose_jacobians_match_finite_differences(seed):
    """∂w_i/∂w_h (through E(θ_h)) and ∂w_i/∂ψ of every wheel against central differences (≤ 1e−6)."""
    rng = np.random.default_rng(seed)
    w_h, psi = random_pose(rng)
    ch = K.chain_from_pose(w_h, psi, L)
    Mh = K.head_euler_map(w_h[3:])
    for i in range(1, 10):
        J_t, J_psi = K.wheel_pose_jacobian(ch, i)
        assert np.abs(J_t @ Mh - fd(lambda w: K.chain_from_pose(w, psi, L).wheel_pose(i), w_h)).max() <= TOL
        assert np.abs(J_psi - fd(lambda p: K.chain_from_pose(w_h, p, L).wheel_pose(i), psi)).max() <= TOL
    assert np.all(K.wheel_pose_jacobian(ch, 3)[1][:, 6:] == 0.0)  # wheel 3 moves with joints 1..6 only


def test_anchored_twist_map_keeps_the_anchor_still():
    """Head twist T_a·0 − T_ψ ψ̇ moves the joints with wheel 3 fixed (the head part of §4.3.1)."""
    rng = np.random.default_rng(3)
    w_h, psi = random_pose(rng)
    ch = K.chain_from_pose(w_h, psi, L)
    psi_dot = rng.normal(size=17)
    _, T_psi = K.anchored_twist_map(ch, 6, ch.wheel_link(3))
    twist = -T_psi @ psi_dot
    J_t, J_psi = K.pose_jacobian(ch, 6, ch.wheel_link(3))
    point_and_omega = np.r_[K.point_jacobian(ch, 6)[0] @ twist + K.point_jacobian(ch, 6)[1] @ psi_dot,
                            K.frame_jacobian(ch, 6)[0] @ twist + K.frame_jacobian(ch, 6)[1] @ psi_dot]
    assert np.abs(point_and_omega).max() < 1e-12
    assert np.abs(J_t @ twist + J_psi @ psi_dot).max() < 1e-12


def test_chain_from_wheel_places_that_wheel():
    rng = np.random.default_rng(4)
    psi = rng.uniform(-1, 1, 17)
    R = K.rot_zyx([0.1, -0.2, 1.0])
    ch = K.chain_from_wheel(psi, L, 4, [1.0, 2.0, 3.0], R)
    assert np.allclose(ch.wheel_position(4), [1, 2, 3]) and np.allclose(ch.wheel_frame(4), R)


# ------------------------------------------------------------------------------------ wheel–plane (§2.6.1)

def test_wheel_plane_relation_hand_computed_cases():
    """d (2.36), κ (2.37), λ (2.38) for cases worked out by hand."""
    floor = K.Plane(np.array([0.0, 0.0, 0.1]), np.array([0.0, 0.0, 1.0]))
    assert np.allclose(K.contact_relation([1.0, 2.0, 0.129], np.eye(3), floor), [0.029, 0.0, 0.0])
    a = 0.107  # a plane rolled by −a (condition 1, §4.5): n = R_x(−a) e_z = [0, sin a, cos a]
    rolled = K.Plane.from_pose([0.0, 0.0, 0.0], [-a, 0.0, 0.0])
    assert np.allclose(rolled.normal, [0.0, math.sin(a), math.cos(a)])
    d, kappa, lam = K.contact_relation([0.0, 1.0, 0.0], np.eye(3), rolled)
    assert d == pytest.approx(math.sin(a)) and kappa == pytest.approx(a) and lam == pytest.approx(0.0, abs=1e-15)
    # a level plane and a wheel whose link behind is pitched down by b: λ = asin(e_z · [cos b, 0, −sin b]) = −b
    b = 0.3
    assert np.allclose(K.contact_relation([0, 0, 0.029], rot_y(b), K.Plane(np.zeros(3), K.E_Z)),
                       [0.029, 0.0, -b])
    # proper contact on the rolled plane: frame = the plane's own frame, lifted by r_w along its normal
    R_f = K.rot_zyx([-a, 0.0, 0.0])
    assert np.allclose(K.contact_relation(0.029 * rolled.normal, R_f @ rot_z(2.0), rolled), [0.029, 0, 0])


@pytest.mark.parametrize("seed", range(2))
def test_contact_jacobian_matches_finite_differences(seed):
    rng = np.random.default_rng(10 + seed)
    w_h, psi = random_pose(rng)
    plane = K.Plane.from_pose(rng.normal(size=3), [0.2, -0.1, 0.5])
    Mh = K.head_euler_map(w_h[3:])
    ch = K.chain_from_pose(w_h, psi, L)

    def r(w, p, i):
        c = K.chain_from_pose(w, p, L)
        return K.contact_relation(c.wheel_position(i), c.wheel_frame(i), plane)

    for i in (1, 5, 9):
        J_t, J_psi = K.contact_jacobian(ch, i, plane)
        assert np.abs(J_t @ Mh - fd(lambda w: r(w, psi, i), w_h)).max() <= TOL
        assert np.abs(J_psi - fd(lambda p: r(w_h, p, i), psi)).max() <= TOL


# ------------------------------------------------------------------------------ head raised (§2.5.1)

def base_and_flat_rows_by_fd(w_h, psi, w_dot, psi_dot, n_h, n_last, l=L):
    """The meaning of A_h ẇ_h − B_h ψ̄̇ (2.25): lateral speed (2.6) of base wheels n_h..n_last, then ż, θ̇_r,
    θ̇_p of wheel n_h — all from finite differences of the 3D forward kinematics along (ẇ_h, ψ̇)."""
    def rows(s):
        ch = K.chain_from_pose(w_h + s * w_dot, psi + s * psi_dot, l)
        return np.r_[[ch.wheel_position(i) for i in range(n_h, n_last + 1)], [ch.wheel_pose(n_h)[2:5]]]

    rate = (rows(H) - rows(-H)) / (2 * H)
    ch = K.chain_from_pose(w_h, psi, l)
    lateral = [-(ch.wheel_frame(i)[:, 1] @ rate[k]) for k, i in enumerate(range(n_h, n_last + 1))]  # (2.6)
    return np.r_[lateral, rate[-1]]


def flat_motion(rng, ch, n_h, psi_free):
    """A motion keeping wheel n_h flat on its plane: planar anchor twist, joint rates on ``psi_free``."""
    psi_dot = np.zeros(len(ch.psi))
    psi_dot[psi_free] = rng.normal(size=len(psi_free))
    T_a, T_psi = K.anchored_twist_map(ch, 2 * n_h, ch.wheel_link(n_h))
    anchor = np.r_[rng.normal(size=2), 0.0, 0.0, 0.0, rng.normal()]  # ẋ, ẏ, ω_z only
    twist = T_a @ anchor - T_psi @ psi_dot
    return np.linalg.solve(K.head_euler_map(ch.head_pose()[3:]), twist), psi_dot


@pytest.mark.parametrize("n_h", [2, 3, 4])
def test_head_raised_model_means_base_no_slip_and_flat_front_wheel(n_h):
    """(2.25): A_h ẇ_h − B_h ψ̄̇ = [lateral speeds of the base wheels; ż, θ̇_r, θ̇_p of wheel n_h]."""
    rng = np.random.default_rng(20 + n_h)
    n = 9
    w_h, psi = flat_state(rng, n, n_h)
    ch = K.chain_from_pose(w_h, psi, L)
    hr = K.head_raised(ch, n_h)
    n_b = n - n_h + 1
    assert hr.A_h.shape == (n_b + 3, 6) and hr.B_h.shape == (n_b + 3, n + n_h)  # (2.26)
    assert hr.J_b3.shape == (3, 6) and hr.J_b4.shape == (3, 2 * n_h) and hr.B_b.shape == (n_b, n_b - 1)
    bar = np.r_[np.arange(2 * n_h), K.yaw_joints(2 * n_h + 1, 2 * n - 1)]  # ψ̄ = [ψ_h; φ_b]
    w_dot, psi_dot = flat_motion(rng, ch, n_h, bar)
    expected = base_and_flat_rows_by_fd(w_h, psi, w_dot, psi_dot, n_h, n)
    assert np.abs(hr.A_h @ w_dot - hr.B_h @ psi_dot[bar] - expected).max() <= TOL
    assert np.abs(expected[-3:]).max() <= TOL  # the motion kept wheel n_h flat
    # any motion, flat or not: the last three rows are (2.16) exactly
    w_any, p_any = rng.normal(size=6), rng.normal(size=17)
    p_any[2 * n_h + 1::2] = 0.0
    exact = base_and_flat_rows_by_fd(w_h, psi, w_any, p_any, n_h, n)[-3:]
    assert np.abs(hr.J_b1 @ w_any + hr.J_b2 @ p_any[: 2 * n_h] - exact).max() <= TOL


def test_head_raised_needs_n_h_of_at_least_two():
    ch = K.chain_from_pose(np.zeros(6), np.zeros(17), L)
    with pytest.raises(ValueError, match="n_h >= 2"):
        K.head_raised(ch, 1)


# ------------------------------------------------------------------------------ double arm (§2.5.2, §3.4.2)

HANDCART = dict(n=15, n_h=3, n_t=13)  # §3.4.2 lengthened robot, n = 15; n_h, n_t chosen for the test


def handcart_state(seed):
    rng = np.random.default_rng(seed)
    model = K.DoubleArm(l=0.0685, **HANDCART)
    w_h, psi = flat_state(rng, model.n, model.n_h, model.n_t)
    psi *= 0.6
    psi[2 * model.n_h + 1:2 * model.n_t - 1:2] = 0.0
    ch = K.chain_from_wheel(psi, model.l, model.n_h, [0.2, -0.1, 0.029], rot_z(2.5))
    return rng, model, ch.head_pose(), psi


def test_double_arm_dimensions_for_the_handcart_robot():
    """n = 15, n_h = 3, n_t = 13: n'_b = 11; A_d (n'_b,σ+9)×12, B_d (n'_b,σ+9)×(2n − n'_b + 1) (2.33), (2.35)."""
    _, model, w_h, psi = handcart_state(0)
    m = model.matrices(w_h, psi)
    n, nb = model.n, model.base_wheels
    assert nb == 11 and len(model.input_joints) == 2 * n - nb + 1 == 20
    assert m.A_d.shape == (nb + 9, 12) and m.B_d.shape == (nb + 9, 2 * n - nb + 1)
    assert m.J_t1.shape == (6, 3) and m.J_t2.shape == (6, 2 * n - 2 * model.n_t)
    assert m.J_nt1.shape == (3, 6) and m.J_nt2.shape == (3, model.n_t + model.n_h)
    assert m.A_h.shape == (nb + 3, 6) and m.B_h.shape == (nb + 3, model.n_t + model.n_h)
    grounded = np.ones(nb, bool)
    grounded[[2, 5, 6]] = False
    ms = model.matrices(w_h, psi, grounded)
    assert ms.A_d.shape == (nb - 3 + 9, 12) and ms.B_d.shape == (nb - 3 + 9, 2 * n - nb + 1)  # A4
    keep = np.r_[np.flatnonzero(grounded), np.arange(nb, nb + 9)]
    assert np.array_equal(ms.A_d, m.A_d[keep]) and np.array_equal(ms.B_d, m.B_d[keep])
    assert np.allclose(m.c_d[:6], w_h)
    with pytest.raises(ValueError, match="n_h < n_t < n"):
        K.DoubleArm(n=15, l=0.0685, n_h=3, n_t=15)


def test_double_arm_end_point_jacobians_match_finite_differences():
    """J_{n_t,1}, J_{n_t,2} (2.30) and J_{t,2} (2.29) against FD of the FK; J_{t,1} against a rigid planar
    motion of the whole body about wheel n_t (all ≤ 1e−6)."""
    _, model, w_h, psi = handcart_state(1)
    m = model.matrices(w_h, psi)
    n_t, bar = model.n_t, model.input_joints[: model.n_t + model.n_h]
    tail = model.input_joints[model.n_t + model.n_h:]

    def w_tilde_nt(w, p):
        return K.planar_pose(model.chain(w, p), 2 * n_t, 2 * n_t - 1)

    def with_cols(cols, x):
        p = psi.copy()
        p[cols] = x
        return p

    assert np.abs(m.J_nt1 - fd(lambda w: w_tilde_nt(w, psi), w_h)).max() <= TOL
    assert np.abs(m.J_nt2 - fd(lambda x: w_tilde_nt(w_h, with_cols(bar, x)), psi[bar])).max() <= TOL
    tail_pose = lambda w, p: model.chain(w, p).wheel_pose(model.n)  # noqa: E731
    assert np.abs(m.J_t2 - fd(lambda x: tail_pose(w_h, with_cols(tail, x)), psi[tail])).max() <= TOL
    ch = model.chain(w_h, psi)
    pivot = ch.wheel_position(n_t)

    def moved(q):  # the body moved rigidly by planar (dx, dy, dθ) of wheel n_t
        Rz = rot_z(q[2])
        return tail_pose(np.r_[Rz @ (ch.P[0] - pivot) + pivot + [q[0], q[1], 0.0],
                               K.euler_zyx(Rz @ ch.R[0])], psi)

    assert np.abs(m.J_t1 - fd(moved, np.zeros(3))).max() <= TOL


def test_double_arm_model_means_no_slip_flat_base_and_tail_pose():
    """(2.32): A_d ċ_d − B_d ψ̇_d = [base lateral speeds; 0 (wheel n_h flat); 0 (tail pose rows)] for a motion
    that keeps the base flat, with ẇ_t from finite differences of the FK."""
    rng, model, w_h, psi = handcart_state(2)
    ch = model.chain(w_h, psi)
    w_dot, psi_dot = flat_motion(rng, ch, model.n_h, model.input_joints)
    w_t_dot = fd(lambda s: model.chain(w_h + s[0] * w_dot, psi + s[0] * psi_dot).wheel_pose(model.n), [0.0])[:, 0]
    m = model.matrices(w_h, psi)
    residual = m.A_d @ np.r_[w_dot, w_t_dot] - m.B_d @ psi_dot[model.input_joints]
    lateral = base_and_flat_rows_by_fd(w_h, psi, w_dot, psi_dot, model.n_h, model.n_t, model.l)
    assert np.abs(residual[: model.base_wheels + 3] - lateral).max() <= TOL
    assert np.abs(residual[model.base_wheels:]).max() <= TOL
