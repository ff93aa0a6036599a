"""Cla's whole-body behaviours of seed 003 §5.2.5–5.2.8 (spine/cla_keyframes.py, cla_reach.py, cla_pick_place.py,
cla_cop.py, cla_roll_over.py): the key player, the arm keys on the model, the arm-swing reflex, and each
behaviour's with/without switch, run short."""

import math

import numpy as np
import pytest

from shintai.core.runtime import Loop
from shintai.spine.cla import cop as CB
from shintai.spine.cla import pick_place as PP
from shintai.spine.cla import roll_over as RO
from shintai.spine.cla.body import LIMB_JOINTS, SPINE_JOINTS, ClaBody, start_targets
from shintai.spine.cla.constants import COP_ARM_SPEED_RAD_S, COP_BAND_M, COP_FULL_M
from shintai.spine.cla.keyframes import Key, KeyframePlayer, WholeBodyKeys, key_vectors
from shintai.spine.cla.reach import ArmIK
from shintai.spine.control import SETPOINTS
from shintai.spine.robots import CLA

CAL_S = 0.3  # a short §4.6.4 zeroing for the tests (the scenarios take 1 s)


def test_keys_change_only_what_they_name_and_are_reached_on_time():
    keys = [Key(1.0, {"a": 1.0}, "one"), Key(0.5, {"b": -2.0}, "two")]
    np.testing.assert_allclose(key_vectors(("a", "b"), {"b": 0.5}, keys), [[1.0, 0.5], [1.0, -2.0]])
    with pytest.raises(ValueError, match="unknown joints"):
        key_vectors(("a",), {}, [Key(1.0, {"c": 1.0})])
    player = KeyframePlayer(("a", "b"), {"b": 0.5}, keys)
    player.reset({"t": 0.0})
    assert player.update({"t": 0.5})["pose"][0] == pytest.approx(0.5)  # half way by minimum jerk
    assert player.label(0.5) == "one" and player.label(1.2) == "two"
    np.testing.assert_allclose(player.update({"t": 1.5})["pose"], [1.0, -2.0])


def test_reflex_moves_the_arms_back_when_the_cop_is_ahead_and_rests_near_the_centre():
    assert CB.reflex_rate(0.5 * COP_BAND_M) == 0.0
    assert CB.reflex_rate(COP_FULL_M) == pytest.approx(-COP_ARM_SPEED_RAD_S)  # ahead → arms back
    assert CB.reflex_rate(-2 * COP_FULL_M) == pytest.approx(COP_ARM_SPEED_RAD_S)  # behind → forward, capped
    assert CB.reflex_rate(float("nan")) == 0.0  # no CoP (off the ground): no reflex
    for enabled in (True, False):
        reflex = CB.ArmSwingReflex(lambda snap: 0.02, enabled=enabled)
        reflex.reset({"t": 0.0})
        out = reflex.update({"t": 1.0})
        assert set(out) == {"shoulder_pitch_r", "shoulder_pitch_l"}
        assert (out["shoulder_pitch_r"] < 0) if enabled else (out["shoulder_pitch_r"] == 0.0)


def test_the_spine_brings_the_hand_to_the_floor_object_and_the_place_spot_on_the_model():
    body = ClaBody("seated", spec=PP.seated_spec())
    scene = PP.set_scene(body)
    assert scene["floor_z"] > 0.2  # the floor just under the soles (§5.2.1)
    ik = ArmIK(body.model, body.data, SPINE_JOINTS, CLA.n)
    _, gaps_spine = PP.keys(ik, scene, spine=True)
    _, gaps_locked = PP.keys(ik, scene, spine=False)
    assert gaps_spine["reach"] < 1e-3 and gaps_spine["lower"] < 1e-3
    assert gaps_locked["reach"] > 0.05  # the arm alone stays ≈ 9 cm above the object (§5.2.5)


def _whole_deg(body):
    return np.degrees(body.theta().reshape(CLA.n, 3).sum(axis=0))


