"""Geometric model of seed 003 §4.3–4.5: eq. 4.25 lengths, J_m, virtual work, K_j, tension distribution."""

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from shintai.spine.geometry import (
    Chain, MuscleSet, SpineModel, distribute_tension, joint_stiffness, matrix_rpy, rpy_matrix, uniform_posture,
    whole_spine,
)
from shintai.spine.robots import BEBE, CLA, KENTA, KENTA_MOTOR_GROUPS, RABBIT

MODELS = {"cla": CLA.model, "rabbit": RABBIT.model, "kenta": KENTA.model, "bebe": BEBE.model}


def random_posture(model, rng, scale=0.8):
    return rng.uniform(scale * model.chain.lower, scale * model.chain.upper)


def elementary(axis, angle):
    c, s = np.cos(angle), np.sin(angle)
    return {"x": np.array([[1, 0, 0], [0, c, -s], [0, s, c]]), "y": np.array([[c, 0, s], [0, 1, 0], [-s, 0, c]]),
            "z": np.array([[c, -s, 0], [s, c, 0], [0, 0, 1]])}[axis]


def test_rpy_is_euslisp_rz_ry_rx_and_inverts():
    phi, theta, psi = 0.3, -0.2, 0.7
    R = rpy_matrix([phi, theta, psi])
    assert np.allclose(R, elementary("z", psi) @ elementary("y", theta) @ elementary("x", phi))
    assert np.allclose(matrix_rpy(R), [phi, theta, psi])
    batch = np.random.default_rng(0).uniform(-1, 1, (4, 5, 3))
    assert np.allclose(matrix_rpy(rpy_matrix(batch)), batch)


@pytest.mark.parametrize("name", list(MODELS))
def test_length_is_the_sum_of_segment_norms(name):
    """Eq. 4.25, recomputed point by point from the link frames."""
    model = MODELS[name]
    theta = random_posture(model, np.random.default_rng(1))
    R, p, _ = model.chain.frames(theta)
    expected = np.zeros(model.m)
    for j, path in enumerate(model.muscles.paths):
        pts = [R[link] @ np.array(x) + p[link] for link, x in path]
        expected[j] = sum(np.linalg.norm(b - a) for a, b in zip(pts, pts[1:]))
    assert np.allclose(model.lengths(theta), expected, rtol=0, atol=1e-12)


@pytest.mark.parametrize("name", list(MODELS))
def test_jacobian_matches_finite_differences(name):
    """J_m (eq. 4.14) analytic vs the thesis's numerical differentiation (eq. 4.15): ≤ 1e−6 relative."""
    model = MODELS[name]
    rng = np.random.default_rng(2)
    for _ in range(3):
        theta = random_posture(model, rng)
        J, Jfd = model.jacobian(theta), model.jacobian_fd(theta, step=1e-6)
        assert J.shape == (model.m, 3 * model.n)
        assert np.abs(J - Jfd).max() <= 1e-6 * np.abs(J).max()


def test_gap_jacobian_matches_finite_differences():
    model = RABBIT.model
    rng = np.random.default_rng(3)
    theta, gap = random_posture(model, rng), rng.normal(0, 5e-4, model.n)
    h = 1e-7
    fd = np.stack([(model.lengths(theta, gap + h * e) - model.lengths(theta, gap - h * e)) / (2 * h)
                   for e in np.eye(model.n)], axis=-1)
    assert np.abs(model.gap_jacobian(theta, gap) - fd).max() <= 1e-6 * np.abs(fd).max()


@settings(max_examples=25, deadline=None)
@given(st.integers(0, 2**32 - 1))
def test_virtual_work(seed):
    """θ̇ᵀτ = −q̇ᵀT (eq. 4.20) with τ = −J_mᵀT (eq. 4.22); q̇ by finite differences of eq. 4.25."""
    rng = np.random.default_rng(seed)
    model = CLA.model
    theta, theta_dot = random_posture(model, rng), rng.normal(0, 1, 15)
    tension = rng.uniform(0, 50, model.m)
    tau = model.tension_to_torque(theta, tension)
    eps = 1e-6
    q_dot = (model.lengths(theta + eps * theta_dot) - model.lengths(theta - eps * theta_dot)) / (2 * eps)
    assert theta_dot @ tau == pytest.approx(-q_dot @ tension, rel=1e-6, abs=1e-9)


