"""Fuzzed line streams (hypothesis): random bytes, huge lines, unbalanced parentheses, NaN/inf numbers, wrong
DOF counts. The server never crashes, every non-empty non-comment line gets exactly one ok/error line, every
bad line gets an error: line, and a bad line never changes the robot's targets."""

import math
import socket

import numpy as np
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st
from nervous_support import THESIS_RC, run

from shintai.nervous.client import NerveClient
from shintai.nervous.nerve import Nerve
from shintai.nervous.protocol import MAX_LINE_BYTES, ProtocolError, decode, error, is_silent

FUZZ = settings(derandomize=True, deadline=None, max_examples=300,
                suppress_health_check=[HealthCheck.too_slow, HealthCheck.data_too_large])

numbers = st.one_of(st.sampled_from(["nan", "NaN", "inf", "-inf", "1e999", "-1e999", "0x10", "1,5", "--1", "+", "."]),
                    st.sampled_from([math.nan, math.inf, -math.inf]).map(repr))
finite = st.floats(-100, 100, allow_nan=False).map(lambda x: f"{x:g}")


def vector(elements, sizes=st.integers(0, 8)):
    return sizes.flatmap(lambda n: st.lists(elements, min_size=n, max_size=n)).map(lambda v: "#f(" + " ".join(v) + ")")


bad_lines = st.one_of(
    # NaN / inf / not-a-number in a DOF vector
    st.tuples(vector(finite, st.just(2)), numbers).map(lambda t: f"sequence propocmd {t[0][:-1]} {t[1]}) 100"),
    # wrong DOF counts
    vector(finite, st.integers(0, 12).filter(lambda n: n != 3)).map(lambda v: f"sequence propocmd {v} 100"),
    vector(finite, st.integers(0, 12).filter(lambda n: n != 3)).map(lambda v: f"(send *ns* :angle-vector {v} 100)"),
    # bad times and options
    st.tuples(vector(finite, st.just(3)), st.sampled_from(["0", "-1", "nan", "inf", "1e99", "x", ":bogus", "1 :nope"]))
    .map(lambda t: f"sequence propocmd {t[0]} {t[1]}"),
    # unbalanced parentheses
    st.tuples(st.integers(1, 30), st.integers(0, 29), st.text(alphabet=" abc:*#f()0123", max_size=30))
    .filter(lambda t: t[0] != t[1]).map(lambda t: "(" * t[0] + "send *ns* :state " + t[2] + ")" * t[1])
    .filter(lambda s: s.count("(") != s.count(")")),
    # words that are not commands (the shell is refused)
    st.from_regex(r"[a-z/$`!.][a-z0-9_/ .-]{0,30}", fullmatch=True).filter(
        lambda s: s.split()[0] not in {"dof", "help", "state", "stream", "stats", "timeprint", "plugins", "events",
                                       "describe", "interface", "wait", "quit", "exit", "start", "stop", "sequence"}),
)

any_text = st.text(max_size=200)
any_bytes = st.binary(max_size=300).map(lambda b: b.replace(b"\n", b""))
huge = st.integers(MAX_LINE_BYTES + 1, 3 * MAX_LINE_BYTES).map(lambda n: b"(" * n)


def snapshot(nerve):
    seq = nerve.instances["sequence"].plugin
    return (nerve.interface.reference.tolist(), seq.player.x.tolist(), seq.describe(),
            sorted((i.name, i.status) for i in nerve.instances.values()))


def feed(nerve, raw: bytes):
    """What the server does with one received line: decode, interpret; the reply text (or None)."""
    try:
        text = decode(raw)
    except ProtocolError as exc:
        return error(str(exc)), False
    return nerve.execute(text, nerve_client).text, is_silent(text)


class _Client:
    name = "fuzz"
    stream_every = 0
    stream_keys = None
    dropped = 0

    def send(self, line, droppable=False):
        pass


nerve_client = _Client()


def moving_nerve():
    n = Nerve("arm3", "dummy")
    run(n, THESIS_RC + ["sequence propocmd #f(10 20 30) 500"])
    for _ in range(5):
        n.tick()
    return n


@FUZZ
@given(st.lists(bad_lines, min_size=1, max_size=20))
def test_every_bad_line_gets_one_error_and_changes_nothing(lines):
    nerve = moving_nerve()
    before = snapshot(nerve)
    for line in lines:
        reply, silent = feed(nerve, line.encode())
        assert reply is not None and reply.startswith("error: ") and "\n" not in reply, (line, reply)
        assert snapshot(nerve) == before, line
    nerve.tick()  # the loop goes on


@FUZZ
@given(st.lists(st.one_of(any_text.map(str.encode), any_bytes, huge), min_size=1, max_size=10))
def test_random_lines_get_one_reply_each_and_never_crash(lines):
    nerve = moving_nerve()
    before = snapshot(nerve)
    for raw in lines:
        reply, silent = feed(nerve, raw)
        if silent:
            assert reply is None
            continue
        assert reply == "ok" or reply.startswith(("ok ", "error: ")), (raw[:80], reply)
        assert "\n" not in reply
        if reply.startswith("error: "):
            assert snapshot(nerve) == before, raw[:80]
        before = snapshot(nerve)
    nerve.tick()
    assert np.all(np.isfinite(nerve.state()["reference"]))


@settings(derandomize=True, deadline=None, max_examples=25, suppress_health_check=[HealthCheck.too_slow,
                                                                                  HealthCheck.function_scoped_fixture])
@given(st.lists(st.one_of(bad_lines.map(str.encode), any_bytes, huge.map(lambda b: b[:MAX_LINE_BYTES + 10])),
                min_size=1, max_size=15))
def test_over_a_socket_the_fuzzed_stream_gets_one_reply_per_line(server, lines):
    expected = 0
    for raw in lines:
        try:
            expected += 0 if is_silent(decode(raw)) else 1
        except ProtocolError:
            expected += 1
    with NerveClient(port=server.port, timeout=10) as c:
        before = c.state("reference")["reference"].tolist()
        c.sock.sendall(b"\n".join(lines) + b"\ndof\n")
        replies = [c.reply() for _ in range(expected + 1)]
        assert replies[-1] == "ok 3 j0 j1 j2", replies[-3:]
        assert all(r == "ok" or r.startswith(("ok ", "error: ")) for r in replies)
        assert c.state("reference")["reference"].tolist() == before
        c.sock.settimeout(0.05)
        try:
            extra = c.sock.recv(65536)
        except (socket.timeout, TimeoutError):
            extra = b""
        assert extra == b""  # nothing more than one reply per line
