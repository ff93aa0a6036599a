"""The socket server (§6.3.3, C.2.2): loopback by default, one reply per line over TCP, many clients at
once, bounded output for slow clients, abrupt disconnects, `wait` without a race, the CLI contract."""

import os
import queue
import re
import select
import signal
import socket
import struct
import subprocess
import sys
import threading
import time
from pathlib import Path

import pytest
from nervous_support import THESIS_RC, run

from shintai.cli import main
from shintai.nervous.cli import build_serve_parser_defaults
from shintai.nervous.client import NerveClient, NerveError
from shintai.nervous.nerve import Nerve
from shintai.nervous.server import DEFAULT_HOST, ServerThread

SRC = str(Path(__file__).resolve().parents[2] / "src")


def abort(sock):
    """Close with a TCP reset (no FIN): an abrupt disconnect."""
    sock.setsockopt(socket.SOL_SOCKET, socket.SO_LINGER, struct.pack("ii", 1, 0))
    sock.close()


def wait_until(predicate, timeout=5.0):
    end = time.monotonic() + timeout
    while time.monotonic() < end:
        if predicate():
            return True
        time.sleep(0.01)
    return False


def test_the_default_bind_is_loopback(server):
    assert DEFAULT_HOST == "127.0.0.1"
    assert build_serve_parser_defaults()["host"] == "127.0.0.1"
    assert server.server._server.sockets[0].getsockname()[0] == "127.0.0.1"
    try:
        outside = socket.gethostbyname(socket.gethostname())
    except OSError:
        outside = "127.0.0.1"
    if not outside.startswith("127."):
        with pytest.raises(OSError):
            socket.create_connection((outside, server.port), timeout=2).close()


def test_every_line_gets_one_reply_in_order(server):
    lines = ["dof", "# a comment", "", "nonsense", "(send *ns* :state :angle-vector)", "  ", "sequence status",
             "(unbalanced", "sequence propocmd #f(1 2)", "help dof"]
    with NerveClient(port=server.port, timeout=5) as c:
        c.send_line("\n".join(lines))
        replies = [c.reply() for _ in range(7)]
        assert replies[0] == "ok 3 j0 j1 j2" and replies[1].startswith("error: unknown command 'nonsense'")
        assert replies[2] == "ok #f(0 0 0)" and replies[3].startswith("ok busy=0")
        assert replies[4].startswith("error: unbalanced") and replies[5].startswith("error: propocmd target: 2 values")
        assert replies[6].startswith("ok dof")
        assert c.command("dof") == "3 j0 j1 j2"  # nothing else was pending


def test_a_shell_command_over_the_socket_is_an_error(server, tmp_path):
    marker = tmp_path / "x"
    with NerveClient(port=server.port, timeout=5) as c:
        with pytest.raises(NerveError, match="never passed to a shell"):
            c.command(f"touch {marker}")
    assert not marker.exists()


def test_bad_bytes_and_overlong_lines_get_one_error_each(server):
    with NerveClient(port=server.port, timeout=5) as c:
        c.sock.sendall(b"\xff\xfe\xfd\n" + b"x" * 200_000 + b"\n" + b"do\x01f\n" + b"dof\n")
        assert c.reply().startswith("error: line is not UTF-8")
        assert c.reply() == "error: line too long (200000 bytes, the limit is 65536)"
        assert c.reply() == "error: control character U+0001 at column 3"
        assert c.reply() == "ok 3 j0 j1 j2"


def test_a_disconnect_in_the_middle_of_a_line_executes_nothing(server):
    with NerveClient(port=server.port, timeout=5) as c:
        before = c.state("reference")["reference"].tolist()
        half = socket.create_connection(("127.0.0.1", server.port), timeout=5)
        half.sendall(b"sequence propocmd #f(50 50 50) 10")  # no newline
        abort(half)
        half = socket.create_connection(("127.0.0.1", server.port), timeout=5)
        half.sendall(b"sequence propocmd #f(60 60 60) 10")
        half.close()  # FIN in the middle of a line
        time.sleep(0.1)
        assert c.state("reference")["reference"].tolist() == before
        assert wait_until(lambda: server.call(lambda: len(server.server.connections)) == 1)


def test_a_disconnect_in_the_middle_of_a_stream_is_cleaned_up(server):
    streams = [NerveClient(port=server.port, timeout=5) for _ in range(3)]
    for s in streams:
        s.stream()
        s.collect(20)
    abort(streams[0].sock)
    streams[1].close()
    with NerveClient(port=server.port, timeout=5) as c:
        assert wait_until(lambda: server.call(lambda: len(server.nerve.clients)) == 2)
        assert c.command("dof") == "3 j0 j1 j2"
        got = streams[2].collect(50)
        assert [s["seq"] for s in got] == list(range(got[0]["seq"], got[0]["seq"] + 50))
    streams[2].close()


def test_a_hundred_clients_at_once(server):
    clients = [NerveClient(port=server.port, timeout=10) for _ in range(100)]
    try:
        for k, c in enumerate(clients):
            c.send_line(f"stream on 5\ndof\nsequence propocmd #f({k % 90} 0 0) 20 @m{k}")
        for c in clients:
            assert [c.reply() for _ in range(3)][1:] == ["ok 3 j0 j1 j2", "ok"]
        for c in clients:
            assert len(c.collect(3)) == 3
        assert server.call(lambda: len(server.nerve.clients)) == 100
        for k, c in enumerate(clients):
            c.send_line(f"wait m{k}")
        for k, c in enumerate(clients):
            assert c.reply(timeout=10) in (f"ok m{k}:done", f"ok m{k}:cleared")
    finally:
        for c in clients:
            c.close()
    assert wait_until(lambda: server.call(lambda: len(server.nerve.clients)) == 0)


