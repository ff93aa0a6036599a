"""``spine.software-spring``: E10 on the MuJoCo Cla, arms down (seed 003 §4.5.2, eq. 4.36, Figs. 4.13–4.17).
One trial per k_s (:func:`shintai.spine.cla.spring_trial.spring_rig`), and with ``compare`` the same under the
other spring law."""

from __future__ import annotations

from shintai.core.constants import KGF_N
from shintai.scenarios.registry import Check, Param, ThesisValue, experiment
from shintai.spine.cla import plots as pictures
from shintai.spine.cla.setup import SPRING_LAWS
from shintai.spine.cla.spring_trial import spring_rig, trial_metrics


def k_list(params) -> list[float]:
    return [float(k) for k in params["k_s_list"].split(",")]


def trial_names(params) -> dict[str, float]:
    """The trials of the chosen spring law by name (``k50``: k_s = 50), in the order given."""
    return {f"k{int(k)}": k for k in k_list(params)}


def other_law(params) -> str:
    return next(x for x in SPRING_LAWS if x != params["spring_law"])


def variants(params) -> list[str]:
    main = list(trial_names(params))
    return main + ([f"{other_law(params)}.{v}" for v in main] if params["compare"] else [])


def rig(params, variant, seed):
    law, _, name = variant.rpartition(".")  # "newtons.k50": the other law; "k50": the chosen one
    return spring_rig(trial_names(params)[name], params["push_deg"], params["push_s"], params["release_s"],
                      law or params["spring_law"], log=not law)


def trials(runs, params) -> dict[float, dict]:
    return {k: trial_metrics(runs[f"k{int(k)}"].body, runs[f"k{int(k)}"].state) for k in k_list(params)}


def metrics(runs, params):
    ks, main = k_list(params), trials(runs, params)
    out = {f"k_s_{int(k)}.{key}": value for k in ks for key, value in main[k].items()}
    if params["compare"]:
        other = other_law(params)
        for k in ks:
            run = runs[f"{other}.k{int(k)}"]
            out |= {f"{other}.k_s_{int(k)}.{key}": value for key, value in trial_metrics(run.body, run.state).items()}
    changes = [main[k]["tension_change_n"] for k in ks]
    out["tension_change_monotone"] = int(all(b > a for a, b in zip(changes, changes[1:])))
    out["max_return_error_deg"] = max(t["return_error_deg"] for t in main.values())
    out["max_spring_law_error_n"] = max(t["spring_law_error_n"] for t in main.values())
    return out


def plots(ctx, runs, params):
    pictures.software_spring(ctx, k_list(params), trials(runs, params))


def _k_list_ok(text: str) -> bool:
    try:
        ks = [float(k) for k in text.split(",")]
    except ValueError:
        return False
    return all(k > 0 for k in ks) and len({int(k) for k in ks}) == len(ks)


experiment(
    "spine.software-spring",
    source="seed 003 §4.5.2, eq. 4.36, Figs. 4.13–4.17",
    covers=("003:fig4.13",),
    summary="E10 on Cla: all muscles in S mode, k_s = 50/100/200/400; push, release, return; tension change vs k_s",
    params=[
        Param("k_s_list", "50,100,200,400", "software springs, thesis units (ADC counts / encoder counts)"),
        Param("push_deg", 8.0, "whole-spine roll and pitch the hand imposes [deg]", lo=1.0, hi=20.0),
        Param("push_s", 2.0, "how long the hand holds the spine bent [s]", lo=0.2, hi=10.0),
        Param("release_s", 3.0, "time after release to return [s]", lo=0.5, hi=10.0),
        Param("spring_law", "counts", "S mode's spring: on the ADC count (§4.5.2) or linear in newtons",
              choices=SPRING_LAWS),
        Param("compare", True, "also run the other spring law (metrics prefixed with its name)"),
    ],
    checks=[
        Check("tension_change_monotone", "==", 1, "§4.5.2 / Figs. 4.14–4.17: the larger k_s, the larger the "
              "tension change for the same displacement", kind="consistency"),
        Check("max_return_error_deg", "<=", 2.0, "§4.5.2 (Fig. 4.13): released, the spine returns; derived: the "
              "dead band T_t / k_s over the pitch moment arm is ≤ 1.1° for the softest spring", kind="reproduction"),
        Check("max_spring_law_error_n", "<=", 0.05 * KGF_N + 0.2, "eq. 4.39: at rest |T − k_s(l_0 − l)| stays within "
              "the dead band T_t (0.05 kgf) plus sensor quantisation", kind="consistency"),
    ],
    thesis={"k_s": ThesisValue("50, 100, 200, 400 (ADC counts / encoder counts)", "§4.5.2"),
            "trend": ThesisValue("larger k_s → larger tension change for a small length change", "§4.5.2")},
    constraints=[(lambda p: _k_list_ok(p["k_s_list"]),
                  "k_s_list: a comma list of positive numbers with distinct integer parts (they name the runs)")],
    rig=rig, variants=variants, filmed=lambda p: list(trial_names(p))[-1:],  # the stiffest spring
    metrics=metrics, plots=plots,
    video=True,
    smoke={"k_s_list": "50,400", "push_s": 0.8, "release_s": 1.5},
)
