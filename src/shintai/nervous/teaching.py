"""Direct teaching and cyclic playback through nervous (seed 003 §4.2.1–4.2.2) — a client program's side.

§4.2.1: "全ての筋を 1[kgf] の張力になるように制御しておけば、人間が外から加えた力によって … 張力を 1[kgf] に保つ。
そして、ロボットが目的の姿勢になったところで、各筋の長さを記録する。その姿勢を再現するには、各筋の長さを記録した長さ
になるように制御すれば良い." §4.2.2 (a): "いくつかの姿勢を途中を補間しながら再生することにより動作を実現する" —
Fig. 4.1 (Kenta) teaches three postures and replays them in turn, repeatedly.

Through nervous: the ``servo`` plugin puts every muscle in T mode at the teaching tension (``servo mode T``,
``servo set T_r``); the human — the world, not the client: :meth:`~shintai.nervous.bodies.MuscleRobot.hold`
— moves the spine; the client waits, then reads the encoders (``state angle-vector``: the muscle lengths).
For playback it queues the current lengths with ``:clear`` (so length control starts where the spine is),
switches to L mode, and queues the taught lengths with ``propocmd``, each followed by a hold, waiting on the
``@ID`` of each hold. Waits are in body time (a hold is a queued posture), so the procedure is the same in
real time and as fast as possible.
"""

from __future__ import annotations

from collections.abc import Callable

from shintai.nervous.client import NerveClient
from shintai.nervous.protocol import fmt

KGF = 9.80665


def vector(values) -> str:
    return "#f(" + " ".join(fmt(v) for v in values) + ")"


def hold(client: NerveClient, ms: float, id: str) -> dict:
    """Let ``ms`` of body time pass (a queued hold of the current target); the state after it."""
    current = client.command("sequence angle-vector").replace(",", " ")
    client.command(f"sequence propocmd #f({current}) {fmt(ms)} @{id}")
    client.wait(id)
    return client.state()


def teach(client: NerveClient, hand: Callable[[object], None], postures_deg, settle_ms: float = 1500.0,
          tension_kgf: float = 1.0) -> list[dict]:
    """§4.2.1 for each whole-spine posture (roll, pitch, yaw) [deg]: T mode at ``tension_kgf``, the hand
    holds the spine there for ``settle_ms``, then the state is read; its ``angle-vector`` holds the
    encoder lengths to record [mm]. Returns those states."""
    client.command(f"servo set T_r {fmt(tension_kgf * KGF)}")
    client.command("servo mode T")
    taught = []
    for k, posture in enumerate(postures_deg):
        hand(posture)
        taught.append(hold(client, settle_ms, f"teach{k}"))
    return taught


def to_length_control(client: NerveClient, hand: Callable[[object], None], settle_ms: float = 1000.0) -> None:
    """The hand brings the spine back to the basic posture; the target is set to where the muscles are
    (``:clear``); L mode holds those lengths; the hand lets go."""
    hand((0.0, 0.0, 0.0))
    state = hold(client, settle_ms, "home")
    client.command(f"sequence propocmd {vector(state['angle-vector'])} 1 :clear @sync")
    client.wait("sync")
    client.command("servo mode L")
    hand(None)


def play(client: NerveClient, taught, cycles: int, move_ms: float, hold_ms: float,
         at_hold: Callable[[int, int, dict], None] | None = None) -> None:
    """§4.2.2 (a): the taught lengths in turn, ``cycles`` times — each reached in ``move_ms`` (minimum jerk)
    and held ``hold_ms``; ``at_hold(cycle, k, state)`` sees the state at the end of each hold."""
    for c in range(cycles):
        for k, lengths in enumerate(taught):
            client.command(f"sequence propocmd {vector(lengths)} {fmt(move_ms)} @c{c}p{k}")
            client.command(f"sequence propocmd {vector(lengths)} {fmt(hold_ms)} @c{c}h{k}")
            client.wait(f"c{c}h{k}")
            if at_hold is not None:
                at_hold(c, k, client.state())
