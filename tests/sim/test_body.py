"""MujocoBody: snapshot/command conventions, run-time switching, contact forces, divergence."""

import mujoco
import numpy as np
import pytest

from shintai.core import Loop, Module, Recorder, SimulationDiverged
from shintai.core.runtime import FunctionModule
from shintai.sim import MujocoBody

# A pendulum turning about z (gravity does not load it) with a position servo, and a second
# pendulum driven by a torque motor; sensors at a tip site.
PENDULUM = """
<mujoco>
  <option timestep="0.002"/>
  <worldbody>
    <body name="arm">
      <joint name="hinge" type="hinge" axis="0 0 1" damping="0.1"/>
      <geom type="capsule" fromto="0 0 0 0.5 0 0" size="0.03" mass="1"/>
      <site name="tip" pos="0.5 0 0"/>
    </body>
    <body name="arm2" pos="0 0 1">
      <joint name="hinge2" type="hinge" axis="0 1 0"/>
      <geom type="capsule" fromto="0 0 0 0 0 -0.3" size="0.02" mass="0.5"/>
    </body>
  </worldbody>
  <actuator>
    <position name="servo" joint="hinge" kp="100" kv="5"/>
    <motor name="motor" joint="hinge2"/>
  </actuator>
  <sensor>
    <jointpos name="angle" joint="hinge"/>
    <framequat name="tip_quat" objtype="site" objname="tip"/>
    <accelerometer name="tip_acc" site="tip"/>
  </sensor>
  <keyframe><key name="bent" qpos="0.3 -0.2"/></keyframe>
</mujoco>
"""

BOX_MASS = 2.0
BOX = f"""
<mujoco>
  <option timestep="0.002"/>
  <worldbody>
    <geom name="floor" type="plane" size="5 5 0.1"/>
    <body name="box" pos="0 0 0.1">
      <freejoint name="free"/>
      <geom name="box_geom" type="box" size="0.1 0.1 0.1" mass="{BOX_MASS}"/>
    </body>
    <body name="far" pos="3 0 0.1">
      <freejoint/>
      <geom type="sphere" size="0.1" mass="1"/>
    </body>
  </worldbody>
</mujoco>
"""

# A ball held to the world by a weld, and one hanging from it by a connect.
HELD = """
<mujoco>
  <option timestep="0.002"/>
  <worldbody>
    <body name="ball" pos="0 0 1">
      <freejoint/>
      <geom type="sphere" size="0.05" mass="1"/>
    </body>
  </worldbody>
  <equality>
    <weld name="grip" body1="ball"/>
  </equality>
</mujoco>
"""


def settle(body: MujocoBody, seconds: float) -> None:
    for _ in range(int(round(seconds / body.dt))):
        body.step()


def test_snapshot_keys_and_shapes():
    body = MujocoBody(PENDULUM)
    snap = body.snapshot()
    assert snap["t"] == 0.0
    assert snap["qpos"].shape == (2,) and snap["qvel"].shape == (2,) and snap["ctrl"].shape == (2,)
    assert snap["angle"].shape == (1,) and snap["tip_quat"].shape == (4,) and snap["tip_acc"].shape == (3,)
    assert isinstance(snap["q:hinge"], float) and isinstance(snap["dq:hinge2"], float)
    np.testing.assert_allclose(snap["tip_quat"], [1, 0, 0, 0], atol=1e-12)


def test_snapshot_is_a_copy():
    body = MujocoBody(PENDULUM)
    snap = body.snapshot()
    body.apply({"servo": 0.5})
    settle(body, 0.1)
    assert snap["qpos"][0] == 0.0 and snap["ctrl"][0] == 0.0 and snap["angle"][0] == 0.0


def eager_snapshot(body: MujocoBody) -> dict:
    """The snapshot as it was formed before its entries were read lazily: every entry at once."""
    values = np.concatenate((body.data.qpos, body.data.qvel, body.data.ctrl, body.data.sensordata))
    snap = {"t": body.data.time}
    snap.update((k, values[w]) for k, w in body._views)
    snap.update((k, values[i:i + 1].tolist()[0]) for k, i in body._scalars)
    return snap


def same_entries(a: dict, b: dict) -> bool:
    return list(a) == list(b) and all(np.array_equal(a[k], b[k]) and type(a[k]) is type(b[k]) for k in a)


def test_a_lazy_snapshot_reads_as_the_eager_dict():
    body = MujocoBody(PENDULUM)
    body.apply({"servo": 0.5})
    settle(body, 0.05)
    eager = eager_snapshot(body)
    snap = body.snapshot()
    assert len(snap) == len(eager) and "q:hinge" in snap and "nothing" not in snap and 3 not in snap
    assert snap.get("q:hinge") == eager["q:hinge"] and snap.get("nothing", 7) == 7
    assert snap["qpos"] is snap["qpos"]  # formed once, then kept
    with pytest.raises(KeyError):
        snap["nothing"]
    view = snap.copy()  # the Loop's view: unread entries stay unread, written ones stay in this copy
    view["ref"] = np.ones(2)
    assert "ref" not in snap and np.array_equal(view["qvel"], eager["qvel"])
    assert same_entries(dict(snap), eager) and same_entries({**view}, {**eager, "ref": np.ones(2)})
    assert list(body.snapshot()) == list(eager) and same_entries(dict(body.snapshot().items()), eager)
    import pickle
    assert same_entries(pickle.loads(pickle.dumps(body.snapshot())), eager)