@pytest.mark.parametrize("name", ["cla", "rabbit", "kenta"])
def test_joint_stiffness_symmetric_psd_low_rank(name):
    """K_j = J_mᵀK_mJ_m (eq. 4.35): symmetric, PSD, rank ≤ min(m, 3n); linear in K_m."""
    model = MODELS[name]
    rng = np.random.default_rng(4)
    theta = random_posture(model, rng)
    k = rng.uniform(100, 5000, model.m)
    K = model.joint_stiffness(theta, k)
    assert np.allclose(K, K.T)
    assert np.linalg.eigvalsh(K).min() >= -1e-9 * np.abs(K).max()
    assert np.linalg.matrix_rank(K) <= min(model.m, 3 * model.n)
    assert np.allclose(model.joint_stiffness(theta, 2 * k), 2 * K)


def test_cla_muscles_only_constrain_the_clavicle_pose():
    """Cla's 8 muscles run block to block, so rank J_m ≤ 6: eq. 4.24's Z is not 0 (a co-contraction
    null space of dim ≥ 2) and ≥ 9 joint directions are held by the discs alone."""
    J = CLA.model.jacobian(random_posture(CLA.model, np.random.default_rng(5)))
    assert np.linalg.matrix_rank(J) == 6
    result = distribute_tension(J, np.zeros(15))
    assert result.null_dim == 2


def test_tension_distribution_with_an_empty_null_space_is_reported():
    """Rabbit's 6 muscles pass through every vertebra: rank J_m = m = 6, Z = 0 (eq. 4.24), so the
    min-norm tension is the only one; when it has a negative element there is no exact T ≥ 0."""
    model = RABBIT.model
    theta = random_posture(model, np.random.default_rng(6), 0.3)
    J = model.jacobian(theta)
    achievable = -J.T @ np.full(6, 20.0)
    ok = distribute_tension(J, achievable)
    assert ok.null_dim == 0 and ok.exact and np.allclose(ok.tension, 20.0)
    pushing = -J.T @ np.array([20.0, -10.0, 20.0, 20.0, 20.0, 20.0])
    bad = distribute_tension(J, pushing)
    assert bad.null_dim == 0 and not bad.exact and bad.tension.min() >= 0.0 and bad.min_norm.min() < 0
    assert ok.report().startswith("Z = 0") and "reproduces τ" in ok.report()
    assert "no T ≥ t_min reproduces τ" in bad.report() and f"{bad.residual:.3g}" in bad.report()


def test_tension_distribution_uses_the_null_space_for_non_negative_tensions():
    """Cla in uniform-bend coordinates: J is 8 × 3 with a 5-dim null space (spec §2.3); a torque
    whose min-norm tensions are partly negative gets T ≥ 0 reproducing it exactly."""
    U = np.tile(np.eye(3) / CLA.n, (CLA.n, 1))
    J = CLA.model.jacobian(np.zeros(15)) @ U
    tau = np.array([0.0, -0.3, 0.0])  # a pure pitch torque
    result = distribute_tension(J, tau, t_min=1.0)
    assert result.null_dim == 5 and result.min_norm.min() < 0
    assert result.exact and result.tension.min() >= 1.0 - 1e-9
    assert np.allclose(-J.T @ result.tension, tau, atol=1e-9)


def test_uniform_posture_and_whole_spine():
    theta = uniform_posture(np.radians([0.0, -30.0, 0.0]), 5)
    assert np.allclose(np.degrees(theta[1::3]), -6.0)  # Appendix A.1.3: pitch −30 = 5 × −6°
    assert np.allclose(whole_spine(theta), np.radians([0.0, -30.0, 0.0]))


def test_cla_geometry_is_calibrated_to_table_4_2_division_counts():
    """‖Δq‖ for 1°/joint uniform bends: roll ≈ 6 mm, pitch 2–3 mm, yaw ≈ 2 mm (spec §2.3, derived)."""
    q0 = CLA.model.lengths(np.zeros(15))
    norms = [1e3 * np.linalg.norm(CLA.model.lengths(uniform_posture(np.radians(5.0) * e, 5)) - q0)
             for e in np.eye(3)]
    assert 5.0 <= norms[0] <= 7.0 and 2.0 <= norms[1] <= 3.5 and 1.5 <= norms[2] <= 3.0


