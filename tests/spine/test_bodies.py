"""The MuJoCo spine body (spatial tendons = eq. 4.25, wires that only pull, reels) and the quasi-static body."""

import numpy as np
import pytest

from shintai.core.runtime import ADD, SET, ChannelError, FunctionModule, Loop
from shintai.spine.bodies import QuasiStaticSpine
from shintai.spine.bodies_mujoco import SpineBody
from shintai.spine.control import Mode
from shintai.spine.geometry import uniform_posture, whole_spine
from shintai.spine.robots import CLA, CLA_ARMS_DOWN, CLA_TRUNK_LOADS


@pytest.fixture(scope="module")
def plain():
    return SpineBody(CLA, interference=False)


def test_tendon_paths_are_eq_4_25_for_hinge_and_ball_joints(plain):
    rng = np.random.default_rng(0)
    ball = SpineBody(CLA, joint="ball", interference=False)
    for _ in range(3):
        theta = rng.uniform(-0.25, 0.25, 15)
        for body in (plain, ball):
            body.set_theta(theta)
            assert np.allclose(body.theta(), theta, atol=1e-9)
            assert np.allclose(body.path_lengths(), CLA.model.lengths(theta), atol=1e-10)


def test_interference_only_lengthens_the_convex_side():
    """§4.7.2's hypothesis, as modelled: a bent spine pushes the muscles on its convex side out
    around the middle vertebra, so they are longer than eq. 4.25; the others are unchanged."""
    body = SpineBody(CLA, interference=True)
    theta = uniform_posture(np.radians([0.0, 30.0, 0.0]), CLA.n)  # forward: the back is convex
    body.set_theta(theta)
    extra = body.path_lengths() - CLA.model.lengths(theta)
    back = [CLA.muscle_names.index(n) for n in ("CLA-RB", "CLA-LB")]
    assert np.all(extra >= -1e-12)
    assert np.all(extra[back] > 1e-5)
    assert np.allclose(np.delete(extra, back), 0.0, atol=1e-12)


def test_the_column_lengthens_the_muscles_that_bear_on_it():
    """wrap="column" (§4.7.2 "構造材と干渉すると…長くなる"): at rest no muscle touches the column, so every length is
    eq. 4.25's; bent forward, the back muscles bear on it and are longer than eq. 4.25 by more than on the sphere;
    twisted, Fig. 3.31's diagonal front and back muscles wind round it; no muscle is ever shorter."""
    column, sphere = SpineBody(CLA, wrap="column"), SpineBody(CLA, wrap="sphere")

    def extra(body, whole_deg):
        theta = uniform_posture(np.radians(whole_deg), CLA.n)
        body.set_theta(theta)
        return body.path_lengths() - CLA.model.lengths(theta)

    assert np.allclose(extra(column, [0.0, 0.0, 0.0]), 0.0, atol=1e-12)
    back = [CLA.muscle_names.index(n) for n in ("CLA-RB", "CLA-LB")]
    forward_c, forward_s = extra(column, [0.0, 30.0, 0.0]), extra(sphere, [0.0, 30.0, 0.0])
    assert np.all(forward_c[back] > 2e-4) and np.all(forward_c[back] > 2 * forward_s[back])
    assert np.allclose(np.delete(forward_c, back), 0.0, atol=1e-12)
    twist = extra(column, [0.0, 0.0, 60.0])
    wound = [CLA.muscle_names.index(n) for n in ("CLA-LF", "CLA-RB")]
    assert np.all(twist[wound] > 2e-3) and np.all(twist >= -1e-12)
    with pytest.raises(ValueError, match="wrap"):
        SpineBody(CLA, wrap="torus")


