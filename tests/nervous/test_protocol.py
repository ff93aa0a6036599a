"""The line rules of App. C.2.1 in order — comment, s-expression, registered command, plugin instance — and
the refused fifth rule (the shell): every non-empty, non-comment line gets exactly one ok/error line."""

import math

import numpy as np
import pytest
from nervous_support import run, ticks

from shintai.nervous.commands import Client
from shintai.nervous.protocol import (MAX_LINE_BYTES, Keyword, ProtocolError, Symbol, Vector, decode, fmt,
                                      read_sexpr, split_id, words)


def test_decode_takes_utf8_text_and_refuses_control_characters_and_huge_lines():
    assert decode(b"dof\r") == "dof"
    with pytest.raises(ProtocolError, match="not UTF-8"):
        decode(b"\xff\xfe")
    with pytest.raises(ProtocolError, match="control character U\\+0000"):
        decode(b"do\x00f")
    with pytest.raises(ProtocolError, match="line too long"):
        decode(b"x" * (MAX_LINE_BYTES + 1))


def test_words_keep_a_float_vector_as_one_token_and_check_its_numbers():
    assert words("sequence propocmd #f(0 1 2.5) 1000 :clear") == [
        "sequence", "propocmd", Vector((0.0, 1.0, 2.5)), "1000", ":clear"]
    for bad, message in (("x #f(1 nan)", "not a finite number"), ("x #f(1 inf)", "not a finite number"),
                         ("x #f(1 2", "unbalanced #f"), ("x #f(1 (2))", "unbalanced #f"), ("x #f(a)", "expected a number"),
                         ("x (1 2)", "unexpected parenthesis")):
        with pytest.raises(ProtocolError, match=message):
            words(bad)


def test_sexpressions_are_read_into_data_never_evaluated():
    form = read_sexpr("(send *ns* :angle-vector #f(0 1 2) 1000 :overwrite t)")
    assert form == [Symbol("send"), Symbol("*ns*"), Keyword("angle-vector"), Vector((0.0, 1.0, 2.0)), 1000,
                    Keyword("overwrite"), True]
    assert read_sexpr("(a (b (c nil)))") == [Symbol("a"), [Symbol("b"), [Symbol("c"), None]]]
    for bad, message in (("(send", "unbalanced '\\('"), ("(a))", "after the closing"), (")", "unbalanced '\\)'"),
                         ("(quote 'x)", "quoting"), ("(" * 20 + ")" * 20, "deeper")):
        with pytest.raises(ProtocolError, match=message):
            read_sexpr(bad)


def test_an_id_is_the_last_token():
    assert split_id("dof @a.1") == ("dof", "a.1")
    assert split_id("dof") == ("dof", None)
    assert split_id("sequence propocmd #f(1 2 3) 10\t@m-2 ") == ("sequence propocmd #f(1 2 3) 10", "m-2")
    with pytest.raises(ProtocolError, match="bad id"):
        split_id("dof @bad/id")


def test_numbers_are_written_short():
    assert [fmt(1.0), fmt(-2.5), fmt(1 / 3), fmt(1e20), fmt(math.nan)] == ["1", "-2.5", "0.333333", "1e+20", "nan"]


def test_rule_1_a_comment_or_an_empty_line_gets_no_reply(nerve):
    assert run(nerve, ["# a comment", "   #x", "", "   "]) == [None] * 4


