"""``snake.handcart``: handcart steering, seed 001 §3.4.2 — the n = 15 snake raises head and tail (double-arm
model) and pushes a wheeled cart 0.5 m; on MuJoCo (compared with the kinematic run) or on the kinematic plant."""

from __future__ import annotations

from shintai.scenarios.registry import Check, Param, ThesisValue, experiment
from shintai.snake.constants import HANDCART
from shintai.snake.handcart import handcart_metrics, handcart_rig, handcart_series
from shintai.snake.plots import plot_handcart


def variants(params):
    return ("mujoco", "kinematic") if params["plant"] == "mujoco" else ("kinematic",)


def rig(params, variant, seed):
    return handcart_rig(params["duration_s"], variant)


def metrics(runs, params):
    reference = handcart_series(runs["kinematic"]) if params["plant"] == "mujoco" else None
    return handcart_metrics(handcart_series(runs[params["plant"]]), reference)


def plots(ctx, runs, params):
    plot_handcart(ctx, handcart_series(runs[params["plant"]]))


experiment(
    "snake.handcart",
    source="seed 001 §3.4.2",
    covers=("001:fig3.10",),
    summary="n = 15 snake, head and tail raised (double-arm model of model3d), pushes a wheeled cart 0.5 m",
    params=(Param("duration_s", HANDCART.t_end, "simulated time; the ramp (3.26) keeps t_end", lo=0.05,
                  hi=HANDCART.t_end),
            Param("plant", "mujoco", "mujoco: physical snake and cart (joint encoders, mocap head pose); "
                  "kinematic: the double-arm model itself with a pushed cart", choices=("mujoco", "kinematic"))),
    checks=(
        Check("max_pos_error_m", "<=", 0.01, "thesis §3.4.2: controlled variables follow the targets (Fig. 3.10c, "
              "no number); 1 cm as for caging (spec §5.4 #11, #14)", kind="reproduction"),
        Check("relative_pose_drift_m", "<=", 0.005, "thesis §3.4.2: the head–tail relation is kept, or the ends slip "
              "off the handles; 'a few mm' from spec §5.4 #14", kind="consistency"),
        Check("cart_displacement_m", ">=", 0.4, "thesis §3.4.2 / Fig. 3.11: the cart is steered along; both ends "
              "advance 0.5 m", kind="reproduction"),
    ),
    thesis={"result": ThesisValue("targets followed; cart steered by head and tail (Figs. 3.10–3.11, no numbers)",
                                  "seed 001 §3.4.2", "cart_displacement_m")},
    rig=rig, variants=variants, filmed=("mujoco",), metrics=metrics, plots=plots,
    video=lambda params: params["plant"] == "mujoco",
    smoke={"duration_s": 0.5},
)