def test_kenta_has_forty_routed_muscles_in_table_3_3_groups():
    assert KENTA.m == 40 and KENTA.n == 10
    assert [KENTA_MOTOR_GROUPS.count(g) for g in "ABC"] == [16, 6, 18]
    # every muscle has one end on the hip or shoulder block (§3.7.2)
    assert all({path[0][0], path[-1][0]} & {0, 10} for path in KENTA.model.muscles.paths)
    # back muscles from the hip end at vertebrae 2, 4, 6, 8 (links 8, 6, 4, 2) or the shoulder block
    ends = {nm: path[-1][0] for nm, path in zip(KENTA.muscle_names, KENTA.model.muscles.paths)}
    assert [ends[f"HIP-BL{k}"] for k in range(1, 6)] == [10, 8, 6, 4, 2]
    assert [ends[f"SHO-BL{k}"] for k in range(1, 6)] == [0, 2, 4, 6, 8]
    assert np.linalg.matrix_rank(KENTA.model.jacobian(np.full(30, 0.05))) <= 30


def test_a_muscle_needs_two_points_and_unique_names():
    with pytest.raises(ValueError, match="two points"):
        MuscleSet.from_paths(["a"], [[(0, (0, 0, 0))]])
    with pytest.raises(ValueError, match="unique"):
        MuscleSet.from_paths(["a", "a"], [[(0, (0, 0, 0)), (1, (0, 0, 0))]] * 2)
    chain = Chain.straight([0.03, 0.03], 0.3)
    with pytest.raises(ValueError, match="3n = 6"):
        SpineModel(chain, MuscleSet.from_paths(["a"], [[(0, (0, 0, 0)), (2, (0, 0, 0))]])).lengths(np.zeros(5))


def test_joint_stiffness_function_accepts_a_jacobian():
    J = np.array([[1.0, 0.0], [0.0, 2.0], [1.0, 1.0]])
    assert np.allclose(joint_stiffness(J, [1.0, 1.0, 2.0]), J.T @ np.diag([1.0, 1.0, 2.0]) @ J)


# Appendix A, Tables A.1 (all L, mean tension) and A.2 (all LL, mean tension) — the evidence for
# Cla's routing (robots.CLA_TOP_M; Fig. 3.31 is not in the text). +1: the muscle
# lengthens as the whole spine bends that way (A.1: its tension rises from ~0 under L control — it
# is stretched past its model length; A.2: it stays at or rises to the LL limit), −1: it shortens
# (A.2: it goes slack; A.1: its tension falls to 0); 0: the tables disagree or show nothing. Values
# in kgf, 0 → ±20 (or ±30) of the first sweep. Pitch + is forward (the back muscles CLA-RB/LB
# load), roll + to the right (the left muscles load).
CLA_APPENDIX_A_SIGNS = {
    #             CLA-RF CLA-LF CLA-RB CLA-LB HIP-RF HIP-LF HIP-RB HIP-LB
    ("pitch", -1): (+1, +1, -1, -1, -1, -1, +1, +1),
    # A.1: CLA-RF .07→.41, CLA-LF .01→.22, HIP-RB .04→.52, HIP-LB .03→.43 (−20);
    # A.2: CLA-RB .42→0, CLA-LB .64→.03, HIP-RF .46→.06, HIP-LF .68→0 (−20 on the way back)
    ("pitch", +1): (-1, -1, +1, +1, +1, +1, -1, -1),
    # A.1: CLA-RB .01→.29, CLA-LB .07→.51, HIP-RF 0→.49, HIP-LF 0→.39, HIP-RB .25→0, HIP-LB .45→.02,
    # CLA-RF .07→.02, CLA-LF .01→0 (+20)
    ("roll", -1): (+1, 0, +1, 0, 0, -1, +1, -1),
    # A.1: CLA-RF .04→.72, HIP-RB .19→.35 (−20); A.2: CLA-RF .44→1.24, CLA-RB .27→.71, HIP-LF
    # .52→.03, HIP-LB .65→.07 (−30); CLA-LB (A.1 up, A.2 down) and HIP-RF (slack with HIP-LF in A.2:
    # a pitch drift) undetermined
    ("roll", +1): (-1, +1, -1, +1, 0, +1, 0, +1),
    # A.1: CLA-LF 0→.25, CLA-LB .01→.18, HIP-LB .03→.22 (+30, from +10); A.2: CLA-RF .44→.03,
    # CLA-RB .27→.09, HIP-LF .52→.80 (+30); HIP-RF, HIP-RB (A.1 and A.2 disagree) undetermined
}