def test_a_lazy_snapshot_keeps_an_overwritten_entry_in_its_place():
    body = MujocoBody(PENDULUM)
    snap = body.snapshot()
    snap["qvel"] = np.full(2, 9.0)
    snap["extra"] = 1.0
    keys = list(snap)
    assert keys[:2] == ["t", "qpos"] and keys[2] == "qvel" and keys[-1] == "extra" and snap["qvel"][0] == 9.0
    del snap["qpos"]
    assert "qpos" not in snap and snap.get("qpos") is None


def test_free_joint_keys_are_vectors():
    snap = MujocoBody(BOX).snapshot()
    assert snap["q:free"].shape == (7,) and snap["dq:free"].shape == (6,)


def test_position_servo_converges_to_command():
    body = MujocoBody(PENDULUM)
    body.apply({"servo": 0.7})
    settle(body, 2.0)
    snap = body.snapshot()
    assert abs(snap["q:hinge"] - 0.7) < 1e-3
    assert abs(snap["angle"][0] - 0.7) < 1e-3
    assert abs(body.joint_qpos("hinge") - 0.7) < 1e-3


def test_dt_is_substeps_times_timestep():
    body = MujocoBody(PENDULUM, substeps=3)
    assert body.dt == pytest.approx(3 * 0.002)
    for _ in range(10):
        body.step()
    assert body.t == pytest.approx(10 * body.dt)
    with pytest.raises(ValueError, match="substeps"):
        MujocoBody(PENDULUM, substeps=0)


def test_before_physics_hooks_run_before_every_physics_step():
    """An embedded controller (a plant's firmware) sees every physics step's state and its ctrl
    acts in that step: a torque feedback written each 2 ms step holds the motor's pendulum up."""
    body = MujocoBody(PENDULUM, substeps=3)
    times = []

    def firmware():
        times.append(body.data.time)
        body.data.ctrl[1] = -20.0 * body.data.qpos[1] - 1.0 * body.data.qvel[1]

    body.data.qpos[1] = 0.2
    body.before_physics.append(firmware)
    for _ in range(150):
        body.step()
    assert times[:4] == pytest.approx([0.0, 0.002, 0.004, 0.006])
    assert len(times) == 3 * 150
    assert abs(body.joint_qpos("hinge2")) < 0.01  # settled under the feedback, not swinging ±0.2


def test_command_channels():
    body = MujocoBody(PENDULUM)
    body.apply({"ctrl": [0.1, 0.2]})
    np.testing.assert_allclose(body.data.ctrl, [0.1, 0.2])
    body.apply({"motor": 0.5})  # an unaddressed actuator keeps its value
    np.testing.assert_allclose(body.data.ctrl, [0.1, 0.5])
    body.apply({"ctrl": [0.1, 0.2], "servo": 0.3})  # what addresses one actuator adds up
    np.testing.assert_allclose(body.data.ctrl, [0.4, 0.2])


def test_bad_commands_raise_one_line_errors():
    body = MujocoBody(PENDULUM)
    with pytest.raises(KeyError, match=r"unknown command channel 'elbow'; valid: ctrl, servo, motor") as err:
        body.apply({"elbow": 1.0})
    assert "\n" not in str(err.value)
    with pytest.raises(ValueError, match="shape"):
        body.apply({"ctrl": [1.0, 2.0, 3.0]})
    with pytest.raises(ValueError, match="scalar"):
        body.apply({"servo": [1.0, 2.0]})


def test_other_unknown_names_raise_key_errors():
    body = MujocoBody(PENDULUM)
    for call in (lambda: body.set_equality("nope", True), lambda: body.set_contact("nope", False),
                 lambda: body.site_pos("nope"), lambda: body.reset("nope")):
        with pytest.raises(KeyError, match="unknown .* 'nope'; valid"):
            call()


def test_sources_spec_path_and_keyframe(tmp_path):
    path = tmp_path / "pendulum.xml"
    path.write_text(PENDULUM)
    from_path = MujocoBody(path, keyframe="bent")
    from_spec = MujocoBody(mujoco.MjSpec.from_string(PENDULUM), keyframe=0)
    for body in (from_path, from_spec):
        np.testing.assert_allclose(body.snapshot()["qpos"], [0.3, -0.2])
    with pytest.raises(FileNotFoundError, match="MJCF file not found"):
        MujocoBody(tmp_path / "missing.xml")


