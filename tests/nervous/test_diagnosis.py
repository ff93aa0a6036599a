"""The spine plugins on the simulated Cla: rotadjust levels the shoulders (§5.2.2), and the autonomous
diagnosis of §6.1.2 — slack take-up, over-current stop, tension-sensor and encoder faults — each found on a
fault injected into the simulation."""

import numpy as np
import pytest
from nervous_support import THESIS_RC, run, ticks

from shintai.nervous.commands import Client
from shintai.nervous.nerve import Nerve
from shintai.spine.actuators import tilt


@pytest.fixture
def cla():
    n = Nerve("cla", "sim")
    watcher = Client("watcher")
    n.clients.add(watcher)
    run(n, THESIS_RC)
    ticks(n, 300)
    return n, watcher


def roll_deg(nerve, packets=100):
    rolls = []
    for _ in range(packets):
        nerve.tick()
        rolls.append(tilt(nerve.state()["acc_chest"])[0])
    return float(np.degrees(np.mean(rolls)))


def test_rotadjust_levels_the_shoulders_on_a_tilted_seat(cla):
    n, _ = cla
    n.interface.robot.tilt(8.0)
    ticks(n, 500)
    assert roll_deg(n) > 6.0
    assert run(n, ["load-plugin rotadjustplugin", "create-plugin level rotadjust", "start level"])[2] == "ok started level"
    ticks(n, 4000)
    assert abs(roll_deg(n)) < 0.5
    status = run(n, ["level status"])[0]
    assert "corrections=" in status and float(status.split("correction_deg=")[1]) > 6.0


def test_the_spine_plugins_refuse_a_robot_without_the_sensors(nerve):
    replies = run(nerve, ["load-plugin rotadjust", "create-plugin r rotadjust", "load-plugin slack",
                          "create-plugin s slack", "load-plugin overcurrent", "create-plugin o overcurrent",
                          "load-plugin sensorfault", "create-plugin f sensorfault"])
    assert replies[1] == "error: rotadjust: needs a spine robot with a clavicle accelerometer (acc_chest); arm3 has none"
    assert replies[3] == "error: slack: needs a per-muscle tension reading; arm3 has none"
    assert replies[5].startswith("error: overcurrent: needs a per-muscle current")
    assert replies[7].startswith("error: sensorfault: needs a per-muscle tension and current")


def test_slack_is_detected_and_taken_up(cla):
    n, watcher = cla
    run(n, ["load-plugin slack", "create-plugin sl slack", "start sl"])
    ticks(n, 2000)
    n.interface.robot.fault("slack", 2, 5.0)  # CLA-RB's wire stretched by 5 mm
    ticks(n, 300)
    assert n.state()["tension"][2] < 0.1
    ticks(n, 3000)
    assert any("slack CLA-RB: taking up" in e for e in watcher.received)
    assert any("CLA-RB taken up by" in e for e in watcher.received)
    take_up = n.instances["sl"].plugin.take_up
    assert take_up[2] > 0.5 and n.state()["tension"][2] > 1.0


def test_a_blocked_reel_trips_the_over_current_stop(cla):
    n, watcher = cla
    run(n, ["load-plugin overcurrent", "create-plugin oc overcurrent", "start oc"])
    n.interface.robot.fault("stall", 0)
    run(n, ["sequence propocmd #f(10 0 0 0 0 0 0 0) 200"])
    ticks(n, 600)
    assert "event oc: over-current > 0.8 A on CLA-RF: motor stopped" in watcher.received
    assert abs(n.state()["current"][0]) < 0.1
    assert run(n, ["oc status", "oc reset CLA-RF", "oc reset"]) == [
        "ok stopped=CLA-RF limit_a=0.8", "ok CLA-RF", "error: reset: no motor is stopped"]


def test_a_stuck_tension_sensor_is_found(cla):
    n, watcher = cla
    run(n, ["load-plugin sensorfault", "create-plugin sf sensorfault", "start sf"])
    ticks(n, 600)
    assert run(n, ["sf status"]) == ["ok tension_faults=- encoder_faults=-"]  # a healthy spine: nothing
    n.interface.robot.fault("tension-stuck", 2, 4.0)
    run(n, ["sequence propocmd #f(0 0 5 -5 0 0 0 0) 500"])
    ticks(n, 1500)
    assert run(n, ["sf status"]) == ["ok tension_faults=CLA-RB encoder_faults=-"]
    assert "event sf: tension sensor fault on CLA-RB" in watcher.received


def test_a_frozen_encoder_is_found_and_its_motor_stopped(cla):
    n, watcher = cla
    run(n, ["load-plugin sensorfault", "create-plugin sf sensorfault", "start sf"])
    n.interface.robot.fault("encoder-stuck", 3)
    run(n, ["sequence propocmd #f(0 0 0 3 0 0 0 0) 300"])
    ticks(n, 2500)
    assert "event sf: encoder fault on CLA-LB: motor stopped" in watcher.received
    assert n.interface.robot.control.modes[3] == 1  # T mode with zero tension gains: off