@pytest.mark.parametrize("angle_deg", [10.0, 20.0, 30.0])
@pytest.mark.parametrize("axis, sign", list(CLA_APPENDIX_A_SIGNS))
def test_cla_routing_length_changes_agree_with_appendix_a(axis, sign, angle_deg):
    """Eq. 4.25 on our Cla routing lengthens/shortens each muscle as Tables A.1/A.2 say the real
    robot's did (the determinate entries of CLA_APPENDIX_A_SIGNS), at ±10°, ±20° and ±30°."""
    assert CLA.muscle_names == ("CLA-RF", "CLA-LF", "CLA-RB", "CLA-LB", "HIP-RF", "HIP-LF", "HIP-RB", "HIP-LB")
    whole = np.zeros(3)
    whole[{"roll": 0, "pitch": 1}[axis]] = sign * np.radians(angle_deg)
    delta = CLA.model.lengths(uniform_posture(whole, CLA.n)) - CLA.model.lengths(np.zeros(15))
    expected = np.array(CLA_APPENDIX_A_SIGNS[(axis, sign)])
    known = expected != 0
    assert np.array_equal(np.sign(delta[known]), expected[known]), dict(zip(CLA.muscle_names, 1e3 * delta))


def test_hanzous_cam_sets_the_leaf_length_and_so_its_stiffness():
    """§3.3.1: the cam angle is proportional to the leaf spring's effective length; a cantilever's
    tip stiffness 3EI/L³ then falls with the cube of it (the cam softens the trunk)."""
    from shintai.spine.robots import HANZOUS

    lo, hi = HANZOUS.length_range_m
    assert HANZOUS.effective_length_m([0.0, 90.0, 180.0, 270.0]) == pytest.approx([lo, (lo + hi) / 2, hi, hi])
    k = HANZOUS.bending_stiffness_n_m([0.0, 180.0])
    assert k[0] / k[1] == pytest.approx((hi / lo) ** 3)
    assert HANZOUS.servos == HANZOUS.joints + 1


def test_one_posture_takes_the_same_products_as_a_batch():
    """frames/lengths/uniform_posture of one posture (the 1 ms players' path) equal, bit for bit, the same
    posture's row of a batch."""
    rng = np.random.default_rng(3)
    for model in (CLA.model, KENTA.model):
        thetas = rng.normal(0.0, 0.1, (20, 3 * model.n))
        wholes = rng.normal(0.0, 0.3, (20, 3))
        batch = model.chain.frames(thetas)
        for k in range(len(thetas)):
            assert all(np.array_equal(one, many[k]) for one, many in zip(model.chain.frames(thetas[k]), batch))
            assert np.array_equal(model.lengths(thetas[k]), model.lengths(thetas)[k])
            assert np.array_equal(uniform_posture(wholes[k], model.n), uniform_posture(wholes, model.n)[k])


@pytest.mark.parametrize("name", list(MODELS))
def test_one_postures_lengths_in_the_compiled_loop_are_numpys(name):
    """lengths of one posture (geometry._segment_lengths, the players' 1 ms path) are, bit for bit, eq. 4.25
    through the NumPy frames, path points and segments (every chain robot: Kenta's wedges, Rabbit's helical
    many-segment muscles)."""
    model, rng = MODELS[name], np.random.default_rng(4)
    for _ in range(50):
        theta = random_posture(model, rng, scale=1.2)
        numpy_path = model.muscles.sum_per_muscle(model.muscles.segments(model.points(theta))[1])
        assert np.array_equal(model.lengths(theta), numpy_path)
    with pytest.raises(ValueError):
        model.lengths(np.zeros(3 * model.n + 1))
