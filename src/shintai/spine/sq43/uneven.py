"""SQ43 crawls over unknown uneven ground, levelling by its accelerometers (seed 003 §3.2.4 不整地歩行, Fig. 3.8).

§3.2.4: "基本的には前項に示したクローラ歩容を行うが, 脚を接地した時に地面が平らではないことを検知すると (3 軸
加速度センサにより重力方向を算出), 歩容を中断し肩・腰の部分水平になるように前脚・後脚の曲げ角度を調節する. 肩・
腰が水平になったらその時の各脚の曲げ角を記憶し, そこからの相対量でクローラ歩容の動きを行う". :class:`UnevenCrawl`
plays the planned crawl of :func:`~shintai.spine.sq43.gaits.crawl_schedule`; after each swing leg is down and the
trunk is back over the feet it pauses, reads the accelerometer of that leg's end of the trunk (shoulder for a front
leg, hip for a hind one) when steady and changes that leg's length toward level (:class:`~shintai.spine.sq43.levelling.Levelling`'s
law), until level; each leg's length change is kept as an offset the crawl then runs relative to. The ground is a
block on the floor under the left feet's path (:class:`Ground`), which the left front foot steps onto and off.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from shintai.core.runtime import Module, Snapshot
from shintai.scenarios.experiment import Rig
from shintai.spine.sq43.body import BODY, LEGS, SQ43Body, SQ43BodySpec, accelerometer_roll, leg_ik, roll_of, servo_ctrl
from shintai.spine.sq43.gaits import CRAWL_ORDER, CrawlPlan, crawl_schedule
from shintai.spine.sq43.levelling import Levelling


@dataclass(frozen=True)
class Ground:
    """A block ``height_mm`` high under the left feet, from ``start_mm`` to ``end_mm`` ahead of the left front
    foot's first position (chosen, not in the text). On flat ground the crawl puts the left front foot down
    43.5, 95.5 and 147.1 mm ahead of its start in cycles 1–3 (measured, no block); the block's edges lie midway
    between, so the foot steps onto it in cycle 2 and off it in cycle 3. 60 mm wide, so the right feet stay on
    the floor."""

    height_mm: float = 15.0
    start_mm: float = 70.0
    end_mm: float = 121.0
    width_mm: float = 60.0

    def blocks(self, spec: SQ43BodySpec = BODY) -> tuple:
        x0, y = spec.leg_x, spec.body_width_m / 2
        return ((x0 + 1e-3 * self.start_mm, x0 + 1e-3 * self.end_mm, y - 5e-4 * self.width_mm,
                 y + 5e-4 * self.width_mm, 1e-3 * self.height_mm),) if self.height_mm > 0 else ()


@dataclass
class Pause:
    """One levelling pause: the leg that touched down, when it began and ended [s], the adjustments made, and
    whether it ended level (else it timed out)."""

    leg: str
    start_s: float
    end_s: float = math.nan
    adjustments: int = 0
    level: bool = False


class UnevenCrawl(Module):
    """The crawl's foot targets + per-leg length offsets, paused after each swing for the levelling (module
    docstring); ``levelling`` None: the same crawl with no pauses and no offsets. ``pauses``: what each pause did
    (without levelling, the instants a pause would begin, each ``end_s`` = ``start_s``)."""

    def __init__(self, model, plan: CrawlPlan, cycles: int, levelling: Levelling | None, timeout_s: float,
                 spec: SQ43BodySpec = BODY, dt: float = 0.01):
        super().__init__("uneven_crawl")
        self.model, self.levelling, self.spec, self.dt, self.timeout_s = model, levelling, spec, dt, timeout_s
        self.t_plan, self.targets, windows = crawl_schedule(plan, CRAWL_ORDER * cycles, spec, dt=dt)
        self.at = sorted((b + plan.settle_s, leg) for leg in LEGS for _, b in windows[leg])
        self.k = 0  # index into the schedule
        self.offset = {leg: 0.0 for leg in LEGS}  # leg length change [m] (+: longer)
        self.pauses: list[Pause] = []
        self.window: list[np.ndarray] = []

    @property
    def done(self) -> bool:
        return self.k >= len(self.t_plan) - 1 and not self._paused()

    def _paused(self) -> bool:
        return bool(self.pauses) and math.isnan(self.pauses[-1].end_s)

    def update(self, snapshot: Snapshot):
        t = snapshot["t"]
        if self._paused():
            self._level(snapshot)
        elif self.k < len(self.t_plan) - 1:
            self.k += 1
            due = len(self.pauses) < len(self.at) and self.t_plan[self.k] >= self.at[len(self.pauses)][0]
            if due:
                self.pauses.append(Pause(self.at[len(self.pauses)][1], t))
                self.window = []
                if self.levelling is None:
                    self.pauses[-1].end_s = t
        feet = {leg: self.targets[leg][self.k] - [0.0, 0.0, self.offset[leg]] for leg in LEGS}
        return {"ctrl": servo_ctrl(self.model, {leg: leg_ik(leg, feet[leg], self.spec) for leg in LEGS})}

    def _level(self, snapshot: Snapshot) -> None:
        law, pause, spec = self.levelling, self.pauses[-1], self.spec
        self.window.append(snapshot["acc_shoulder" if pause.leg[1] == "F" else "acc_hip"].copy())
        n = round(law.window_s / self.dt)
        self.window = self.window[-n:]
        if snapshot["t"] - pause.start_s > self.timeout_s:
            pause.end_s = snapshot["t"]
            return
        if len(self.window) < n or np.ptp(np.array(self.window), axis=0).max() >= law.steady_ms2:
            return
        roll = float(accelerometer_roll(np.mean(self.window, axis=0)))
        if abs(math.degrees(roll)) <= law.deadband_deg:
            pause.end_s, pause.level = snapshot["t"], True
            return
        side = 1.0 if pause.leg[0] == "L" else -1.0  # roll > 0: left side up → shorten a left leg, lengthen a right
        self.offset[pause.leg] -= side * law.gain * spec.body_width_m * math.sin(roll)
        pause.adjustments += 1
        self.window = []


def uneven_rig(ground: Ground, plan: CrawlPlan, cycles: int, levelling: Levelling | None, timeout_s: float,
               spec: SQ43BodySpec = BODY, view=None) -> Rig:
    """The crawl over ``ground``, a 10 ms body step (5 physics steps); runs until the schedule and the last pause
    are done. Records after every step: ``t_s``, the true shoulder and hip roll [deg], the feet in contact
    (``contact``, 4 × 0/1 in LEGS order), the trunk centre's x [mm] and the left-front offset [mm]."""
    body = SQ43Body(spec, substeps=round(0.01 / spec.timestep), blocks=ground.blocks(spec))
    model, data = body.model, body.data
    crawl = UnevenCrawl(model, plan, cycles, levelling, timeout_s, spec)
    feet = [model.geom(f"{leg}_foot").id for leg in LEGS]
    adr = {n: model.sensor(n).adr[0] for n in ("shoulder_quat", "hip_quat", "shoulder_pos", "hip_pos")}

    def after(snap):
        touching = np.zeros(4)
        for c in data.contact[:data.ncon]:
            for g in (c.geom1, c.geom2):
                if g in feet:
                    touching[feet.index(g)] = 1.0
        quat = {n: data.sensordata[adr[n]:adr[n] + 4] for n in ("shoulder_quat", "hip_quat")}
        x = 0.5 * (data.sensordata[adr["shoulder_pos"]] + data.sensordata[adr["hip_pos"]])
        return {"t_s": data.time, "shoulder_roll_deg": math.degrees(float(roll_of(quat["shoulder_quat"]))),
                "hip_roll_deg": math.degrees(float(roll_of(quat["hip_quat"]))), "contact": touching,
                "trunk_x_mm": 1e3 * float(x), "lf_offset_mm": 1e3 * crawl.offset["LF"]}

    cap = len(crawl.t_plan) * crawl.dt + len(crawl.at) * (timeout_s if levelling else 0.0)
    return Rig(body, [crawl], duration=cap, until=lambda snap: crawl.done, record={1: after}, view=view or {},
               state=crawl)


