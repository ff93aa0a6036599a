"""The V-BOARD of seed 000 App. A.1.2: Eqs. A.1–A.4, the firmware's speed law and contact switches,
a static load, and HRP2 standing on it."""

from __future__ import annotations

import dataclasses
import math

import mujoco
import numpy as np
import pytest

from shintai.humanoid.constants import DEG, HRP2_MASS, SCENE, SOLE, VBOARD
from shintai.humanoid.vboard import vehicle as vb
from shintai.humanoid.vboard.stand import build_vboard_stand
from shintai.sim.body import MujocoBody
from shintai.sim.export import load_models
from shintai.sim.spec import fill_keyframe, scene_spec

G = 9.81
HALF_RIDER = HRP2_MASS / 2  # kg on each board
LOAD_HEIGHT = 0.30  # m, a box of half the rider's mass standing on each pad


def run(body: MujocoBody, seconds: float) -> dict:
    for _ in range(round(seconds / body.dt)):
        body.step()
    return body.snapshot()


def dtheta_deg(snapshot) -> dict:
    """θ_s − θ_sO in degrees."""
    return {s: (theta - VBOARD.theta_o(s)) / DEG for s, theta in vb.board_pitch(snapshot).items()}


def loaded(offset: float = 0.0, *, firmware: bool = True) -> MujocoBody:
    """The V-BOARD on the floor, boards at θ_O, with a box of half the rider's mass flat on each pad,
    its mass centre ``offset`` m ahead of the axle; the firmware installed unless ``firmware`` is False."""
    spec = scene_spec("vboard-loaded", *SCENE)
    vb.add_vboard(spec, spec.worldbody)
    for s in vb.SIDES:
        box = spec.worldbody.add_body(name=f"load_{s}")
        box.add_freejoint(name=f"load_{s}")
        box.add_geom(type=mujoco.mjtGeom.mjGEOM_BOX, size=[0.06, 0.06, LOAD_HEIGHT / 2], mass=HALF_RIDER,
                     contype=SOLE, conaffinity=0)
    spec.add_key(name="park")
    model = spec.compile()
    qpos = model.qpos0.copy()
    vb.vboard_state(model, qpos)
    data = mujoco.MjData(model)
    data.qpos[:] = qpos
    mujoco.mj_kinematics(model, data)
    for s in vb.SIDES:
        pad = data.site(vb.PAD[s])
        centre = pad.xpos + pad.xmat.reshape(3, 3) @ [0.0, 0.0, LOAD_HEIGHT / 2]
        centre[0] = data.site("vboard_centre").xpos[0] + offset
        quat = np.zeros(4)
        mujoco.mju_mat2Quat(quat, pad.xmat)
        adr = model.joint(f"load_{s}").qposadr[0]
        qpos[adr:adr + 7] = [*centre, *quat]
    fill_keyframe(model, "park", qpos)
    body = MujocoBody(model, keyframe="park", substeps=4, spec=spec)
    body.firmware = vb.install_firmware(body) if firmware else None
    return body


# --- Eqs. A.1–A.4 by hand ---------------------------------------------------------------------


def test_constants_are_the_thesis_values():
    """Eq. A.1 and Fig. A.4 as printed (seed 000 line ~4231)."""
    assert dict(VBOARD.k) == {"r": 4.6203, "l": 4.3356}
    assert dict(VBOARD.theta_o_deg) == {"r": -1.7871, "l": -1.9972}
    assert (VBOARD.wheel_radius, VBOARD.track) == (0.080, 0.515)


def test_equations_a1_to_a4_against_a_hand_calculation():
    theta_r, theta_l = (-1.7871 + 1.0) * DEG, (-1.9972 + 0.5) * DEG  # 1° and 0.5° past θ_O
    assert vb.wheel_speed(theta_r, "r") == pytest.approx(4.6203)  # Eq. A.1: K_R · 1°
    assert vb.wheel_speed(theta_l, "l") == pytest.approx(4.3356 * 0.5)
    assert vb.wheel_speed(VBOARD.theta_o("l"), "l") == pytest.approx(0.0, abs=1e-12)
    v_r, v_l = 0.08 * 4.6203, 0.08 * 4.3356 * 0.5  # Eq. A.2
    v, omega = vb.tilt_velocity(theta_r, theta_l)  # Eq. A.4 = A.3 ∘ A.2 ∘ A.1
    assert (v, omega) == pytest.approx(((v_r + v_l) / 2, (v_r - v_l) / 0.515))  # Eq. A.3
    assert (v, omega) == pytest.approx((0.271524, 0.380971), abs=1e-6)
    assert vb.wheel_odometry(4.6203, 4.6203) == pytest.approx((0.08 * 4.6203, 0.0))  # straight on
    both = vb.tilt_velocity(VBOARD.theta_o("r") + DEG, VBOARD.theta_o("l") + DEG)  # spec-A §8 item 2
    assert both == pytest.approx((0.3582, 0.02277 / 0.515), abs=1e-4)  # K_R ≠ K_L: it curves left
    assert vb.wheel_odometry(1.0, -1.0)[0] == pytest.approx(0.0)  # turning in place
    assert vb.wheel_odometry(1.0, -1.0)[1] > 0  # right wheel forward: turns left (+z)


