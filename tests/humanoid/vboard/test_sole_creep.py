"""Issue 26 item 5 (vboard.sole_creep): at level 2 with MuJoCo's soft contacts alone the soles creep on the pads, the
creep's difference is the pitch-torque difference that the damping turns into a turn; with no-slip (the default) the
soles hold and the turn does not grow. Both rides over the probe's 14 s (≈2 s of wall time each)."""

import pytest

from shintai.humanoid.vboard.ride import VboardRide
from shintai.humanoid.vboard.sole_creep import probe


@pytest.fixture(scope="module")
def creep():
    return probe()["readings"]


def test_soft_contacts_let_the_soles_creep_back(creep):
    for side in "lr":
        assert creep[f"creep_sole_{side}_mm_creep"] < -3.0, creep  # ≈ −5 mm in 13 s


def test_no_slip_holds_the_soles(creep):
    for side in "lr":
        assert abs(creep[f"creep_sole_{side}_mm_noslip"]) < 0.3, creep


def test_the_creep_difference_is_the_torque_difference(creep):
    """Link 2: at a steady speed the pressure stays over the axle, so τ_L − τ_R moves by −f̄_z (s_L − s_R)."""
    change, from_creep = creep["creep_tau_diff_change_nm_creep"], creep["creep_tau_diff_from_creep_nm_creep"]
    assert from_creep > 0.08, creep
    assert abs(change - from_creep) < 0.3 * from_creep, creep


def test_the_turn_grows_only_with_the_creep(creep):
    assert creep["creep_omega_final_creep"] > 0.1, creep  # the creep's sign: the left sole creeps further back
    assert creep["creep_max_abs_omega_noslip"] < 0.1, creep
    assert not creep["creep_fallen_creep"] and not creep["creep_fallen_noslip"]


def test_the_option_turns_no_slip_off():
    assert VboardRide(level=1, sole_creep=True, noise=False).body.model.opt.noslip_iterations == 0
    assert VboardRide(level=1, noise=False).body.model.opt.noslip_iterations > 0