def _run(body, control, keys, seconds):
    """Play ``keys`` for ``seconds``: the whole-spine (roll, pitch, yaw) change it made [deg]."""
    start = {**start_targets(body.posture), "spine_roll": 0.0, "spine_pitch": 0.0, "spine_yaw": 0.0}
    zero = CLA.model.lengths(np.zeros(3 * CLA.n))
    player = WholeBodyKeys(CLA.model, zero, LIMB_JOINTS, start, keys)
    before = _whole_deg(body)
    Loop(body, stages=[[player], [control]], channels=SETPOINTS).run(seconds)
    return _whole_deg(body) - before


def test_pick_place_switch_locks_the_spine_and_the_free_spine_bends_sideways():
    """Both variants as the scenario builds them, the keys' sideways bend commanded for 1 s."""
    bend = [Key(0.8, {"spine_roll": math.radians(60.0)})]
    free_body, _, _, free_control, _, _ = PP.build(True, calibration_s=CAL_S)
    locked_body, _, _, locked_control, _, _ = PP.build(False, calibration_s=CAL_S)
    assert locked_body.spine_locked and not free_body.spine_locked
    assert _run(free_body, free_control, bend, 1.0)[0] > 30.0
    assert np.abs(_run(locked_body, locked_control, bend, 1.0)).max() < 1.5


def test_roll_over_switch_locks_the_spine_and_the_free_twist_turns_the_shoulders_up():
    twist = [Key(0.5, {"spine_yaw": math.radians(-60.0)})]
    turned = {}
    for spine in (True, False):
        body, _, control = RO.build(spine, calibration_s=CAL_S)
        assert body.spine_locked != spine
        assert RO.turn_deg(body, "link0") < 5.0  # lying on its back
        whole = _run(body, control, twist, 0.8)
        turned[spine] = RO.turn_deg(body, f"link{CLA.n}")
        if not spine:
            assert np.abs(whole).max() < 1.5
    assert turned[True] > 15.0 and turned[False] < 5.0


def test_roll_over_genes_decode_to_the_hand_made_keys_and_prone_lies_on_its_front():
    """The hand-made keys are a genome (the search's initial individual); lay(prone) puts the front down."""
    keys = RO.keys(RO.HAND_MADE)
    assert [k.label for k in keys] == ["rest", "raise", "twist", "follow", "lie", "hold"]
    assert [k.duration_s for k in keys[1:4]] == pytest.approx([1.5, 1.5, 1.5])
    assert keys[1].targets == pytest.approx({"shoulder_pitch_r": 2.8, "shoulder_pitch_l": 1.57, "hip_l": 1.0,
                                             "knee_l": 1.2})
    assert keys[2].targets["spine_yaw"] == pytest.approx(math.radians(-60.0))
    assert keys[3].targets == pytest.approx({"spine_yaw": math.radians(40.0), "spine_roll": 0.0, "hip_l": 1.8,
                                             "hip_r": 0.0})
    assert set(keys[4].targets.values()) == {0.0} and len(keys[4].targets) == 8  # lie: everything back to 0
    assert RO.keys(np.ones(RO.N_GENES))[2].targets["spine_yaw"] == pytest.approx(math.radians(90.0))
    body, _, _ = RO.build(True, calibration_s=0.01, prone=True)
    assert RO.turn_deg(body, "link0") > 175.0 and RO.turn_deg(body, f"link{CLA.n}") > 175.0


def test_roll_fitness_counts_both_halves_and_the_pelvis_peak():
    o = {"final_pelvis_turn_deg": 10.0, "final_shoulder_turn_deg": 50.0, "max_pelvis_turn_deg": 40.0}
    assert RO.roll_fitness(o) == pytest.approx(30.0 + 20.0)


def test_cop_balance_reflex_answers_the_soles():
    """Standing, the reflex's arm offset moves against the sole CoP's front–back error (eq. 3.5); switched off,
    the arms hold."""
    for swing in (True, False):
        body, player, reflex, control, centre = CB.build(swing, cycles=1, calibration_s=CAL_S)
        Loop(body, stages=[[player, reflex], [control]], channels=SETPOINTS).run(0.6)
        snap = body.snapshot()
        weight = body.model.body_subtreemass[body.id("body", "link0")] * 9.81
        assert snap["sole_force"].sum() == pytest.approx(weight, rel=0.15)
        error = snap["cop"][0] - centre
        if not swing:
            assert reflex.offset == 0.0
        elif abs(error) > COP_BAND_M:
            assert np.sign(reflex.offset) == -np.sign(error)
