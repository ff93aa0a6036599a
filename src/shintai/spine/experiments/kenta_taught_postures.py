"""``spine.kenta-taught-postures``: Fig. 4.1 on the whole-body Kenta (seed 003 §4.2.1–4.2.2): three postures taught
with every muscle tension-controlled, replayed in turn with minimum-jerk interpolation, cycled; and the locked-reel probe. Two rigs (:mod:`shintai.spine.kenta.postures`), each with its teaching as the
prelude: the replay, and one taught posture held with its reels locked."""

from __future__ import annotations

import math

from shintai.scenarios.registry import Check, Param, ThesisValue, experiment
from shintai.spine.kenta.constants import KENTA_KEY_POSTURES_DEG, KENTA_TAUGHT_S
from shintai.spine.kenta.plots import taught_postures
from shintai.spine.kenta.postures import lock_result, lock_rig, replay_result, replay_rig

VIEW = {"fps": 15, "width": 480, "height": 360, "track": "link0", "distance": 1.8, "azimuth": 150.0, "elevation": -10}


VARIANTS = ("replay", "lock")  # the replay of Fig. 4.1, then the locked-reel probe


def rig(params, variant, seed):
    if variant == "replay":
        return replay_rig(params["teach_kgf"], int(params["cycles"]), params["period_s"], params["move_s"],
                          params["hold_s"], params["zeroing_s"], view=VIEW)
    return lock_rig(params["teach_kgf"], params["hold_s"], params["lock_s"], params["zeroing_s"])


def _replay(runs):
    run = runs["replay"]
    return run.log, run.state, run.body


def metrics(runs, params):
    out = replay_result(*_replay(runs))
    series = out.pop("series")
    out["cycle_timing_error_s"] = (abs(out["measured_cycle_period_s"] - out["cycle_period_s"])
                                   if math.isfinite(out["measured_cycle_period_s"]) else float("nan"))
    for k, (wanted, taught) in enumerate(zip(KENTA_KEY_POSTURES_DEG, series["taught"])):
        out[f"posture_{k + 1}_taught_offset_deg"] = float(sum((a - b) ** 2 for a, b in zip(wanted, taught)) ** 0.5)
    return out | lock_result(runs["lock"].body, runs["lock"].state)


experiment(
    "spine.kenta-taught-postures",
    source="seed 003 §4.2.2, Fig. 4.1",
    covers=("003:fig4.1", "003:fig3.53"),
    summary="Kenta (whole body): three postures taught under 1 kgf tension control, replayed in turn with "
            "minimum-jerk interpolation in L mode, cycled",
    params=[
        Param("teach_kgf", 1.0, "teaching tension of every muscle [kgf] (§4.2.1: e.g. 1 kgf)", lo=0.1, hi=5.0),
        Param("zeroing_s", 1.0, "§4.6.4 encoder zeroing time (LL at the just-taut limit) [s]", lo=0.2, hi=5.0),
        Param("hold_s", KENTA_TAUGHT_S, "how long the teacher holds each posture before it is read [s]", lo=0.1,
              hi=10.0),
        Param("cycles", 2, "replay cycles through the three postures", lo=1, hi=10),
        Param("period_s", 2.0, "time from one posture's command to the next [s]", lo=0.2, hi=10.0),
        Param("move_s", 1.0, "minimum-jerk move to each posture [s]", lo=0.1, hi=10.0),
        Param("lock_s", 0.5, "the locked-reel probe: a taught forward bend with every reel locked, this long [s]",
              lo=0.05, hi=5.0),
    ],
    checks=[
        Check("nearest_taught_fraction", ">=", 1.0,
              "§4.2.2 '腱太(第 3.7節参照)に三種類の姿勢を教示し，それを順に繰り返し再生する' (Fig. 4.1): every "
              "replayed posture is recognisably its taught one — nearer to it than to the other two (ours: no "
              "tolerance is printed)",
              kind="reproduction", row="003:fig4.1"),
        Check("mean_replay_error_deg", "<=", 5.0,
              "§3.7.6 '全身の動きを利用した人間の動きに近づいた動きを可能にしている' with §4.2.1 (replaying "
              "the recorded lengths reproduces the posture): within 5° of the taught whole-spine angles (ours)",
              kind="reproduction", row="003:fig3.53"),
        Check("cycle_timing_error_s", "<=", 0.2, "the replayed motion repeats once per commanded cycle (its "
              "autocorrelation peak; derived: our schedule, 0.2 s ours)", kind="consistency"),
    ],
    thesis={"taught_and_replayed": ThesisValue(
        "three postures, replayed in turn repeatedly",
        "seed 003 §4.2.2 '三種類の姿勢を教示し，それを順に繰り返し再生する'",
        "nearest_taught_fraction")},
    constraints=[(lambda p: p["move_s"] <= p["period_s"], "move_s must not exceed period_s")],
    video=True,
    rig=rig, variants=VARIANTS, filmed=("replay",), metrics=metrics,
    plots=lambda ctx, runs, params: taught_postures(ctx, replay_result(*_replay(runs))["series"]),
    smoke={"zeroing_s": 0.2, "hold_s": 0.1, "cycles": 1, "period_s": 0.2, "move_s": 0.1, "lock_s": 0.1},
)