def test_rule_2_sexpressions_of_the_thesis_client(nerve):
    c = Client()
    assert run(nerve, ["(send *ns* :angle-vector #f(10 20 30) 5)"], c) == ["ok"]
    ticks(nerve, 10)
    assert run(nerve, ["(send *ns* :angle-vector)", "(send *ns* :state :angle-vector)",
                       "(send *ns* :interpolation-method)", "(send *ns* :interpolation-method linear)",
                       "(send *ns* :interpolation-method)"], c) == [
        "ok #f(10 20 30)", "ok #f(10 20 30)", "ok minjerk", "ok linear", "ok linear"]
    state = run(nerve, ["(send *ns* :state)"], c)[0]
    assert state.startswith("ok (:time 0.010000 :seq 10 :angle-vector #f(10 20 30) :reference #f(10 20 30)")
    # EusLisp's :overwrite t is propocmd's :clear (C.2.2)
    assert run(nerve, ["(send *ns* :angle-vector #f(0 0 0) 1000)", "(send *ns* :angle-vector #f(1 1 1) 4 :overwrite t)"],
               c) == ["ok", "ok"]
    ticks(nerve, 5)
    assert np.allclose(nerve.state()["angle-vector"], 1.0)
    for bad in ("(progn (unix:system \"rm -rf /\"))", "(send *ns* :eval 1)", "(send *ns* angle-vector)",
                "(send *ns* :angle-vector #f(1 2))", "(send *ns* :state :nothing)", "((send))"):
        reply = run(nerve, [bad], c)[0]
        assert reply.startswith("error: "), bad


def test_rule_3_registered_commands(nerve):
    replies = run(nerve, ["dof", "help", "?", "help dof", "interface", "plugins", "stats", "describe", "state"])
    assert replies[0] == "ok 3 j0 j1 j2"
    assert replies[1] == replies[2] and "never a shell command" in replies[1]
    assert replies[3] == "ok dof — the DOF: ok N name1 … nameN"
    assert replies[4].startswith("ok dummy robot=arm3 fast period_ms=1")
    assert "sequence(sequence,running,set" in replies[5]
    assert replies[6].startswith("ok packets=0 packet_ms=1 ")
    assert replies[7].startswith('ok {"robot":"arm3"')
    assert replies[8] == "ok t=0.000000 seq=0 angle-vector=0,0,0 reference=0,0,0 tip=0,0,0"
    assert all(r.count("\n") == 0 for r in replies)


def test_rule_4_a_plugin_instance_takes_the_rest_of_the_line(nerve):
    assert run(nerve, ["sequence propocmd #f(0 1 2) 1", "sequence switch minjerksequence", "sequence nonsense"]) == [
        "ok", "ok minjerksequence", "error: sequence: unknown method 'nonsense' (methods: angle-vector, clear, help, "
        "propocmd, status, switch, via)"]
    ticks(nerve, 2)
    assert run(nerve, ["sequence angle-vector"]) == ["ok 0,1,2"]


def test_rule_5_the_shell_is_refused(nerve, tmp_path):
    marker = tmp_path / "made-by-a-shell"
    for line in (f"touch {marker}", f"echo hi > {marker}", "ls -l", f"/bin/sh -c 'touch {marker}'", "!ls",
                 f"`touch {marker}`"):
        (reply,) = run(nerve, [line])
        assert reply.startswith("error: unknown command") and "never passed to a shell" in reply, line
    assert run(nerve, [f"$(touch {marker})"])[0].startswith("error: ")
    assert not marker.exists()


def test_a_command_may_carry_an_id_and_hears_done(nerve):
    c = Client()
    assert run(nerve, ["sequence propocmd #f(0 10 0) 5 @m1", "dof @d"], c) == ["ok", "ok 3 j0 j1 j2"]
    assert c.received == []  # nervous sends `done d` after the reply, through the server (Reply.after)
    assert nerve.execute("dof @d2", c).after == ["done d2"]  # no motion queued: done at once
    ticks(nerve, 4)
    assert c.received == []
    ticks(nerve, 2)
    assert c.received == ["done m1"]


def test_the_thesis_client_reads_cla_tensions():
    """§6.3.3: `(send *ns* :state :tension-vector)` — the key is the sensor's name, `-vector` optional."""
    from shintai.nervous.nerve import Nerve

    n = Nerve("cla", "dummy")
    n.interface.sensors["tension"][:] = np.arange(8.0)
    n.tick()
    assert run(n, ["(send *ns* :state :tension-vector)", "state tension", "(send *ns* :state :tension)"]) == [
        "ok #f(0 1 2 3 4 5 6 7)", "ok t=0.001000 seq=1 tension=0,1,2,3,4,5,6,7", "ok #f(0 1 2 3 4 5 6 7)"]
