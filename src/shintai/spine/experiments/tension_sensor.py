"""``spine.tension-sensor``: Cla's tension sensor calibrated on a bench, as Fig. 3.34 was (seed 003 §3.6.1, eq. 3.3):
known tensions applied, each read as the 10-bit ADC count, and the resolution (the width of one count step [N])
found along the curve. The sensor is :class:`~shintai.spine.actuators.TensionSensor` (eq. 3.3, the FSR in a divider,
the ADC). No body and no loop: a compute experiment. One sensor (the thesis calibrated two FSR sizes, #400 and
#402; our :class:`~shintai.spine.robots.TensionSensorSpec` is one chosen set of constants)."""

from __future__ import annotations

import numpy as np

from shintai.scenarios.registry import Check, Param, ThesisValue, scenario
from shintai.spine.actuators import TensionSensor
from shintai.spine.plots import tension_sensor as plot
from shintai.spine.robots import CLA, SENSOR_COARSE_RATIO, SENSOR_PROBE_N, SENSOR_SWEEP_STEP_N

QUOTE = "§3.6.1 (Fig. 3.34): '小さい力の領域で分解能が高く大きい力の領域で分解能が粗い事がわかる'"


def count_steps(tension, counts):
    """The tensions where the count changes (the sweep's first sample of each new count) and the widths of the
    count steps between them [N]."""
    edges = tension[1:][np.diff(counts) != 0]
    return edges, np.diff(edges)


def step_at(edges, widths, t: float) -> float:
    """The width [N] of the count step that contains tension ``t``."""
    k = int(np.searchsorted(edges, t, side="right")) - 1
    return float(widths[min(max(k, 0), len(widths) - 1)])


@scenario(
    "spine.tension-sensor",
    source="seed 003 §3.6.1, Fig. 3.34, eq. 3.3",
    covers=("003:fig3.34",),
    summary="Cla's tension sensor on a bench: known tensions against the 10-bit count; the resolution is fine at "
            "small tensions and coarse at large ones (a property of eq. 3.3 and the FSR divider)",
    params=(Param("max_n", CLA.motors[0].max_tension_n, "largest tension applied [N] (Table 3.2's maximum muscle "
                  "tension)", lo=SENSOR_PROBE_N[-1], hi=1000.0),
            Param("step_n", SENSOR_SWEEP_STEP_N, "tension step of the sweep [N]", lo=1e-4, hi=0.01)),
    checks=(
        Check("steps_monotone", "==", 1, QUOTE + " — every count step at a larger probe tension is at least as "
              "wide: follows from our sensor model's saturation (eq. 3.3 with chosen l, b, k and FSR divider)",
              kind="consistency"),
        Check("coarsening_ratio", ">=", SENSOR_COARSE_RATIO, QUOTE + f" — the step at {SENSOR_PROBE_N[-1]:g} N at "
              f"least {SENSOR_COARSE_RATIO:g}× the step at {SENSOR_PROBE_N[0]:g} N (declared before the run); our "
              "constants were chosen for it (robots.TensionSensorSpec), so this is consistency", kind="consistency"),
        Check("readback_error_large_n", ">", "readback_error_small_n", "the read-back error (count → tension through "
              "the calibration table) grows with the step: half a step", kind="consistency"),
    ),
    thesis={"resolution": ThesisValue("fine at small forces, coarse at large (curves only, no number)",
                                      "seed 003 " + QUOTE, "coarsening_ratio")},
    smoke={"step_n": 0.01},
)
def tension_sensor(ctx) -> dict:
    p = ctx.params
    sensor = TensionSensor(CLA.sensor)
    tension = np.arange(0.0, p["max_n"] + p["step_n"] / 2, p["step_n"])
    counts = sensor.adc(tension)
    edges, widths = count_steps(tension, counts)
    probes = [t for t in SENSOR_PROBE_N if t <= p["max_n"]]
    steps = [step_at(edges, widths, t) for t in probes]
    error = np.abs(sensor.read(tension) - tension)
    small, large = tension <= probes[1], tension >= probes[-2]
    ctx.recorder.record(0.0, tension_n=tension[::max(1, len(tension) // 4000)],
                        count=counts[::max(1, len(tension) // 4000)])
    plot(ctx, tension, counts, probes, steps)
    return {**{f"step_at_{t:g}n_n": s for t, s in zip(probes, steps)},
            "counts_used": int(counts.max() - counts.min()), "count_at_max": int(counts[-1]),
            "steps_monotone": int(all(b >= a for a, b in zip(steps, steps[1:]))),
            "coarsening_ratio": steps[-1] / steps[0],
            "readback_error_small_n": float(error[small].max()), "readback_error_large_n": float(error[large].max())}