def test_tilts_for_inverts_eq_a4():
    for speed, yaw_rate in ((0.0, 0.0), (0.3, 0.0), (-0.2, 0.5), (0.1, -1.0)):
        assert vb.tilt_velocity(*vb.tilts_for(speed, yaw_rate)) == pytest.approx((speed, yaw_rate), abs=1e-12)
    assert vb.tilts_for(0.0, 0.0) == pytest.approx((VBOARD.theta_o("r"), VBOARD.theta_o("l")))


@pytest.mark.parametrize("change, field", [
    ({"wheel_radius": -0.08}, "wheel_radius"), ({"track": math.nan}, "track"), ({"speed_gain": 0.0}, "speed_gain"),
    ({"k": (("r", 4.6), ("l", -1.0))}, "k"), ({"k": (("r", 4.6),)}, "k"),
    ({"theta_o_deg": (("r", math.inf), ("l", -2.0))}, "theta_o_deg"), ({"deck_height": 0.05}, "housing"),
])
def test_bad_spec_values_raise_one_line_naming_the_field(change, field):
    with pytest.raises(ValueError, match=field) as err:
        dataclasses.replace(VBOARD, **change)
    assert "\n" not in str(err.value)


def test_strapped_side_must_exist():
    body = vb.build_vboard()
    with pytest.raises(ValueError, match="strapped"):
        vb.install_firmware(body, strapped=("x",))


# --- the firmware: Eq. A.1 measured as in Figs. A.5/A.6 ---------------------------------------


def test_stand_measurement_recovers_eq_a1():
    """Fig. A.5 in simulation: the scooter on a stand, contact switches strapped on, each board held
    at a tilt, the wheel's steady speed read; the regression of Fig. A.6 gives back K and θ_O. The
    wheel bearing's drag costs 0.5 % of K (k_v / (k_v + bearing damping))."""
    body = vb.build_vboard(hold=True, fixed=True, strapped=("r", "l"))
    tilts = np.array([-4.0, -2.0, -1.0, 1.0, 3.0])  # degrees past θ_O
    speeds = {s: [] for s in vb.SIDES}
    for d in tilts:
        for s in vb.SIDES:
            body.apply({f"board_{s}_hold": VBOARD.theta_o(s) + d * DEG})
        snap = run(body, 0.15)
        for s, omega in vb.wheel_speeds(snap).items():
            speeds[s].append(omega)
    for s in vb.SIDES:
        theta_deg = tilts + dict(VBOARD.theta_o_deg)[s]
        slope, intercept = np.polyfit(theta_deg, speeds[s], 1)
        assert slope == pytest.approx(dict(VBOARD.k)[s], rel=0.01)
        assert -intercept / slope == pytest.approx(dict(VBOARD.theta_o_deg)[s], abs=0.01)


@pytest.mark.parametrize("law", vb.FIRMWARE_LAWS)
def test_both_firmware_laws_give_eq_a1_on_the_stand(law):
    """Fig. A.5's stand cannot tell the laws apart: boards held 1.5° (right) and −2° (left) past θ_O, switches
    strapped, the free wheel's steady speed is Eq. A.1's within 1 % whether the motor is speed-servoed or torque
    driven against the bearing's drag (its time constant I/b ≈ 0.5 s: 5 s is ≈ 10 of them)."""
    theta = {"r": VBOARD.theta_o("r") + 1.5 * DEG, "l": VBOARD.theta_o("l") - 2.0 * DEG}
    body = vb.build_vboard(theta, hold=True, fixed=True, strapped=("r", "l"), law=law)
    snap = run(body, 5.0)
    for s, omega in vb.wheel_speeds(snap).items():
        assert omega == pytest.approx(vb.wheel_speed(theta[s], s), rel=0.01)
    dampers = [body.id("actuator", f"wheel_{s}_damper") for s in vb.SIDES]
    assert np.all((body.data.actuator_force[dampers] == 0.0) == (law == "torque"))  # the torque law has no speed term