def test_a_client_that_never_reads_loses_stream_lines_not_the_loop():
    """As fast as possible the dummy streams megabytes a second; a client that reads nothing fills the
    kernel's buffers, then its stream lines are dropped and counted, its queue stays bounded, and the
    packet loop and the other clients go on."""
    nerve = Nerve("arm3", "dummy")
    run(nerve, THESIS_RC)
    with ServerThread(nerve, max_queue=64, send_buffer=8192) as srv:
        slow = socket.socket()
        slow.setsockopt(socket.SOL_SOCKET, socket.SO_RCVBUF, 4096)  # before connect: a small window
        slow.settimeout(5)
        slow.connect(("127.0.0.1", srv.port))
        slow.sendall(b"stream on\n")
        with NerveClient(port=srv.port, timeout=5) as c:
            assert wait_until(lambda: int(re.search(r"dropped=(\d+)", c.command("stats")).group(1)) > 1000, 20)
            seq0 = c.state()["seq"]
            time.sleep(0.2)
            assert c.state()["seq"] > seq0 + 100  # the loop runs on
            assert c.command("dof") == "3 j0 j1 j2"
            queued = srv.call(lambda: max(len(x.outbox) for x in srv.server.connections))
            assert queued <= 64 + 1
        slow.close()


def test_wait_cannot_race(server):
    with NerveClient(port=server.port, timeout=5) as c:
        c.send_line("sequence propocmd #f(5 5 5) 30 @a\nwait a")  # one write: no packet between the two lines
        assert c.reply() == "ok"
        assert c.reply() == "ok a:done" and c.done == {"a": "done"}
        c.command("sequence propocmd #f(6 6 6) 1 @b")
        time.sleep(0.1)  # long over
        assert c.wait("b") == "b:done"  # a wait after the end still finds it
        with pytest.raises(NerveError, match="no motion @zz from this connection"):
            c.wait("zz")
        c.command("sequence propocmd #f(7 7 7) 5000 @slow")
        with pytest.raises(NerveError, match="wait slow: slow not done after 50 ms"):
            c.wait("slow", timeout_ms=50)
        with pytest.raises(NerveError, match="still under way"):
            c.command("sequence propocmd #f(7 7 7) 10 @slow")
        c.command("sequence propocmd #f(0 0 0) 10 :clear @c")
        assert c.wait() == "c:done"
        assert c.done["slow"] == "cleared"


def test_quit_closes_the_connection(server):
    with NerveClient(port=server.port, timeout=5) as c:
        assert c.command("quit") == "bye"
        with pytest.raises(ConnectionError):
            c.read_line()


def test_the_command_line_contract(tmp_path):
    env = {**os.environ, "PYTHONPATH": SRC}
    rc = tmp_path / "nervousrc"
    rc.write_text("load-plugin seqplugin\ncreate-plugin sequence sequence\nstart sequence\n")
    proc = subprocess.Popen([sys.executable, "-m", "shintai", "nervous", "serve", "--robot", "arm3", "--interface",
                             "dummy", "--port", "0", "--rc", str(rc)], env=env, stdout=subprocess.PIPE,
                            stderr=subprocess.PIPE, text=True)
    try:
        ready, _, _ = select.select([proc.stdout], [], [], 60)
        assert ready, "the server printed nothing within 60 s"
        line = proc.stdout.readline()
        match = re.fullmatch(r"nervous: listening on 127\.0\.0\.1:(\d+)\n", line)
        assert match, line
        port = int(match.group(1))
        with NerveClient(port=port, timeout=5) as c:
            assert c.command("dof") == "3 j0 j1 j2"
            c.send_line("stream on")
            assert c.read_line().startswith("ok stream")
            assert c.read_line().startswith("state t=")
        out = subprocess.run([sys.executable, "-m", "shintai", "nervous", "send", "--port", str(port), "dof",
                              "# silent", "nope"], env=env, capture_output=True, text=True, timeout=60)
        assert out.returncode == 1
        assert out.stdout.splitlines()[0] == "ok 3 j0 j1 j2" and out.stdout.splitlines()[1].startswith("error:")
    finally:
        proc.send_signal(signal.SIGTERM)
        assert proc.wait(timeout=30) == 0
    assert "nervous: stopped" in proc.stderr.read()


def test_serve_refuses_bad_arguments_in_one_line(capsys):
    assert main(["nervous", "serve", "--robot", "r2d2", "--port", "0"]) == 2
    assert "unknown (robots: arm3, cla, hrp2, snake)" in capsys.readouterr().err
    assert main(["nervous", "send", "--port", "1", "dof"]) == 2


def test_the_console_reads_standard_input():
    """C.2.1: nervous interprets "socket(と標準入力)" — `serve --stdin` takes the operator's lines too."""
    env = {**os.environ, "PYTHONPATH": SRC}
    proc = subprocess.Popen([sys.executable, "-m", "shintai", "nervous", "serve", "--robot", "arm3", "--interface",
                             "dummy", "--port", "0", "--stdin"], env=env, stdin=subprocess.PIPE,
                            stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    try:
        proc.stdin.write("# comment\nload-plugin seqplugin\ndof\nnope\n")
        proc.stdin.flush()
        got = queue.Queue()
        threading.Thread(target=lambda: [got.put(line.rstrip("\n")) for line in proc.stdout], daemon=True).start()
        lines = [got.get(timeout=60) for _ in range(4)]
        assert lines[0].startswith("nervous: listening on 127.0.0.1:")
        assert lines[1].startswith("ok sequence (set)") and lines[2] == "ok 3 j0 j1 j2"
        assert lines[3].startswith("error: unknown command 'nope'")
    finally:
        proc.send_signal(signal.SIGTERM)
        assert proc.wait(timeout=30) == 0
