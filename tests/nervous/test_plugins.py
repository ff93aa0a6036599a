"""Plugins (§6.3.4): loaded, created, started, stopped and unloaded while the loop runs; a plugin that
raises is stopped and reported while the loop goes on; found by entry point or file; the shipped ones."""

import sys
import textwrap

import numpy as np
import pytest
from nervous_support import THESIS_RC, run, ticks

from shintai.nervous.commands import Client
from shintai.nervous.nerve import Nerve
from shintai.nervous.server import Server


def moving(nerve, ms=200):
    run(nerve, [f"sequence propocmd #f(100 0 0) {ms}"])


def test_a_plugin_that_raises_is_stopped_and_reported_and_the_loop_goes_on(nerve):
    watcher = Client("watcher")
    nerve.clients.add(watcher)
    run(nerve, ["load-plugin null", "create-plugin n1 null", "start n1"])
    moving(nerve)
    ticks(nerve, 20)
    x20 = nerve.state()["reference"][0]
    assert run(nerve, ["n1 raise"]) == ["ok"]
    ticks(nerve, 20)
    assert nerve.state()["reference"][0] > x20  # the sequence kept playing
    assert nerve.state()["seq"] == 40
    assert watcher.received == ["event plugin n1 raised and was stopped: PluginFault: n1: raised on request at "
                                "packet 20"]
    assert "n1(null,failed: PluginFault" in run(nerve, ["plugins"])[0]
    assert run(nerve, ["start n1", "n1 count"])[1] == "ok 0"  # it may be started again
    ticks(nerve, 3)
    assert run(nerve, ["n1 count"]) == ["ok 3"]


class Bad:
    """Plugins whose output is wrong."""

    @staticmethod
    def source(out):
        return textwrap.dedent(f"""
            import numpy as np
            from shintai.nervous.plugins.base import Plugin
            class Bad(Plugin):
                def process(self, state):
                    return {out}
            """)


@pytest.mark.parametrize("out, why", [("np.full(3, np.nan)", "3 not finite"), ("np.zeros(2)", "(2,) values"),
                                      ("'x'", "could not convert")])
def test_a_plugin_returning_a_bad_vector_is_stopped_before_it_reaches_the_body(tmp_path, out, why):
    (tmp_path / "bad.py").write_text(Bad.source(out))
    n = Nerve("arm3", "dummy", plugin_dirs=[tmp_path])
    run(n, THESIS_RC + ["load-plugin bad", "create-plugin b bad", "start b"])
    ticks(n, 5)
    assert np.all(np.isfinite(n.state()["reference"]))
    assert why in n.instances["b"].status


def test_hot_unload_while_running(nerve):
    run(nerve, ["load-plugin null", "create-plugin n1 null", "create-plugin n2 null", "start n1", "start n2",
                "load-plugin smooth", "create-plugin sm smooth 1000", "start sm"])
    moving(nerve)
    ticks(nerve, 10)
    assert run(nerve, ["unload-plugin null"]) == ["ok unloaded null, deleted n1 n2"]
    ticks(nerve, 10)
    assert [m.name for m in nerve.loop.modules] == ["sequence", "(target)", "sm"]
    assert run(nerve, ["n1 count", "unload-plugin smooth", "unload-plugin sequence"])[0].startswith(
        "error: unknown command 'n1'")
    ticks(nerve, 10)
    held = nerve.state()["reference"].copy()
    ticks(nerve, 10)
    assert np.array_equal(nerve.state()["reference"], held)  # no set-point plugin: the last target holds
    assert [m.name for m in nerve.loop.modules] == ["(target)"]
    assert run(nerve, THESIS_RC)[2] == "ok started sequence"  # and loads again
    assert np.array_equal(nerve.state()["reference"], held)


def test_one_set_point_plugin_at_a_time(nerve):
    assert run(nerve, ["create-plugin seq2 sequence", "start seq2"]) == [
        "ok seq2 (sequence)", "error: start: sequence already sets the target (one set-point plugin at a time; "
        "stop sequence first)"]


def test_creation_and_start_errors_are_one_line_and_change_nothing(nerve):
    replies = run(nerve, ["create-plugin x nothing", "load-plugin nothing", "create-plugin dof null",
                          "create-plugin 9x null", "start ghost", "stop ghost", "create-plugin sequence sequence",
                          "load-plugin /tmp/evil.py", "unload-plugin ghost", "delete-plugin ghost", "start sequence"])
    assert all(r.startswith("error: ") for r in replies), replies
    assert "a file path is honoured only in the start-up file" in replies[7]
    assert [m.name for m in nerve.loop.modules] == ["sequence", "(target)"]


def test_a_constructor_that_raises_fails_the_start(tmp_path):
    (tmp_path / "broken.py").write_text(textwrap.dedent("""
        from shintai.nervous.plugins.base import Plugin
        class Broken(Plugin):
            def start(self, state):
                raise RuntimeError("no hardware")
        """))
    n = Nerve("arm3", "dummy", plugin_dirs=[tmp_path])
    assert run(n, ["load-plugin broken", "create-plugin b broken", "start b"])[2] == \
        "error: start: b's constructor raised RuntimeError: no hardware"
    assert not n.instances["b"].running