def test_tilted_boards_drive_the_scooter_at_eq_a4():
    """On the floor, boards held 1° and 0.5° past θ_O (switches strapped): the true v and ω of the
    scooter are Eq. A.4's, and so is the wheels' odometry (Eqs. A.2–A.3)."""
    theta = {"r": VBOARD.theta_o("r") + 1.0 * DEG, "l": VBOARD.theta_o("l") + 0.5 * DEG}
    body = vb.build_vboard(theta, hold=True, strapped=("r", "l"))
    snap = run(body, 1.0)
    expected = vb.tilt_velocity(theta["r"], theta["l"])
    assert vb.scooter_velocity(snap) == pytest.approx(expected, rel=0.02)
    omegas = vb.wheel_speeds(snap)
    assert vb.wheel_odometry(omegas["r"], omegas["l"]) == pytest.approx(vb.scooter_velocity(snap), rel=0.01)
    yaw = snap["q:vboard_yaw"]
    assert yaw == pytest.approx(expected[1] * 1.0, rel=0.1)  # turned left by ∫ω dt (ω settles in ≈ 0.1 s)


def test_added_at_a_pose_it_drives_along_its_heading():
    """add_vboard's pose: placed at (1, 2) facing +y, boards tilted forward, it goes along +y."""
    spec = scene_spec("vboard-pose", *SCENE)
    vb.add_vboard(spec, spec.worldbody, pos=(1.0, 2.0, 0.0), yaw=math.pi / 2, hold=True)
    spec.add_key(name="park")
    model = spec.compile()
    qpos = model.qpos0.copy()
    theta = {s: VBOARD.theta_o(s) + 1.0 * DEG for s in vb.SIDES}
    vb.vboard_state(model, qpos, theta)
    fill_keyframe(model, "park", qpos)
    body = MujocoBody(model, keyframe="park", substeps=4, spec=spec)
    assert body.site_pos("vboard_centre") == pytest.approx([1.0, 2.0, VBOARD.wheel_radius])
    vb.install_firmware(body, strapped=("r", "l"))
    snap = run(body, 0.5)
    moved = body.site_pos("vboard_centre")[:2] - [1.0, 2.0]
    assert moved[1] > 0.1 and abs(moved[0]) < 0.2 * moved[1]
    yaw = math.pi / 2 + snap["q:vboard_yaw"]  # the heading sensor lags qpos by one physics step
    assert snap["vboard_heading"][:2] == pytest.approx([math.cos(yaw), math.sin(yaw)], abs=1e-3)


def test_a_true_theta_o_other_than_the_regression_makes_nominal_tilts_drift():
    """The real board's θ_O is only the regression's intercept (§6.2.1): a scooter built with another
    true θ_O, its boards held at the nominal θ_O, goes at Eq. A.4 of the true values (here backward)."""
    true = dataclasses.replace(VBOARD, theta_o_deg=(("r", -1.5871), ("l", -1.7972)))  # 0.2° higher
    nominal = {s: VBOARD.theta_o(s) for s in vb.SIDES}
    body = vb.build_vboard(nominal, true, hold=True, strapped=("r", "l"))
    v, _ = vb.scooter_velocity(run(body, 1.0))
    assert v == pytest.approx(vb.tilt_velocity(nominal["r"], nominal["l"], true)[0], rel=0.03)
    assert v < -0.05


# --- loads and contact switches ----------------------------------------------------------------


def test_static_load_over_the_axle_holds_theta_o_and_stays_put():
    """Half the rider's mass on each pad, its mass centre over the axle: the speed law holds each
    board at its own θ_O and the scooter stays. A rigid load is slowly unstable on the speed law
    (pole ≈ g/(rK) ≈ 0.45 s⁻¹, see the module), so 1.5 s bounds it."""
    body = loaded()
    start = body.body_pos("vboard")
    snap = run(body, 1.5)
    assert body.firmware.on == {"r": True, "l": True}
    assert max(abs(d) for d in dtheta_deg(snap).values()) < 0.1
    assert np.linalg.norm(body.body_pos("vboard")[:2] - start[:2]) < 0.01
    assert abs(vb.scooter_velocity(snap)[0]) < 0.02
    for s in vb.SIDES:
        assert snap[vb.TOUCH[s]][0] == pytest.approx(HALF_RIDER * G, rel=0.02)


def test_without_the_drive_the_same_load_tips_the_boards():
    """The firmware is what holds the boards: without it the loaded halves turn freely on the axle."""
    snap = run(loaded(firmware=False), 0.8)
    assert max(abs(d) for d in dtheta_deg(snap).values()) > 5.0


@pytest.mark.parametrize("offset", [0.005, -0.005])
def test_load_ahead_of_the_axle_drives_forward(offset):
    """A rider leaning (mass centre ahead of or behind the axle) tips the boards that way and the
    scooter goes that way (§A.1.2: stop, forward, backward by the boards' pitch)."""
    body = loaded(offset)
    snap = run(body, 1.0)
    assert all(np.sign(d) == np.sign(offset) for d in dtheta_deg(snap).values())
    assert np.sign(vb.scooter_velocity(snap)[0]) == np.sign(offset)
    assert abs(vb.scooter_velocity(snap)[0]) > 0.05


