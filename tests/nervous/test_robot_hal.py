"""The robot description generated from the model (§6.3.2, C.1.3 robot2c) and the four HAL calls of §6.3.1
on the sim and dummy interfaces."""

import json
import math

import mujoco
import numpy as np
import pytest

from shintai.cli import main
from shintai.nervous import robots
from shintai.nervous.hal import DummyInterface, SimInterface, open_interface
from shintai.nervous.robot import describe_servos

TWO_JOINTS = """<mujoco><worldbody><body><joint name="h" type="hinge" range="-45 90"/><geom size=".1"/>
<body><joint name="s" type="slide" range="-0.2 0.3"/><geom size=".1"/></body></body></worldbody>
<actuator><position name="h_servo" joint="h" kp="10" kv="1"/><position name="s_servo" joint="s" kp="100"
ctrllimited="true" ctrlrange="-0.1 0.1"/><motor name="m" joint="h"/></actuator>
<sensor><jointpos name="enc" joint="h"/><accelerometer name="acc" site="x"/></sensor>
<worldbody><site name="x"/></worldbody></mujoco>"""


def test_a_description_is_read_from_the_model():
    model = mujoco.MjModel.from_xml_string(TWO_JOINTS)
    qpos = np.array([math.radians(30), 0.05])
    d = describe_servos(model, "two", "test", 0.002, qpos=qpos)
    assert d.names == ["h_servo", "s_servo"]  # position servos only, not the motor
    assert [x.unit for x in d.dofs] == ["deg", "mm"]
    assert d.lower.tolist() == pytest.approx([-45, -100]) and d.upper.tolist() == pytest.approx([90, 100])
    assert d.initial.tolist() == pytest.approx([30, 50])
    assert [(s.name, s.size, s.unit) for s in d.sensors] == [("angle-vector", 2, "deg|mm"), ("enc", 1, "rad"),
                                                             ("acc", 3, "m/s^2")]
    assert d.servo == {"kp": 55.0, "kv": 0.5}
    assert json.loads(d.to_json())["dofs"][1]["unit"] == "mm"


def test_every_robot_is_described_from_its_model():
    counts = {"arm3": 3, "cla": 8, "hrp2": 32, "snake": 17}
    for name, n in counts.items():
        d = robots.describe(name)
        assert d.n == n and len(set(d.names)) == n and np.all(d.lower < d.upper)
        assert np.all((d.initial >= d.lower) & (d.initial <= d.upper)), name
    cla = robots.describe("cla")
    assert cla.names[:2] == ["CLA-RF", "CLA-LF"] and cla.dofs[0].unit == "mm"
    assert {"tension", "current", "acc_chest", "acc_waist"} <= {s.name for s in cla.sensors}
    assert "17.46 µm of wire per count" in cla.sensor("angle-vector").conversion  # Table 3.2: π·6 mm/(16·67.49)
    assert robots.describe("hrp2").packet_period_s == 0.004
    with pytest.raises(KeyError, match="unknown robot 'r2d2'"):
        robots.describe("r2d2")


def test_describe_prints_it(capsys):
    assert main(["nervous", "describe", "arm3"]) == 0
    out = capsys.readouterr().out
    assert "packet period 1 ms, 3 DOF" in out and "j1" in out and "[     -150,       150] deg" in out
    assert main(["nervous", "describe", "arm3", "--json"]) == 0
    assert json.loads(capsys.readouterr().out)["robot"] == "arm3"
    assert main(["nervous", "describe", "nope"]) == 2


@pytest.mark.parametrize("kind", ["sim", "dummy"])
def test_the_four_calls(kind):
    i = open_interface(kind, "arm3")
    assert i.state.seq == 0 and i.state.t == 0.0
    sent = i.set_angle_vector([30.0, 200.0, -10.0])  # SetAngleVector clips to the limits
    assert sent.tolist() == [30.0, 150.0, -10.0]
    for _ in range(400):
        state = i.get_robot_state()
    assert state.seq == 400 and state.t == pytest.approx(0.4)
    assert state.reference.tolist() == [30.0, 150.0, -10.0]
    assert np.allclose(state.angle_vector, [30.0, 150.0, -10.0], atol=3.0)  # the servos got there
    assert i.close_interface() == 0


def test_the_sim_runs_the_body_and_the_dummy_echoes():
    sim, dummy = SimInterface("arm3"), DummyInterface("arm3")
    for i in (sim, dummy):
        i.open_interface()
        i.set_angle_vector([0.0, 90.0, 0.0])
        i.get_robot_state()
    assert dummy.state.angle_vector.tolist() == [0.0, 90.0, 0.0]
    assert sim.state.angle_vector[1] < 10.0  # 1 ms later the arm has barely moved
    assert set(sim.state.sensors) == set(dummy.state.sensors) == {"tip"}


def test_real_time_pacing_releases_a_packet_per_period():
    i = DummyInterface("arm3", realtime=True)
    i.open_interface()
    assert i.ready_in(now=100.0) == pytest.approx(0.001)  # packet 1 is due one period after packet 0
    i.get_robot_state()
    assert i.ready_in(now=100.0005) == pytest.approx(0.0015)
    i.get_robot_state()
    assert i.ready_in(now=100.0035) == 0.0  # late: at once
    assert i.ready_in(now=101.0) == 0.0 and i.resyncs == 1  # far behind: the clock restarts
    assert DummyInterface("arm3").ready_in() == 0.0  # as fast as possible


def test_unknown_interface_names_the_thesis_serial_links():
    with pytest.raises(KeyError, match="serinerve"):
        open_interface("serinerve", "arm3")
