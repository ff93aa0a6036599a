"""``spine.sq43-uneven``: SQ43 crawls over unknown uneven ground, levelling its shoulder and hip by the
accelerometers after each touchdown (seed 003 §3.2.4 不整地歩行, Fig. 3.8), on the MuJoCo SQ43 with a block under
the left feet (:mod:`shintai.spine.sq43.uneven`). Three runs: with the levelling; the same crawl without it (the
spine's passive adaptation); and without it on a trunk rigid in torsion (ablation)."""

from __future__ import annotations

from dataclasses import replace

from shintai.scenarios.experiment import variant_metric
from shintai.scenarios.registry import Check, Param, ThesisValue, experiment
from shintai.spine.sq43 import plots as P
from shintai.spine.sq43.body import BODY
from shintai.spine.sq43.gaits import CrawlPlan
from shintai.spine.sq43.levelling import Levelling
from shintai.spine.sq43.uneven import Ground, uneven_result, uneven_rig

VARIANTS = ("levelling", "passive", "rigid")
RIGID = replace(BODY, twist_free=False)  # ablation: no torsion hinges
VIEW = {"fps": 20, "width": 480, "height": 360, "track": "shoulder", "distance": 0.9, "azimuth": 150.0,
        "elevation": -15}


def rig(params, variant, seed):
    ground = replace(Ground(), height_mm=params["height_mm"])
    law = Levelling(gain=params["gain"]) if variant == "levelling" else None
    return uneven_rig(ground, CrawlPlan(), int(params["cycles"]), law, params["timeout_s"],
                      spec=RIGID if variant == "rigid" else BODY, view=VIEW)


def metrics(runs, params):
    out = {}
    for variant, run in runs.items():
        r = uneven_result(run.log, run.state)
        out |= {variant_metric(k, variant): v for k, v in r.items() if k != "series"}
    h = params["height_mm"]
    out["lf_bend_fraction"] = -out["lf_shortest_levelling_mm"] / h
    out["lf_extend_fraction"] = (out["lf_final_levelling_mm"] - out["lf_shortest_levelling_mm"]) / h
    return out


def plots(ctx, runs, params):
    P.uneven(ctx, {v: uneven_result(r.log, r.state)["series"] for v, r in runs.items()}, params["height_mm"])


experiment(
    "spine.sq43-uneven",
    source="seed 003 §3.2.4 (walking on uneven ground), Fig. 3.8",
    covers=("003:fig3.8",),
    summary="SQ43 (MuJoCo): the crawl over a block under the left feet pauses after each touchdown and levels the "
            "shoulder/hip by the accelerometers; the left front leg bends stepping up and extends stepping down",
    params=[
        Param("height_mm", Ground.height_mm, "block height under the left feet (not in the text)", lo=2.0, hi=30.0),
        Param("gain", Levelling.gain, "fraction of the measured height error corrected per steady reading",
              lo=0.05, hi=1.5),
        Param("cycles", 3, "crawl cycles (four legs each); 3 step the left front foot onto and off the block",
              lo=1, hi=10),
        Param("timeout_s", 5.0, "longest levelling pause before the crawl goes on unlevelled", lo=1.0, hi=30.0),
    ],
    checks=[
        Check("min_feet_in_contact_levelling", "==", 4, "§3.2.4: '脊椎のねじれ方向の柔軟性により … 四脚全てを接地"
              "することができる' — all four feet on the ground at the end of every levelling pause",
              name="four_feet_after_levelling", kind="reproduction"),
        Check("max_shoulder_roll_after_levelling_deg", "<=", 1.0, "§3.2.4: '肩・腰が水平になったら … そこからの相対"
              "量でクローラ歩容の動きを行う' — shoulder level after each adjustment; 1° = twice the 0.5° dead band "
              "(as spine.sq43-levelling)", name="shoulder_level_after", kind="reproduction"),
        Check("max_hip_roll_after_levelling_deg", "<=", 1.0, "§3.2.4: '肩・腰の部分水平になるように前脚・後脚の曲げ"
              "角度を調節する' — hip level after each adjustment; 1° as for the shoulder", name="hip_level_after",
              kind="reproduction"),
        Check("lf_bend_fraction", ">=", 0.5, "Fig. 3.8 (3): '左前脚を曲げて肩を水平にする' on the higher ground — the "
              "left front leg shortened by at least half the block's height (half ours)", kind="reproduction"),
        Check("lf_extend_fraction", ">=", 0.5, "Fig. 3.8 (6): 'また高さが変わったら … 左前脚を伸ばし' — extended "
              "again by at least half the block's height after stepping down (half ours)", kind="reproduction"),
        Check("forward_levelling_mm", ">", 0.0, "§3.2.4: '地面の形状がわからない不整地を歩行する'",
              name="walks_over", kind="reproduction"),
        Check("min_feet_in_contact_passive", "==", 4, "§3.2.4: the spine '地面になじむように … 変形し, 四脚全てを接地"
              "することができる' — passively, without the levelling", name="four_feet_passive", kind="reproduction"),
        Check("min_feet_in_contact_rigid", "<", 4, "§3.2.4: '体幹が剛体である場合は, 未知の不整地では四脚全てを接地する"
              "ことが難しい' — with the torsion hinges removed (ablation) a foot is off the ground at some touchdown",
              name="rigid_trunk_loses_a_foot", kind="reproduction"),
        Check("timeouts_levelling", "==", 0, "every pause ends level, none by the timeout (our controller)",
              kind="consistency"),
    ],
    thesis={"uneven": ThesisValue("crawl over unknown uneven ground, LF bent (3) and extended (6), all four feet down "
                                  "(photographs, no number)", "§3.2.4 Fig. 3.8", "lf_bend_fraction")},
    video=True,
    rig=rig, variants=VARIANTS, filmed=("levelling",), metrics=metrics, plots=plots,
    smoke={"cycles": 1, "timeout_s": 2.0},
)