def test_an_unloaded_board_drives_nothing_until_its_switch_is_pressed():
    """On the stand with both boards held 1° past θ_O: no load, no drive (the wheels stay still);
    pressing the right switch (the thesis's belt, Fig. A.5) turns the right wheel at Eq. A.1's speed."""
    theta = {s: VBOARD.theta_o(s) + 1.0 * DEG for s in vb.SIDES}
    body = vb.build_vboard(theta, hold=True, fixed=True)
    snap = run(body, 0.2)
    assert body.firmware.on == {"r": False, "l": False}
    assert max(abs(w) for w in vb.wheel_speeds(snap).values()) < 1e-3
    motors = [body.id("actuator", f"wheel_{s}_{k}") for s in vb.SIDES for k in ("motor", "damper")]
    assert np.all(body.data.actuator_force[motors] == 0.0)
    body.firmware.strapped = frozenset("r")
    snap = run(body, 0.2)
    assert body.firmware.on == {"r": True, "l": False}
    speeds = vb.wheel_speeds(snap)
    assert speeds["r"] == pytest.approx(vb.wheel_speed(theta["r"], "r"), rel=0.01)
    assert abs(speeds["l"]) < 1e-3


def test_stepping_off_a_board_switches_its_drive_off():
    """Both boards loaded (drives on); the right load taken away: the right switch opens, its motor
    gives no torque and its wheel is free, while the loaded left side keeps driving."""
    body = loaded()
    run(body, 0.3)
    assert body.firmware.on == {"r": True, "l": True}
    joint = body.model.joint("load_r")
    body.data.qpos[joint.qposadr[0]:][:7] = [0.0, -1.0, LOAD_HEIGHT / 2, 1, 0, 0, 0]  # on the floor, aside
    body.data.qvel[joint.dofadr[0]:][:6] = 0.0
    body.forward()
    snap = run(body, 0.1)
    assert vb.contact_switches(snap) == {"r": False, "l": True}
    assert body.firmware.on == {"r": False, "l": True}
    motor_r = [body.id("actuator", f"wheel_r_{k}") for k in ("motor", "damper")]
    assert np.all(body.data.actuator_force[motor_r] == 0.0)
    assert body.data.actuator_force[body.id("actuator", "wheel_l_damper")] != 0.0


def test_unloaded_scooter_stands_with_its_drives_off():
    snap = run(vb.build_vboard(), 1.0)
    assert vb.contact_switches(snap) == {"r": False, "l": False}
    assert all(abs(theta) < 1.0 * DEG for theta in vb.board_pitch(snap).values())  # halves hang near level


# --- the models ----------------------------------------------------------------------------------


def test_model_alone_has_the_named_parts():
    body = vb.build_vboard()
    for kind, names in (("joint", [*vb.ROOT, "board_r", "board_l", "wheel_r", "wheel_l"]),
                        ("sensor", ["board_r_pitch", "wheel_l_speed", "board_r_touch", "vboard_vel",
                                    "vboard_angvel", "vboard_heading"]),
                        ("actuator", ["wheel_r_motor", "wheel_l_damper"]), ("site", [*vb.PAD.values()])):
        for name in names:
            body.id(kind, name)
    assert float(body.model.body_subtreemass[body.id("body", "vboard")]) == pytest.approx(10.5)
    pad = body.site_pos("board_l_top")
    assert pad[1] == pytest.approx(VBOARD.pad_y) and pad[2] == pytest.approx(VBOARD.deck_height, abs=2e-3)


def test_hrp2_stands_on_the_boards():
    """HRP2's soles on the pads, its mass centre over the axle; standing still 0.3 s its weight
    presses both contact switches and the scooter hardly moves."""
    body = build_vboard_stand()
    for s in ("l", "r"):
        assert body.site_pos(f"{s}_sole") == pytest.approx(body.site_pos(vb.PAD[s]), abs=1e-3)
    com = body.data.subtree_com[body.id("body", "waist")]
    assert com[0] == pytest.approx(body.site_pos("vboard_centre")[0], abs=2e-3)
    start = body.body_pos("vboard")
    snap = run(body, 0.3)
    assert body.firmware.on == {"r": True, "l": True}
    assert snap["board_r_touch"][0] + snap["board_l_touch"][0] == pytest.approx(HRP2_MASS * G, rel=0.03)
    assert np.linalg.norm(body.body_pos("vboard")[:2] - start[:2]) < 0.01


def test_models_are_registered():
    models = load_models()
    assert {"humanoid.vboard", "humanoid.hrp2-vboard"} <= set(models)