def test_a_plugin_file_path_is_honoured_from_the_start_up_file_only(tmp_path):
    plugin = tmp_path / "mine.py"
    plugin.write_text(textwrap.dedent("""
        from shintai.nervous.plugins.base import Plugin
        class Mine(Plugin):
            summary = "mine"
        PLUGIN = Mine
        """))
    rc = tmp_path / "rc"
    rc.write_text(f"# start-up\nload-plugin {plugin}\ncreate-plugin m mine\nstart m\nwait\n")
    n = Nerve("arm3", "dummy")
    errors = []
    assert Server(n).run_rc(rc, out=type("W", (), {"write": lambda self, s: errors.append(s)})()) == 1
    assert "rc:5: error: wait: not in a start-up file" in "".join(errors)
    assert n.instances["m"].running
    assert run(Nerve("arm3", "dummy"), [f"load-plugin {plugin}"])[0].startswith("error: load-plugin: a file path")


def test_a_third_party_package_adds_plugins_by_entry_point(tmp_path, monkeypatch):
    (tmp_path / "thirdparty_nerve.py").write_text(textwrap.dedent("""
        import numpy as np
        from shintai.nervous.plugins.base import Plugin
        class Offset(Plugin):
            summary = "adds 1 to every target"
            def process(self, state):
                return np.ones(len(state["reference"]))
        """))
    dist = tmp_path / "thirdparty_nerve-1.0.dist-info"
    dist.mkdir()
    (dist / "METADATA").write_text("Metadata-Version: 2.1\nName: thirdparty-nerve\nVersion: 1.0\n")
    (dist / "entry_points.txt").write_text("[shintai.nervous.plugins]\noffset = thirdparty_nerve:Offset\n")
    monkeypatch.syspath_prepend(str(tmp_path))
    n = Nerve("arm3", "dummy")
    assert run(n, ["load-plugin offset", "create-plugin o offset", "start o"]) == [
        "ok offset (add): adds 1 to every target", "ok o (offset)", "ok started o"]
    ticks(n, 2)
    assert n.state()["reference"].tolist() == [1.0, 1.0, 1.0]
    sys.modules.pop("thirdparty_nerve", None)


def test_smooth_limits_the_rate_of_an_abrupt_target(nerve):
    run(nerve, ["load-plugin smoothplugin", "create-plugin sm smooth 50", "start sm",
                "sequence propocmd #f(100 0 0) 1"])
    ticks(nerve, 102)
    sent = nerve.state()["reference"][0]
    assert sent == pytest.approx(5.0, abs=0.06)  # 50 deg/s for 0.1 s, not 100 at once
    run(nerve, ["sm rate 0"])
    ticks(nerve, 2)
    assert nerve.state()["reference"][0] == pytest.approx(100.0, abs=1e-9)


def test_log_writes_a_file_numpy_loads(tmp_path):
    n = Nerve("arm3", "dummy", log_dir=tmp_path)
    run(n, THESIS_RC + ["load-plugin log", "create-plugin lg log run.txt 2", "start lg",
                        "sequence propocmd #f(10 20 30) 10"])
    ticks(n, 20)
    assert run(n, ["stop lg"]) == ["ok stopped lg"]
    data = np.genfromtxt(tmp_path / "run.txt", names=True)
    assert data.dtype.names[:5] == ("t", "seq", "target_0", "target_1", "target_2")
    assert data.dtype.names[5:7] == ("angle_vector_0", "angle_vector_1")
    assert len(data) == 10 and data["seq"].tolist() == list(range(0, 20, 2))
    assert data["reference_2"][-1] == 30.0
    assert run(n, ["create-plugin l2 log ../escape.txt", "create-plugin l3 log /etc/passwd"]) == [
        "error: log: '../escape.txt' is not a plain file name (letters, digits, _ . -)",
        "error: log: '/etc/passwd' is not a plain file name (letters, digits, _ . -)"]


def test_servo_changes_the_gains_of_the_simulated_servos():
    n = Nerve("arm3", "sim")
    run(n, THESIS_RC + ["load-plugin servo", "create-plugin servo servo"])
    assert run(n, ["servo show", "servo set kp 80 j1", "servo set kp 1 nope", "servo set q 1"]) == [
        "ok kp=40 kv=1.2 off=0", "ok kp=53.3333 kv=1.2 off=0", "error: unknown DOF 'nope' (names j0, j1, j2… or 0–2)",
        "error: servo: unknown parameter 'q' (kp, kv, on, off)"]
    body = n.interface.robot.body.model
    assert body.actuator_gainprm[1, 0] == 80.0 and body.actuator_biasprm[1, 1] == -80.0
    run(n, ["servo off"])
    assert np.all(body.actuator_gainprm[:, 0] == 0.0)


def test_switching_the_interface_keeps_the_client_script(nerve):
    """§5.4.5: the same software runs on the robot or the simulator, "インタフェースを切り替えるだけで"."""
    script = ["sequence propocmd #f(20 -30 40) 300"]
    results = {}
    for kind in ("dummy", "sim"):
        assert run(nerve, [f"set-interface {kind}"] + script) == [f"ok {kind}", "ok"]
        ticks(nerve, 800)
        results[kind] = nerve.state()["angle-vector"]
    assert np.allclose(results["sim"], results["dummy"], atol=2.0)
    assert run(nerve, ["set-interface serinerve"])[0].startswith("error: set-interface: unknown interface")


def test_pyproject_declares_the_shipped_plugins_as_entry_points():
    import tomllib
    from pathlib import Path

    from shintai.nervous.plugins import BUILTIN

    project = tomllib.loads((Path(__file__).resolve().parents[2] / "pyproject.toml").read_text())
    assert project["project"]["entry-points"]["shintai.nervous.plugins"] == BUILTIN
