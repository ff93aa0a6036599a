"""Seed 000 ch. 4 scenarios: registration, the drive parameter, and a short posture-steps ride
(the chest posture control in parallel with driving lowers the trunk roll on the first step)."""

import pytest

from shintai.scenarios.registry import ParameterError, get
from shintai.scenarios.runner import run_scenario

IDS = ("humanoid.sitting-recovery", "humanoid.posture-steps", "humanoid.obstacle-navigation",
       "humanoid.small-obstacle")


@pytest.mark.parametrize("sid", IDS)
def test_registered_with_drive_parameter(sid):
    sc = get(sid)
    assert sc.param("drive").choices == ("motor", "legs")
    with pytest.raises(ParameterError):
        sc.resolve({"drive": "bicycle"})


def test_posture_steps_short(tmp_path):
    out = run_scenario("humanoid.posture-steps", out=tmp_path, overrides={"max_s": "8"}, quiet=True)
    m = out["metrics"]
    assert "error" not in out
    assert m["max_vehicle_roll_with_deg"] > 1.0  # the rear-left wheel is on the 10 mm step
    assert m["max_trunk_roll_with_deg"] < m["max_trunk_roll_without_deg"]
    assert m["rms_trunk_roll_with_deg"] < 0.5 * m["rms_trunk_roll_without_deg"]
    assert m["overturned_with"] == 0 and m["overturned_without"] == 0
