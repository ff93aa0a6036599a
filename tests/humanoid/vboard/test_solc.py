"""SOLC (seed 000 §7.4.2, Table 7.7): the switcher INIT → SLC → MLC → DONE — its guards on the sole-force landings
(Fig. 5.5), SLC's D updates only while boarding, the right pitch taking the learned D, MLC then DONE on Eq. 6.32."""

import numpy as np
import pytest

from shintai.humanoid.learning.slc import SLC, SLCParams, SLCSchedule, slc_update
from shintai.humanoid.vboard.solc import SLC_WINDOW, MLCPhase, solc_switcher, switch_times
from shintai.scenarios.registry import ParameterError, get

DT = 0.004


def snapshots(f_l, f_r, t0=0.0):
    """Snapshots at 4 ms with the given sole forces (N), v = 0.1 m/s, ω = 0."""
    return [{"t": t0 + i * DT, "f_Lz": fl, "f_Rz": fr, "v": 0.1, "omega": 0.0}
            for i, (fl, fr) in enumerate(zip(f_l, f_r, strict=True))]


def test_the_switcher_boards_with_slc_then_governs_with_mlc_then_stops_learning():
    slc = SLCSchedule(SLC(SLCParams()), window=SLC_WINDOW)  # SLC on the switcher's window, after the damping
    gov = MLCPhase()
    sw = solc_switcher(SLCParams(), gov)
    stand, air = [300.0] * 50, [0.0] * 50  # 0.2 s each
    seq = snapshots(stand + air + stand + stand + stand, stand + stand + stand + air + stand)
    phases = []
    for snap in seq:
        out = sw.update(snap)
        # Rδ² > Qe²: SLC raises D (Eq. 5.17)
        slc.update({**snap, **out, "e_tau": np.array([0.0, 1.0, 0.0, 0.0]), "damping_delta": np.array([0.0, 0.02, 0.0, 0.0])})
        phases.append(sw.active)
    times = switch_times(sw)
    # the left foot lands at tick 100 (after 0.2 s in the air), the right at tick 200
    assert times["slc"] == pytest.approx(100 * DT) and times["mlc"] == pytest.approx(200 * DT)
    assert phases[99] == "init" and phases[100] == "slc" and phases[199] == "slc" and phases[200] == "mlc"
    # SLC ran once per tick of its phase, from D₀, and the right pitch took its D when MLC started
    D = 22.0
    for _ in range(100):
        D = slc_update(D, 1.0, 0.02, slc.slc.params.Q_prime, slc.slc.params.R_prime)
    assert slc.D[1] == pytest.approx(D) and D > 22.0
    assert slc.D[3] == slc.D[1] and slc.D[0] == slc.D[2] == 22.0
    # MLC observed its samples; when Eq. 6.32 holds on both axes the switcher goes to DONE and learning stops
    for a in ("v", "omega"):
        gov.mlc[a].converged = True
    sw.update(snapshots([300.0], [300.0], t0=len(seq) * DT)[0])
    assert sw.active == "done" and gov.learn is False and np.isfinite(switch_times(sw)["done"])


@pytest.mark.parametrize("key, value", [("eta_scale", "0"), ("max_s", "nan"), ("plant", "thesis")])
def test_bad_settings_are_one_line_parameter_errors(key, value):
    with pytest.raises(ParameterError) as info:
        get("humanoid.solc").resolve({key: value})
    assert "\n" not in str(info.value)


def test_solc_runs_short_through_the_boarding_into_mlc(smoke):
    """The smoke run (3.5 s): SLC from the left landing (≈1.98 s) to the right (≈3.22 s), then MLC; D rose, the
    right took it."""
    run = smoke("humanoid.solc")
    assert "error" not in run.result, run.result.get("error")
    m = run.result["metrics"]
    assert 1.9 < m["t_slc_start_s"] < 2.05 and 3.1 < m["t_mlc_start_s"] < 3.35 and m["converged"] == 0
    assert m["damping_final"] > m["damping_initial"] == 22.0 and m["right_took_learned_d"] == 1
    assert m["fallen"] == 0 and (run.out / "fig7_20.png").exists()
