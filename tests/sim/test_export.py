"""`shintai model`: every registered body model exports to MJCF that MuJoCo reloads with the same sizes."""

import mujoco
import pytest

from shintai.cli import main
from shintai.sim.export import compiled, export, load_models

SIZES = ("nq", "nv", "nu", "na", "nbody", "njnt", "ngeom", "nsite", "nsensor", "ntendon", "neq", "nmesh", "nkey")


@pytest.mark.parametrize("model_id", sorted(load_models()))
def test_exported_model_reloads_with_the_same_sizes(model_id, tmp_path):
    _, original = compiled(model_id)
    path = export(model_id, tmp_path)
    reloaded = mujoco.MjModel.from_xml_path(str(path))
    assert {s: getattr(reloaded, s) for s in SIZES} == {s: getattr(original, s) for s in SIZES}
    assert reloaded.opt.timestep == original.opt.timestep


def test_model_command_lists_and_exports(tmp_path, capsys):
    assert main(["model", "--list"]) == 0
    assert "sim.wall-corner" in capsys.readouterr().out
    assert main(["model", "sim.wall-corner", "--out", str(tmp_path)]) == 0
    assert (tmp_path / "sim.wall-corner.xml").exists()
    assert main(["model", "nope", "--out", str(tmp_path)]) == 2


def test_exported_scene_starts_where_the_body_starts(tmp_path):
    """What a builder sets on the compiled model (the seated keyframe, the holds' relative poses) is
    exported too: the reloaded HRP2-on-tricycle scene starts in the same state and stays seated."""
    from shintai.humanoid.riding import build_riding

    body = build_riding()
    reloaded = mujoco.MjModel.from_xml_path(str(export("humanoid.hrp2-tricycle", tmp_path)))
    key = reloaded.key("ride")
    # MJCF prints 6 significant digits; anchors and relative poses are eq_data[:, :10]
    assert key.qpos == pytest.approx(body.model.key("ride").qpos, abs=1e-5)
    assert reloaded.eq_data[:, :10] == pytest.approx(body.model.eq_data[:, :10], abs=1e-5)
    data = mujoco.MjData(reloaded)
    mujoco.mj_resetDataKeyframe(reloaded, data, key.id)
    mujoco.mj_step(reloaded, data, 250)  # 0.25 s held by the keyframe's servo targets
    assert abs(data.qpos - key.qpos).max() < 0.05