def test_the_wire_only_pulls_and_its_joint_torque_is_minus_J_transpose_T(plain):
    """Sign convention: winding a reel in tensions its wire, whose generalised force on the spine
    is τ = −J_mᵀT (eq. 4.22); paying it out leaves it slack: no force at all (it cannot push)."""
    body = plain
    theta = uniform_posture(np.radians([5.0, -8.0, 3.0]), CLA.n)
    body.set_theta(theta)
    disc = np.tile([CLA.disc.k_bend_nm_rad, CLA.disc.k_bend_nm_rad, CLA.disc.k_twist_nm_rad], CLA.n) * theta
    reel_q = body.model.jnt_qposadr[[body.id("joint", f"{n}:reel") for n in CLA.muscle_names]]
    spine = body.spine_qpos  # hinge qpos and dof addresses coincide here
    slack = body.model.tendon_lengthspring[body.tendon_ids, 1] - body.data.ten_length[body.tendon_ids]
    body.data.qpos[reel_q] = slack  # every wire exactly taut, zero tension
    for j, wind in ((0, 1e-3), (5, 2e-3)):
        body.data.qpos[reel_q[j]] += wind
    body.forward()
    tension = body.wire_tension()
    assert tension[0] == pytest.approx(CLA.sensor.wire_stiffness_n_m * 1e-3, rel=1e-6)
    assert tension[5] == pytest.approx(CLA.sensor.wire_stiffness_n_m * 2e-3, rel=1e-6)
    assert np.allclose(np.delete(tension, [0, 5]), 0.0)
    tau = body.data.qfrc_passive[spine] + disc  # remove the discs' −Kθ
    assert np.allclose(tau, CLA.model.tension_to_torque(theta, tension), atol=1e-6)
    assert body.data.qfrc_passive[body.model.jnt_dofadr[body.id("joint", "CLA-RF:reel")]] == pytest.approx(-tension[0])
    body.data.qpos[reel_q[0]] -= 3e-3  # pay out: slack, no force
    body.forward()
    assert body.wire_tension()[0] == 0.0
    assert np.allclose(body.data.qfrc_passive[spine] + disc, CLA.model.tension_to_torque(theta, body.wire_tension()),
                       atol=1e-6)


def test_positive_duty_winds_in_and_raises_tension():
    body = SpineBody(CLA, loads=CLA_TRUNK_LOADS + CLA_ARMS_DOWN)
    for _ in range(100):
        body.apply({"duty": np.r_[0.3, np.zeros(7)], "hand": np.zeros(15)})  # the hand holds the spine
        body.step()
    snap = body.snapshot()
    assert snap["encoder"][0] > 0 and snap["tension_true"][0] > 1.0
    assert snap["current"][0] > 0 and snap["encoder"][0] > 10 * np.abs(snap["encoder"][1:]).max()
    with pytest.raises(ValueError, match="8 muscles"):
        body.apply({"duty": np.zeros(3)})


def test_snapshot_sensors_equal_the_body_state():
    """The snapshot's muscle entries are the body's own state functions (tension, current, lengths,
    θ), read at the same instant."""
    body = SpineBody(CLA, loads=CLA_TRUNK_LOADS + CLA_ARMS_DOWN)
    for _ in range(50):
        body.apply({"duty": np.linspace(-0.2, 0.3, 8), "hand": uniform_posture(np.radians([5.0, -8.0, 3.0]), CLA.n)})
        body.step()
    snap = body.snapshot()
    assert np.array_equal(snap["tension_true"], body.wire_tension())
    assert np.array_equal(snap["current"], body.currents())
    assert np.allclose(snap["lengths"], body.path_lengths(), atol=1e-15)
    assert np.array_equal(snap["theta"], body.theta())
    assert np.array_equal(snap["encoder"], body.encoder.read(body.wound()))
    assert snap["t"] == body.t and snap["qpos"].shape == (body.model.nq,)


def test_accelerometers_give_the_true_static_posture():
    """Eq. 3.4 in a static simulation equals the shoulder's pitch/roll relative to the waist
    (spec §5.3.10)."""
    body = SpineBody(CLA, loads=CLA_TRUNK_LOADS + CLA_ARMS_DOWN)
    for whole in ([0.0, 15.0, 0.0], [-12.0, 0.0, 0.0]):
        body.reset()
        body.hold(uniform_posture(np.radians(whole), CLA.n))
        for _ in range(1200):  # 0.6 s: with the Appendix-A clavicle points the pitch bend settles slower
            body.step()
        snap = body.snapshot()
        true = np.degrees(whole_spine(snap["theta"]))[:2]
        assert np.allclose(np.degrees(snap["posture"]), true, atol=0.3)
        assert np.abs(true).max() > 10.0  # the hand did bend the spine


