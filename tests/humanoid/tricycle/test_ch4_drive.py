"""Seed 000 ch. 4 scenarios: registration, the drive parameter, posture-steps' smoke ride (the chest
posture control in parallel with driving lowers the trunk roll on the first step), the legs' Eq. 4.22
crank target from a commanded crank rate, and the navigation run with the legs (stops at the goal)."""

import pytest

from shintai.scenarios.registry import ParameterError, get

IDS = ("humanoid.sitting-recovery", "humanoid.posture-steps", "humanoid.obstacle-navigation",
       "humanoid.small-obstacle")


@pytest.mark.parametrize("sid", IDS)
def test_registered_with_drive_parameter(sid):
    sc = get(sid)
    assert sc.param("drive").choices == ("motor", "legs")
    with pytest.raises(ParameterError):
        sc.resolve({"drive": "bicycle"})


def test_posture_steps_short(smoke):
    """The smoke run (8 s, past the step)."""
    out = smoke("humanoid.posture-steps").result
    m = out["metrics"]
    assert "error" not in out and out["params"]["drive"] == "legs"
    assert m["max_crank_lag_with_deg"] < 45  # the legs keep the crank near its Eq. 4.22 target
    assert m["max_vehicle_roll_with_deg"] > 1.0  # the rear-left wheel is on the 10 mm step
    assert m["max_trunk_roll_with_deg"] < m["max_trunk_roll_without_deg"]
    assert m["rms_trunk_roll_with_deg"] < 0.5 * m["rms_trunk_roll_without_deg"]
    assert m["overturned_with"] == 0 and m["overturned_without"] == 0


def test_lead_pedal_follows_commanded_crank_rate():
    """Eq. 4.22 from ω_c^ref: the target reaches θ_c + Δt ω_c^ref at the end of the sample (linearly),
    and stays at the measured angle when the command is 0 (the legs hold the crank)."""
    from shintai.humanoid.tricycle.ch4_drive import LEAD_DT, LeadPedal
    angle = {"theta": 0.3}
    lead = LeadPedal("legs", lambda s: angle["theta"], None)
    lead.reset({"t": 0.0, "ref:crank_rate": 0.5})
    assert lead.update({"t": 0.0, "ref:crank_rate": 0.5})["ref:crank_target"] == pytest.approx(0.3)
    half = lead.update({"t": LEAD_DT / 2, "ref:crank_rate": 0.5})["ref:crank_target"]
    assert half == pytest.approx(0.3 + 0.5 * 0.5 * LEAD_DT)  # halfway to θ_c + Δt ω_c^ref
    angle["theta"] = 0.6  # the crank followed; the next sample starts from the measured angle
    assert lead.update({"t": LEAD_DT, "ref:crank_rate": 0.0})["ref:crank_target"] == pytest.approx(0.6)
    assert lead.update({"t": 1.5 * LEAD_DT, "ref:crank_rate": 0.0})["ref:crank_target"] == pytest.approx(0.6)
    # a fixed ẋ^ref (the small obstacle) ignores the channel
    fixed = LeadPedal("drive", lambda s: 0.0, 0.3)
    fixed.reset({"t": 0.0})
    from shintai.humanoid.tricycle.navigation import crank_reference
    end = 0.999 * LEAD_DT  # the end of the first sample (at LEAD_DT the next one starts)
    assert fixed.update({"t": end, "ref:crank_rate": 0.0})["ref:crank_target"] == pytest.approx(
        crank_reference(0.0, 0.3, LEAD_DT), rel=2e-3)


def test_obstacle_navigation_with_legs_stops_at_goal():
    """The default drive (legs, Eq. 4.22 from the navigator's ω_c^ref) goes round the wall and stops: the
    experiment's rig on the true pose, ≈22 s of driving (longer than its 5 s smoke run, which ends before the
    wall; the slowest humanoid test)."""
    from shintai.humanoid.experiments import obstacle_navigation as navigation
    from shintai.scenarios.experiment import run_rig

    params = get("humanoid.obstacle-navigation").resolve({"max_s": "30", "pose": "true"})
    m = navigation.metrics({"run": run_rig(navigation.rig(params, "run", 0))}, params)
    assert params["drive"] == "legs"
    assert m["reached"] == 1 and m["final_speed_mps"] <= 0.05
    assert m["min_clearance_m"] > 0.0 and m["max_lateral_m"] > 0.5  # went round, not through
    assert m["max_foot_off_pedal_m"] < 0.1 and m["overturned"] == 0
