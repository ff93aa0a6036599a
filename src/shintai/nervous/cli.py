"""``shintai nervous serve|send|describe`` (the contract is in DESIGN.md).

* ``serve --robot NAME [--interface sim|dummy] [--host H] [--port P] [--rc FILE]`` prints
  ``nervous: listening on HOST:PORT`` once it accepts connections (``--port 0``: a free port; the default
  host is 127.0.0.1); Ctrl-C or SIGTERM stops it (exit 0).
* ``send [--host H] [--port P] LINE…`` (or lines on stdin) prints every line the server sends up to each
  reply; exit 0 when every reply is ``ok``, 1 when one is ``error:``, 2 when the server cannot be reached.
* ``describe ROBOT [--json]`` prints the description generated from the robot's model (§6.3.2).
"""

from __future__ import annotations

import argparse
import asyncio
import sys

from shintai.nervous import robots
from shintai.nervous.client import NerveClient
from shintai.nervous.hal import INTERFACES
from shintai.nervous.nerve import Nerve
from shintai.nervous.server import DEFAULT_HOST, MAX_QUEUE, serve

DEFAULT_PORT = 7643  # chosen (the thesis's port is not given)


def add_parser(sub) -> None:
    """Add ``nervous`` and its sub-commands to the ``shintai`` parser."""
    n = sub.add_parser("nervous", help="the nervous middle-layer server (seed 003 ch. 6): serve, send, describe")
    n.set_defaults(registry=False)
    nsub = n.add_subparsers(dest="nervous_command", required=True, parser_class=type(n))

    s = nsub.add_parser("serve", help="serve a robot over TCP")
    s.add_argument("--robot", required=True, help=f"robot: {', '.join(sorted(robots.ROBOTS))}")
    s.add_argument("--interface", choices=sorted(INTERFACES), default="sim")
    s.add_argument("--host", default=DEFAULT_HOST, help=f"address to bind (default {DEFAULT_HOST}: this machine only)")
    s.add_argument("--port", type=int, default=DEFAULT_PORT, help=f"TCP port (default {DEFAULT_PORT}; 0: a free one)")
    s.add_argument("--rc", help="start-up file of commands (C.1.4 .nervousrc), run before listening")
    pace = s.add_mutually_exclusive_group()
    pace.add_argument("--realtime", dest="realtime", action="store_true", default=True,
                      help="one packet per packet period of wall time (default)")
    pace.add_argument("--fast", dest="realtime", action="store_false", help="packets as fast as possible")
    s.add_argument("--log-dir", default=".", help="folder the log plugin writes into (default: here)")
    s.add_argument("--plugin-dir", action="append", default=[], help="folder of NAME.py plugins (repeatable)")
    s.add_argument("--max-queue", type=int, default=MAX_QUEUE, help="stream lines queued per client")
    s.add_argument("--stdin", action="store_true", help="also read commands from standard input (the thesis's "
                   "console); replies go to standard output")
    s.set_defaults(fn=cmd_serve, registry=False)

    c = nsub.add_parser("send", help="send lines to a server, print what comes back")
    c.add_argument("lines", nargs="*", help="lines to send (default: read stdin)")
    c.add_argument("--host", default=DEFAULT_HOST)
    c.add_argument("--port", type=int, default=DEFAULT_PORT)
    c.add_argument("--timeout", type=float, default=10.0, help="seconds to wait for each reply")
    c.add_argument("--collect", type=int, default=0, help="then print this many more lines (e.g. a stream)")
    c.set_defaults(fn=cmd_send, registry=False)

    d = nsub.add_parser("describe", help="the robot's description, generated from its model")
    d.add_argument("robot", help=f"robot: {', '.join(sorted(robots.ROBOTS))}")
    d.add_argument("--json", action="store_true")
    d.set_defaults(fn=cmd_describe, registry=False)


def build_serve_parser_defaults() -> dict:
    """The defaults of ``shintai nervous serve`` (the tests check the bind is loopback)."""
    parser = argparse.ArgumentParser()
    add_parser(parser.add_subparsers())
    return vars(parser.parse_args(["nervous", "serve", "--robot", "arm3"]))


def usage_error(message: str) -> int:
    print(f"shintai: error: {message}", file=sys.stderr)
    return 2


def cmd_serve(args: argparse.Namespace) -> int:
    if not 0 <= args.port <= 65535:
        return usage_error(f"--port {args.port}: expected 0–65535")
    if args.robot not in robots.ROBOTS:
        return usage_error(f"--robot {args.robot}: unknown (robots: {', '.join(sorted(robots.ROBOTS))})")
    if args.max_queue < 1:
        return usage_error(f"--max-queue {args.max_queue}: expected a positive number")
    nerve = Nerve(args.robot, args.interface, realtime=args.realtime, log_dir=args.log_dir, plugin_dirs=args.plugin_dir)

    def announce(line: str) -> None:
        print(line, flush=True)

    try:
        asyncio.run(serve(nerve, args.host, args.port, args.rc, announce, stdin=args.stdin, max_queue=args.max_queue))
    except OSError as exc:
        return usage_error(f"cannot listen on {args.host}:{args.port}: {exc.strerror or exc}")
    print("nervous: stopped", file=sys.stderr)
    return 0


def cmd_send(args: argparse.Namespace) -> int:
    lines = args.lines or [line.rstrip("\n") for line in sys.stdin]
    try:
        client = NerveClient(args.host, args.port, timeout=args.timeout)
    except OSError as exc:
        return usage_error(f"cannot reach nervous at {args.host}:{args.port}: {exc.strerror or exc}")
    failed = False
    with client:
        try:
            for line in lines:
                stripped = line.strip()
                client.send_line(line)
                if not stripped or stripped.startswith("#"):
                    continue
                while True:
                    got = client.read_line()
                    print(got, flush=True)
                    if got == "ok" or got.startswith(("ok ", "error:")):
                        failed |= got.startswith("error:")
                        break
            for _ in range(args.collect):
                print(client.read_line(), flush=True)
        except (TimeoutError, ConnectionError) as exc:
            print(f"shintai: error: {exc}", file=sys.stderr)
            return 1
    return 1 if failed else 0


def cmd_describe(args: argparse.Namespace) -> int:
    if args.robot not in robots.ROBOTS:
        return usage_error(f"unknown robot {args.robot!r} (robots: {', '.join(sorted(robots.ROBOTS))})")
    description = robots.describe(args.robot)
    print(description.to_json() if args.json else description.text())
    return 0
