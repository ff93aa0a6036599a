"""sim.wall-force: the search index on a MuJoCo contact (spec 000 §5.4 checks 1, 2, 10)."""

import json

import numpy as np
import pytest

from shintai.cli import main
from shintai.sim.corner import build_corner, contact_start, probe_sign, settle


def test_probed_sign_is_minus_identity_and_slope_is_the_servo_stiffness():
    sgn, slope = probe_sign(settle_s=0.3)
    assert np.array_equal(sgn, -np.eye(3))
    assert np.allclose(slope, -3000.0, rtol=0.02)  # servo K_p = 3000 N/m in series with a stiff contact


def test_wrist_sensor_reads_the_contact_force():
    body = build_corner()
    f = settle(body, contact_start(), 0.5)
    assert np.allclose(f, body.contact_force("hand"), atol=1e-3)
    assert f[0] < 0 and f[1] < 0 and f[2] > 0  # walls push the hand back, the floor pushes it up


def test_short_run_holds_its_checks_and_renders(tmp_path):
    code = main(["run", "sim.wall-force", "--out", str(tmp_path), "--set", "updates=8", "--quiet", "--video"])
    m = json.loads((tmp_path / "metrics.json").read_text())
    assert code == 0, [c for c in m["checks"] if not c["ok"]]
    assert m["metrics"]["escape_reference_shift_m"] < -0.009
    assert (tmp_path / "video.mp4").stat().st_size > 5000 and (tmp_path / "wall_force.png").exists()
    film = json.loads((tmp_path / "video.json").read_text())  # rendered after the run: what it shows
    assert film["frames"] >= 2 and film["speed"] >= 1 and (tmp_path / "video.poster.jpg").is_file()


def test_an_update_period_off_the_control_step_is_a_parameter_error():
    from shintai.scenarios.registry import ParameterError, get

    with pytest.raises(ParameterError, match="update_s must be a whole multiple of the 4 ms control step"):
        get("sim.wall-force").resolve({"update_s": "0.05"})
