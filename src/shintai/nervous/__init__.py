"""nervous — the middle layer between programs and robot bodies (seed 003 ch. 6, App. C).

:mod:`~shintai.nervous.hal` (the four calls of §6.3.1, ``sim`` and ``dummy``), :mod:`~shintai.nervous.robot`
(descriptions generated from the model, §6.3.2), :mod:`~shintai.nervous.protocol` and
:mod:`~shintai.nervous.commands` (the line rules of C.2.1), :mod:`~shintai.nervous.nerve` (the plugin loop,
§6.3.4), :mod:`~shintai.nervous.server` (the socket server, §6.3.3), :mod:`~shintai.nervous.plugins`,
:mod:`~shintai.nervous.client` (``NerveClient``), :mod:`~shintai.nervous.plots` (the experiments' figures).
The protocol with a session: ``README.md`` here.

Modules:

benchmarks — ``nervous.loop``: what nervous costs per sensor packet, how fast a command reaches the target, how …
coverage — Coverage rows of seed 003 (Mizuuchi 2001) chapter 6 and Appendix C — the middle layer "nervous" — for …
crowd — Several client programs on one nervous server at once (seed 003 §6.3.3: "上位層のプログラムからのマルチコネク …
motions — Motions a command queued, named by its ``@ID``, and waiting for them without a race
robots — The robots nervous serves (``--robot NAME``): each builds its MuJoCo body and generates its …
stats — Timing of nervous's loop: the period between packets, each tick's cost against the packet period (an …
teaching — Direct teaching and cyclic playback through nervous (seed 003 §4.2.1–4.2.2) — a client program's side
"""