def test_disc_stiffness_changes_at_run_time(plain):
    plain.set_disc(8.0, 2.0)
    names = [plain.model.joint(j).name for j in range(plain.model.njnt)]
    k = dict(zip(names, plain.model.jnt_stiffness))
    assert k["j3_pitch"] == 8.0 and k["j3_yaw"] == 2.0 and k["CLA-RF:reel"] == 0.0


def test_a_stiffer_disc_set_mid_run_holds_the_spine_straighter():
    """Run-time stiffness change (issue: "run-time stiffness changes"): wires paid out (slack), the
    discs alone carry the trunk and arms; stiffening them during the run lowers the forward sag,
    softening them again brings it back."""
    body = SpineBody(CLA, interference=False, loads=CLA_TRUNK_LOADS + CLA_ARMS_DOWN)

    def sag(k_bend: float) -> float:
        """Mean whole-spine pitch over 1 s after 0.5 s (the lightly damped trunk still sways)."""
        body.set_disc(k_bend)
        pitch = []
        for k in range(3000):
            body.apply({"duty": np.full(CLA.m, -0.2)})
            body.step()
            if k >= 1000:
                pitch.append(whole_spine(body.theta())[1])
        assert body.wire_tension().max() == 0.0
        return float(np.degrees(np.mean(pitch)))

    soft, stiff, soft_again = sag(CLA.disc.k_bend_nm_rad), sag(4 * CLA.disc.k_bend_nm_rad), sag(CLA.disc.k_bend_nm_rad)
    assert soft > 5.0 and 0.0 < stiff < soft / 2
    assert soft_again == pytest.approx(soft, rel=0.05)


def test_quasi_static_equal_tensions_cancel():
    """§4.6.2: all muscles at the same target tension cancel; only the discs hold the posture (no
    gravity, symmetric layout → upright). Pulling the two front muscles harder bends the spine
    forward (+pitch), by about what linear statics with the uniform-bend J predicts."""
    body = QuasiStaticSpine(CLA, gravity=False)
    body.set_laws(Mode.T, tension=0.2)
    body.step()
    assert body.result.success and np.abs(body.result.theta).max() < 1e-9
    extra = np.r_[0.5, 0.5, np.zeros(6)]  # small, so the column's compression barely softens it
    body.set_laws(Mode.T, tension=0.2 + extra)
    body.step()
    pitch = whole_spine(body.result.theta)[1]
    U = np.tile(np.eye(3) / CLA.n, (CLA.n, 1))
    J_u = CLA.model.jacobian(np.zeros(15)) @ U
    predicted = -(J_u.T @ extra)[1] / (CLA.disc.k_bend_nm_rad / CLA.n)
    assert body.result.success and pitch > 0 and pitch == pytest.approx(predicted, rel=0.1)


def test_quasi_static_length_control_reaches_the_model_posture():
    """L mode without gravity: the muscles at their eq. 4.25 lengths put the spine at the commanded
    uniform posture, up to the wire stretch the discs cause."""
    body = QuasiStaticSpine(CLA, gravity=False)
    target = uniform_posture(np.radians([8.0, -10.0, 0.0]), CLA.n)
    body.apply({"length": CLA.model.lengths(target)})
    body.step()
    assert body.result.success
    assert np.allclose(np.degrees(whole_spine(body.result.theta)), [8.0, -10.0, 0.0], atol=1.0)


