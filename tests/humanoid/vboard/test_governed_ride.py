"""MLC speed governing on the V-BOARD ride (seed 000 §6.4, Figs. 6.15–6.17): the gated governor, the analysis
helpers (Routh–Hurwitz intervals, u_I jumps, the Fig. 6.17 replay) and short runs of the two scenarios."""

import numpy as np
import pytest

from shintai.core.recorder import Recorder
from shintai.core.runtime import Loop
from shintai.humanoid.learning.speed_governing import IdentifiedScooterPlant
from shintai.humanoid.vboard.governed_ride import (
    governed_ride,
    governor_series,
    mlc_params,
    plant_values,
    replay_integrator,
    ui_jumps,
    unstable_intervals,
)
from shintai.humanoid.vboard.governor import GatedGovernor
from shintai.scenarios.registry import ParameterError, get
from shintai.scenarios.runner import run_scenario

TABLE = plant_values("table6.2")


def test_governor_is_off_until_the_start_then_runs_the_pid():
    """§6.4.1: level 2 (governor off) until learning starts; then Eq. 6.2 → Eq. 6.5 increments."""
    gov = GatedGovernor(lambda s: s["t"] >= 0.1, gains0=((2.0, 0.0, 0.0), (0.0, 0.0, 0.0)), learn=False)
    out = gov.update({"t": 0.0, "v": 0.5, "omega": 0.0})
    assert np.all(out["foot_pitch"] == 0.0) and gov.t_start is None
    out = gov.update({"t": 0.1, "v": 0.5, "omega": 0.0})
    assert gov.t_start == 0.1
    np.testing.assert_allclose(out["foot_pitch"], [-1.0, -1.0])  # u_v = 2·(0 − 0.5) on both soles


def test_unstable_intervals_of_the_routh_hurwitz_flag():
    t = np.arange(10) * 0.5
    flag = np.array([-1, -1, 1, 1, -1, -1, -1, 1, 1, -1])
    assert unstable_intervals(t, flag) == [(0.0, 1.0), (2.0, 3.5), (4.5, 4.5)]
    assert unstable_intervals(t, np.ones(10)) == []


def learned_on_identified_plant(mode, seconds=9.0):
    """MLC on Table 6.2's plant (no humanoid) with a constant board disturbance, recording the governor."""
    body = IdentifiedScooterPlant(disturbance=(1e-4, 1e-4))
    gov = GatedGovernor(lambda s: True, params=mlc_params(TABLE), mode=mode)
    rec = Recorder()
    Loop(body, [gov], rec).run(duration=seconds)
    return governor_series(rec, "v"), gov


def test_replay_reproduces_the_run_and_the_saturation_jumps_where_the_correction_does_not():
    s, gov = learned_on_identified_plant("corrected")
    KI = [b.gains[1] for b in gov.mlc["v"].batches]
    assert len(KI) == 4 and KI[1] > KI[0] > 0  # two I-gain increases, the second from K_I > 0
    np.testing.assert_allclose(replay_integrator(s, "corrected"), s["uI"], rtol=0, atol=1e-15)
    jumps = ui_jumps(s)
    assert jumps.size == sum(1 for a, b in zip([0.0] + KI, KI) if b > a)
    sat = dict(s, uI=replay_integrator(s, "saturated"))
    plain = dict(s, uI=replay_integrator(s, "plain"))
    # Eq. 6.38 vs 6.42 vs 6.36 at the increases (Fig. 6.17): corrected ≪ saturated ≪ plain
    assert jumps.max() < 0.1 * ui_jumps(sat).max() < 0.1 * ui_jumps(plain).max()
    s_closed, _ = learned_on_identified_plant("saturated")
    # a closed-loop saturated run has the same e up to its first saturated jump (then its u_I differs)
    np.testing.assert_allclose(ui_jumps(s_closed)[:2], ui_jumps(sat)[:2], rtol=1e-9)


def test_bad_values_raise_one_line():
    with pytest.raises(ValueError, match="^plant must be"):
        plant_values("u")
    with pytest.raises(ValueError, match="^mode must be"):
        governed_ride(TABLE, mode="x", lift=False)
    for sid, key, text in (("humanoid.speed-governing", "plant", "thesis"),
                           ("humanoid.speed-governing", "eta_scale", "0"),
                           ("humanoid.speed-governing", "boarding", "maybe"),
                           ("humanoid.integrator-comparison", "start", "floor"),
                           ("humanoid.integrator-comparison", "learn_s", "nan")):
        with pytest.raises(ParameterError) as info:
            get(sid).resolve({key: text})
        assert "\n" not in str(info.value)