def test_kinematic_helpers():
    body = MujocoBody(PENDULUM, keyframe="bent")
    np.testing.assert_allclose(body.site_pos("tip"), 0.5 * np.array([np.cos(0.3), np.sin(0.3), 0]), atol=1e-12)
    assert body.site_xmat("tip").shape == (3, 3)
    np.testing.assert_allclose(body.body_pos("arm2"), [0, 0, 1])
    jacp, jacr = body.jac_site("tip")
    assert jacp.shape == (3, 2) and jacr.shape == (3, 2)
    np.testing.assert_allclose(jacr[:, 0], [0, 0, 1])  # tip rotates about z with the hinge


def test_box_on_floor_contact_force_is_mg_up():
    body = MujocoBody(BOX)
    settle(body, 0.5)
    mg = BOX_MASS * 9.81
    np.testing.assert_allclose(body.contact_force("box"), [0, 0, mg], atol=1e-3 * mg)
    np.testing.assert_allclose(body.contact_force("box", "world"), [0, 0, mg], atol=1e-3 * mg)
    np.testing.assert_allclose(body.contact_force("world", "box"), [0, 0, -mg], atol=1e-3 * mg)
    np.testing.assert_allclose(body.contact_force("box", "far"), 0.0)


def test_disabled_contact_lets_the_box_fall_through_and_comes_back():
    body = MujocoBody(BOX)
    body.set_contact("box_geom", False)
    settle(body, 0.5)
    assert body.body_pos("box")[2] < -0.5
    body.set_contact("box_geom", True)
    assert body.model.geom_contype[body.id("geom", "box_geom")] == 1
    body.reset()
    settle(body, 0.5)
    assert abs(body.body_pos("box")[2] - 0.1) < 0.01


def test_released_weld_lets_the_ball_fall():
    body = MujocoBody(HELD)
    settle(body, 0.3)
    assert abs(body.body_pos("ball")[2] - 1.0) < 1e-3  # held up
    body.set_equality("grip", False)
    settle(body, 0.3)
    z = body.body_pos("ball")[2]
    assert z < 1.0 - 0.5 * 9.81 * 0.3**2 * 0.9  # free fall


def test_injected_nan_raises_with_time_and_joint(monkeypatch, tmp_path):
    monkeypatch.chdir(tmp_path)  # MuJoCo writes MUJOCO_LOG.TXT on its first warning
    body = MujocoBody(PENDULUM)
    settle(body, 0.1)
    body.data.qpos[1] = np.nan
    with pytest.raises(SimulationDiverged, match=r"t=0\.1000 s: MuJoCo warning bad qpos .* qpos\[1\] \(joint 'hinge2'\)"):
        body.step()


def test_non_finite_integrated_state_raises(monkeypatch):
    body = MujocoBody(PENDULUM)
    real_step = mujoco.mj_step

    def step_to_inf(m, d, nstep=1):
        real_step(m, d, nstep)
        d.qvel[0] = np.inf

    monkeypatch.setattr(mujoco, "mj_step", step_to_inf)
    with pytest.raises(SimulationDiverged, match=r"t=0\.0000 s: NaN, Inf or huge value in qvel\[0\] = inf \(joint 'hinge'\)"):
        body.step()


class Kick(Module):
    """Logs the angle every step; after ``at`` seconds commands an absurd torque."""

    def __init__(self, at: float):
        super().__init__("kick")
        self.at = at

    def update(self, snapshot):
        self.log(snapshot["t"], angle=snapshot["q:hinge2"])
        return {"motor": 1e12 if snapshot["t"] >= self.at else 0.0}


def test_absurd_torque_diverges_in_a_loop_and_the_log_survives(monkeypatch, tmp_path):
    monkeypatch.chdir(tmp_path)
    body = MujocoBody(PENDULUM, substeps=2)
    recorder = Recorder()
    loop = Loop(body, [Kick(at=0.099)], recorder)
    with pytest.raises(SimulationDiverged, match=r"bad ctrl .* actuator 1 \(actuator 'motor'\)"):
        loop.run(1.0)
    times = recorder.times("angle")
    assert len(times) == 26 and times[-1] == pytest.approx(0.1)


def test_body_runs_in_a_loop():
    body = MujocoBody(PENDULUM, substeps=2)
    servo = FunctionModule(lambda s: {"servo": 0.4}, name="servo")
    loop = Loop(body, [servo], base={"ctrl": np.zeros(2)})
    assert loop.run(1.5) == 375
    assert body.t == pytest.approx(1.5)
    assert abs(body.joint_qpos("hinge") - 0.4) < 1e-3


def test_sensor_named_like_a_snapshot_key_is_refused():
    xml = PENDULUM.replace('<jointpos name="angle"', '<jointpos name="qpos"')
    with pytest.raises(ValueError, match=r"clash with snapshot keys: \['qpos'\]"):
        MujocoBody(xml)