def uneven_result(log, crawl: UnevenCrawl) -> dict:
    """At the end of each pause (after its adjustments): the feet in contact (also at the step onto the block alone)
    and the shoulder and hip roll; over the run: the trunk's forward travel, the left-front offset's extremes, the adjustments and the pauses that timed
    out."""
    t = log.values("t_s")
    ends = [int(np.searchsorted(t, p.end_s - 1e-9)) for p in crawl.pauses]
    ends = [min(i, len(t) - 1) for i in ends]
    contact = log.values("contact")[ends].sum(axis=1)
    shoulder, hip = log.values("shoulder_roll_deg")[ends], log.values("hip_roll_deg")[ends]
    lf_mm = log.values("lf_offset_mm")
    x = log.values("trunk_x_mm")
    lf = [i for i, p in enumerate(crawl.pauses) if p.leg == "LF"]
    step_up = int(contact[lf[1]]) if len(lf) > 1 else -1  # the left front's second touchdown: onto the block
    return {"min_feet_in_contact": int(contact.min()), "pauses_all_feet": int(np.sum(contact == 4)),
            "step_up_feet_in_contact": step_up,
            "pauses": len(crawl.pauses), "max_shoulder_roll_after_deg": float(np.abs(shoulder).max()),
            "max_hip_roll_after_deg": float(np.abs(hip).max()), "adjustments": int(sum(p.adjustments for p in crawl.pauses)),
            "timeouts": int(sum(1 for p in crawl.pauses if crawl.levelling is not None and not p.level)),
            "lf_shortest_mm": float(lf_mm.min()), "lf_final_mm": float(lf_mm[-1]), "forward_mm": float(x[-1] - x[0]),
            "max_shoulder_roll_deg": float(np.abs(log.values("shoulder_roll_deg")).max()),
            "series": {"t": t, "shoulder": log.values("shoulder_roll_deg"), "hip": log.values("hip_roll_deg"),
                       "lf": lf_mm, "contact": log.values("contact").sum(axis=1),
                       "pauses": [(p.start_s, p.end_s, p.leg) for p in crawl.pauses]}}