def test_speed_governing_runs_short(smoke):
    """The smoke run, one mini-batch after the lift lets go: the learn variant updates the gains once, the 'off'
    baseline (zero gains, level 2) not at all."""
    run = smoke("humanoid.speed-governing")
    assert "error" not in run.result, run.result.get("error")
    m = run.result["metrics"]
    assert m["v_batches_learn"] == 1 and m["omega_batches_learn"] == 1 and m["v_batches_off"] == 0
    assert m["v_K_P_learn"] + m["v_K_I_learn"] + m["v_K_D_learn"] > 0.0 and m["plant_K_v"] == TABLE["K_v"]
    assert 2.0 < m["ride_learn_s"] < 2.2 and m["fallen_learn"] == 0
    assert m["v_unstable_learn_s"] > 1.99  # gains from 0: outside Eq. 6.41 for the whole first batch
    assert m["v_last_unstable_start_learn_s"] == pytest.approx(0.0, abs=0.01)
    assert (run.out / "fig6_15_learn.png").exists()


def test_after_self_boarding_learning_starts_when_both_feet_have_landed():
    """Fig. 6.16's start (§6.4.1): the robot boards from the floor (ch. 5's SLC boarding); the governor stays off
    (level 2) until the right foot's sole-force guard (f_Rz > 25 N, SLC's stop), then runs with the learned D."""
    ride = governed_ride(TABLE, boarding="slc", noise=False)
    st, sched = ride.boarding
    assert ride.lift is None and ride.body is st.body
    loop = Loop(ride.body, stages=ride.stages, channels=ride.channels)
    loop.run(3.0)
    assert sched.state == "learning" and ride.governor.t_start is None  # the right foot is still in the air
    assert ride.foot_pitch.theta.tolist() == [0.0, 0.0]
    loop.run(0.5)
    assert sched.t_stop is not None and 3.1 < sched.t_stop < 3.45  # ≈3.38 s (the soles held on the pads; ≈3.2 s creeping)
    assert ride.governor.t_start == pytest.approx(sched.t_stop + 0.004)  # the next tick (the governor runs first)
    learned = sched.D[1]
    assert learned > 22.0 and sched.D[3] == learned and not ride.fallen()
    assert st.damping.feet["L"].D[1] == st.damping.feet["R"].D[1] == learned  # the damping took D from SLC


def test_integrator_comparison_runs_short(smoke):
    run = smoke("humanoid.integrator-comparison")
    assert "error" not in run.result, run.result.get("error")
    m = run.result["metrics"]
    for k in ("max_ui_jump_corrected", "max_ui_jump_saturated", "max_ui_jump_saturated_replay", "eq643_residual"):
        assert np.isfinite(m[k]), k
    assert m["corrected_replay_error"] < 1e-12 and m["eq643_residual"] < 1e-12
    assert (run.out / "fig6_17.png").exists()


def test_a_fall_ends_the_run_and_keeps_what_was_computed(tmp_path, monkeypatch):
    """Issue 13's 'a fall ends the run with what was computed kept', on the ride's stop rule: a fall (here declared
    at 0.6 s, before the learning starts) stops the run there; metrics, pictures and the log are still written.
    A run of its own (the fall is patched in), not the shared smoke run."""
    from shintai.humanoid.balance.standing import Standing

    monkeypatch.setattr(Standing, "fallen", lambda self: self.body.t >= 0.6)
    out = run_scenario("humanoid.speed-governing", out=tmp_path, quiet=True,
                       overrides={"learn_s": "2.1", "plant": "table6.2", "baseline": "false", "boarding": "false"})
    assert "error" not in out, out.get("error")
    m = out["metrics"]
    assert m["fallen_learn"] == 1 and m["v_batches_learn"] == 0 and out["sim_time_s"] == pytest.approx(0.6, abs=0.01)
    assert (tmp_path / "fig6_15_learn.png").exists() and (tmp_path / "log.npz").exists()