def test_kenta_ligaments_are_pre_stretched_extension_springs():
    """§3.7.1: Kenta's ligaments sit where robots.py puts them, are stretched 1–2 mm past their
    natural length at rest (so they pull, k (l − l_n)), and make the spine sag less — shown on 3 N m/rad discs
    (our old choice): against KENTA's 280 N m/rad discs (2 × k*, robots.KENTA_DISC_NM_RAD) the sag is ≈ 0.1°
    either way, and the bare spine model's 1e-6 kg m² armature is too small for them at a 0.5 ms step."""
    import mujoco

    from shintai.spine.geometry import SpineModel
    from shintai.spine.robots import KENTA, KENTA_LIGAMENTS

    body = SpineBody(KENTA, ligaments=KENTA_LIGAMENTS)
    ids = [mujoco.mj_name2id(body.model, mujoco.mjtObj.mjOBJ_TENDON, nm) for nm in KENTA_LIGAMENTS.springs.names]
    body.forward()
    rest = SpineModel(KENTA.model.chain, KENTA_LIGAMENTS.springs).lengths(np.zeros(3 * KENTA.n))
    assert np.allclose(body.data.ten_length[ids], rest, atol=1e-9)
    stretch = body.data.ten_length[ids] - KENTA_LIGAMENTS.natural_length_m
    assert np.all((stretch > 0.9e-3) & (stretch < 2.1e-3))
    assert body.model.tendon_stiffness[ids] == pytest.approx(KENTA_LIGAMENTS.stiffness_n_m)
    sag = {}
    for key, lig in (("with", KENTA_LIGAMENTS), ("without", None)):
        b = SpineBody(KENTA, ligaments=lig)
        b.set_disc(3.0)
        for _ in range(400):
            b.step()
        sag[key] = np.abs(b.theta()).max()
    assert sag["with"] < sag["without"]


def test_the_hand_channel_holds_while_written_and_lets_go_after():
    """The hand is a set channel of the body: a tick that writes a posture welds the top link to its
    pose; a tick without it lets go (so whoever holds the spine writes it every tick)."""
    body = SpineBody(CLA, loads=CLA_TRUNK_LOADS + CLA_ARMS_DOWN)
    assert body.channels["hand"].kind == SET and body.channels["duty"].kind == ADD
    bent = uniform_posture(np.radians([0.0, 12.0, 0.0]), CLA.n)
    Loop(body, [], base={"hand": bent}).run(0.6)
    assert body.data.eq_active[body.id("equality", "hand")]
    assert np.degrees(whole_spine(body.theta()))[1] > 8.0  # bent toward 12° (a firm, not rigid grip)
    Loop(body, []).run(0.001)
    assert not body.data.eq_active[body.id("equality", "hand")]
    with pytest.raises(ChannelError, match="two writers"):
        hand = FunctionModule(lambda snap: {"hand": bent}, name="second_hand")
        Loop(body, [hand], base={"hand": bent}).run(0.001)


@pytest.mark.parametrize("joint", ["hinge", "ball"])
@pytest.mark.parametrize("name", ["Cla", "Kenta"])
def test_compiled_joint_ranges_are_the_robots_limits(name, joint):
    """§3.6.1 (Cla, ±18°) and §3.7.1 (Kenta, ±10°): every vertebral joint compiles to robots.py's limit in
    radians — not to the limit read as degrees (±0.31° / ±0.17°, MjSpec's default ``compiler.degree``)."""
    import mujoco

    from shintai.spine.bodies_mujoco import build_spec
    from shintai.spine.robots import CLA_LIMIT_RAD, KENTA, KENTA_LIMIT_RAD

    robot, limit = {"Cla": (CLA, CLA_LIMIT_RAD), "Kenta": (KENTA, KENTA_LIMIT_RAD)}[name]
    model = build_spec(robot, joint=joint).compile()
    kind = {"hinge": mujoco.mjtJoint.mjJNT_HINGE, "ball": mujoco.mjtJoint.mjJNT_BALL}[joint]
    vertebral = [j for j in range(model.njnt) if model.jnt_type[j] == kind]
    assert len(vertebral) == (3 * robot.n if joint == "hinge" else robot.n)
    assert all(model.jnt_limited[vertebral])
    expected = [-limit, limit] if joint == "hinge" else [0.0, limit]
    assert model.jnt_range[vertebral] == pytest.approx(np.tile(expected, (len(vertebral), 1)), abs=1e-12)


def test_no_joint_limit_acts_inside_the_range():
    """Bent 10° on every axis of every joint (inside Cla's ±18°), the spine meets no joint limit: the
    disc alone resists it."""
    import mujoco

    body = SpineBody(CLA, interference=False)
    body.set_theta(np.full(3 * CLA.n, np.radians(10.0)))
    spine = set(np.flatnonzero(np.isin(body.model.jnt_qposadr, body.spine_qpos)))
    d = body.data
    limits = [i for i in range(d.nefc) if d.efc_type[i] == mujoco.mjtConstraint.mjCNSTR_LIMIT_JOINT and d.efc_id[i] in spine]
    assert limits == []
