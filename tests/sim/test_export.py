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
