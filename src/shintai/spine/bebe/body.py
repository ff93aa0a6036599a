"""BeBe: sensor-based visual tracking with 36 on/off muscles and no geometric model (seed 003 §4.8).

The thesis (§4.8.3) rejects a kinematic model for BeBe: superposition of single-muscle postures does
not hold and the body has hysteresis, θ(t) = f(q(t), q(t−1), θ(t−1)) (4.44). Instead it measures,
from the all-off state with the target at the image centre, the image motion of the target when one
muscle i alone is switched on (Fig. 4.52, 4.53), and runs a rule every image cycle (66 ms, §4.8.4):

1. v = direction of the target from the image centre;
2. muscles whose view shift v_i makes cos∠(v, v_i) > 0.2 are *same-direction*, the others
   *inverse-direction*;
3. if an inverse-direction muscle is on, switch off the one at the largest angle to v;
4. otherwise, if a same-direction muscle is off, switch on the one at the smallest angle to v;
5. inside a central dead zone do nothing.

The text calls v_i both the target's motion in the image (Fig. 4.52) and the *view shift* (視野のずれ,
§4.8.3). Only the view shift makes "same direction" move the target towards the centre, so we store
the target's measured image motion d_i and use v_i = −d_i.

**The plant is ours** (the muscle table 4.10 and the v_i of Fig. 4.53 are not in the text). BeBe's
24 vertebrae are lumped into the six regions of Fig. 4.50 (waist fixed, abdomen 2, abdomen 1, chest,
shoulder, head) joined by five 3-DOF ball joints, built with the project's geometric model
(:mod:`shintai.spine.geometry`: Chain, eq. 4.25 lengths, analytic J_m). 36 McKibben muscles run
straight between rings on the regions: rectus-, erector-, lateral- and oblique-like (Fig. 4.49), each
kind on three spans. What makes it non-superposing and hysteretic, as the thesis measured:

* McKibben force falls linearly with contraction and vanishes at the 30 % stroke (the shape of
  Fig. 4.47), and a muscle stretched past its rest length pulls passively — two muscles do not add:
  two co-operating muscles on the same joints shorten each other as they bend the spine, so each
  pulls less than it did alone (the geometric coupling of co-activated pneumatic muscles). This is
  what the superposition test (:func:`superposition_error` on :func:`cooperating_pairs`) measures;
* the lumped discs stiffen (τ = −k₁Δ − k₃Δ³ per joint axis) and the moment arms change with posture;
* Coulomb friction in every joint axis: the posture moves only where the net torque exceeds τ_f
  (stick-slip), so the rest posture depends on the history — eq. (4.44);
* valve/pressure lag τ_p, so one switch acts over several image cycles.

Motion is overdamped (c θ̇ = the torque beyond friction; no inertia, no gravity — chosen: BeBe
stands on its base and its inertia is not what the rule is about). A head camera (pinhole) sees a
target point in the world; a push on the middle of the spine (Fig. 4.55) enters as an external
force; forced-on muscles (Fig. 4.56) are held on outside the rule.

Why regions and not BeBe's 24 joints: ``notes/bebe-tracking.md``.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from shintai.core import Body, Loop, Module, Recorder, SimulationDiverged
from shintai.core.geometry import cross3
from shintai.core.runtime import SET, FunctionModule, declare
from shintai.spine.bebe.constants import MIDDLE, SPANS
from shintai.spine.geometry import Chain, MuscleSet, SpineModel
from shintai.spine.robots import BEBE

CYCLE_S = BEBE.image_period_s  # 66 ms image feedback, §4.8.4
COS_THRESHOLD = BEBE.cos_threshold  # §4.8.3, "cos θ_i = 0.2", chosen empirically by the thesis
REGIONS = ("waist", "abdomen 2", "abdomen 1", "chest", "shoulder", "head")  # Fig. 4.50, bottom to top

# (kind, angle at the lower ring, angle at the upper ring) [deg], from +x (front) towards +y (left).
# Chosen, because Table 4.10 is not in the text: Fig. 4.49 copies the rectus abdominis (front,
# flexion), the back muscles (extension), lateral muscles and the internal/external obliques
# (lateral bending together, rotation against each other, §4.8.2).
MUSCLE_KINDS = (
    ("rectus-L", 20.0, 20.0), ("rectus-R", -20.0, -20.0),
    ("erector-L", 160.0, 160.0), ("erector-R", -160.0, -160.0),
    ("lateral-L", 90.0, 90.0), ("lateral-R", -90.0, -90.0),
    ("ext-oblique-L", 40.0, 110.0), ("ext-oblique-R", -40.0, -110.0),
    ("int-oblique-L", 110.0, 40.0), ("int-oblique-R", -110.0, -40.0),
    ("back-oblique-L", 140.0, 70.0), ("back-oblique-R", -140.0, -70.0),
)


@dataclass(frozen=True)
class BeBeParams:
    """Plant constants (chosen: the thesis gives none for BeBe beyond 36 muscles, ≈4 atm, ≈720 mm)."""

    region_length_m: float = 0.12  # 6 × 0.12 = 0.72 m, the ≈720 mm total length (Fig. 4.44)
    ring_radius_m: float = 0.07  # muscle attachment ring (ribs / processes), at mid-height of a region
    joint_limit_deg: float = 30.0  # lumped joint range (~5 vertebrae of a few degrees each, §1.2)
    camera_height_m: float = 0.08  # camera above the head joint, looking along the head's +x
    focal_px: float = 300.0  # image resolution not given; ≈46° field of view on a 256-px-wide image
    target_distance_m: float = 0.6  # target in front of the camera in the straight, all-off posture
    f_max_n: float = 30.0  # McKibben force at zero contraction: a small (∅6-mm class) muscle at ≈4 atm
    strength_spread: float = 0.2  # per-muscle ± spread of f_max (self-made vs Shadow muscles, §4.8.2)
    k_passive_n: float = 400.0  # passive pull per unit stretch ratio of a muscle
    tau_p_s: float = 0.05  # valve + tube pressure time constant of a small muscle
    disc_k1: tuple = (6.0, 6.0, 10.0)  # lumped disc stiffness per joint (roll, pitch, yaw) [N·m/rad]
    disc_k3: float = 60.0  # cubic stiffening [N·m/rad³]
    friction_nm: float = 0.15  # Coulomb friction per joint axis [N·m]: the hysteresis of (4.44)
    damping: float = 0.2  # per joint axis [N·m·s/rad]
    dt: float = CYCLE_S / 5  # 5 plant steps per image cycle (the step is implicit in the stiffness)


def bebe_model(prm: BeBeParams = BeBeParams()) -> SpineModel:
    """The lumped six-region chain and its 36 muscles (module doc), as a geometric model (§4.4)."""
    h, r = prm.region_length_m, prm.ring_radius_m
    chain = Chain.straight([h] * (len(REGIONS) - 1), np.radians(prm.joint_limit_deg))
    names, paths = [], []
    for lower, upper in SPANS:
        for kind, lo, hi in MUSCLE_KINDS:
            ring = [(link, (r * np.cos(np.radians(a)), r * np.sin(np.radians(a)), h / 2))
                    for link, a in ((lower, lo), (upper, hi))]
            names.append(f"{kind}/{REGIONS[lower]}-{REGIONS[upper]}")
            paths.append(ring)
    return SpineModel(chain, MuscleSet.from_paths(names, paths))


def point_jacobian(model: SpineModel, R: np.ndarray, p: np.ndarray, Q: np.ndarray, theta: np.ndarray,
                   link: int, x: np.ndarray) -> np.ndarray:
    """∂x/∂θ (3, 3n) of a point x fixed to ``link``: a_k × (x − c_k) for the joints below it."""
    axes = model.chain.joint_axes(theta, Q)
    centres = np.repeat(p[1:], 3, axis=0)
    below = np.repeat(np.arange(1, model.n + 1), 3) <= link
    return (cross3(axes, x - centres) * below[:, None]).T


class BeBePlant(Body):
    """36 on/off McKibben muscles on the lumped six-region spine with a head camera (our plant, module doc).

    Command channels: ``valve`` (36, on if > 0.5) and ``push`` (3, external force [N] on abdomen 1).
    Snapshot: ``t``, ``target_px`` (2, target minus image centre, x right / y up), ``theta`` (15 joint
    angles), ``valve``, ``pressure``.
    """

    channels = {**declare("valve", kind=SET), **declare("push")}  # the valve mask has one writer; pushes add

    def __init__(self, params: BeBeParams = BeBeParams(), target=None, rng: np.random.Generator | None = None):
        self.prm = params
        self.model = bebe_model(params)
        self.dt = params.dt
        self.t = 0.0
        m = self.model.m
        spread = params.strength_spread
        scale = np.ones(m) if rng is None else rng.uniform(1 - spread, 1 + spread, m)
        self.f_max = params.f_max_n * scale
        self.theta = np.zeros(3 * self.model.n)
        self.valve = np.zeros(m)
        self.pressure = np.zeros(m)
        self.push = np.zeros(3)
        self.rest_length = self.model.lengths(self.theta)
        self._frames_at = None
        self.target = target if target is not None else (lambda t: np.zeros(3))  # world offset from home
        R, p, _ = self.frames()
        self.target_home = p[-1] + R[-1] @ np.array([params.target_distance_m, 0.0, params.camera_height_m])

    def frames(self) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """Link frames (R, p, Q) at the current posture, computed once per step."""
        if self._frames_at != self.t:
            self._frames, self._frames_at = self.model.chain.frames(self.theta), self.t
        return self._frames

    def image(self) -> np.ndarray:
        """Pinhole image of the target relative to the image centre [px], x right, y up; the camera
        sits ``camera_height_m`` above the top joint and looks along the head's +x."""
        return self.image_at(self.t)

    def image_at(self, t: float) -> np.ndarray:
        """The image of the target at time ``t`` seen from the current posture."""
        R, p, _ = self.frames()
        cam = p[-1] + R[-1] @ np.array([0.0, 0.0, self.prm.camera_height_m])
        c = R[-1].T @ (self.target_home + self.target(t) - cam)
        return self.prm.focal_px * np.array([-c[1], c[2]]) / c[0]

    def tension(self, lengths: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """McKibben tension T and its slope dT/dl: p·F_max·(1 − ε/ε_max)⁺ active, plus a passive
        pull when stretched past the rest length (ε < 0)."""
        l0, eps_max = self.rest_length, BEBE.contraction_ratio
        eps = (l0 - lengths) / l0  # contraction ratio
        acting = eps < eps_max
        active = self.pressure * self.f_max * np.where(acting, 1.0 - eps / eps_max, 0.0)
        stretched = eps < 0
        T = active + self.prm.k_passive_n * np.where(stretched, -eps, 0.0)
        slope = (self.pressure * self.f_max * acting / eps_max + self.prm.k_passive_n * stretched) / l0
        return T, slope

    def step(self) -> None:
        """Overdamped c θ̇ = τ beyond Coulomb friction (stick while |τ| ≤ τ_f), linearly implicit:
        Δθ = dt (c I + dt K)⁻¹ slip(τ) with the tangent stiffness K = J_mᵀ diag(dT/dl) J_m + discs
        (the muscles are far stiffer than dt allows explicitly); then the pressure lag."""
        th, prm = self.theta, self.prm
        R, p, Q = self.frames()
        _, seg = self.model.muscles.segments(self.model.muscles.world_points(R, p))
        T, slope = self.tension(self.model.muscles.sum_per_muscle(seg))
        J = self.model.jacobian(th)
        k1 = np.tile(prm.disc_k1, self.model.n)
        tau = -J.T @ T - (k1 * th + prm.disc_k3 * th ** 3)
        if np.any(self.push):
            tau += point_jacobian(self.model, R, p, Q, th, MIDDLE, p[MIDDLE]).T @ self.push
        K = J.T @ (slope[:, None] * J) + np.diag(k1 + 3 * prm.disc_k3 * th ** 2)
        slip = np.sign(tau) * np.clip(np.abs(tau) - prm.friction_nm, 0.0, None)
        self.theta = th + np.linalg.solve(prm.damping * np.eye(len(th)) + self.dt * K, self.dt * slip)
        self.pressure += self.dt / prm.tau_p_s * (self.valve - self.pressure)
        self.t += self.dt
        if not np.all(np.isfinite(self.theta)):
            raise SimulationDiverged(f"BeBePlant: non-finite posture at t = {self.t:.3f} s")

    def snapshot(self) -> dict:
        return {"t": self.t, "target_px": self.image(), "theta": self.theta.copy(), "valve": self.valve.copy(),
                "pressure": self.pressure.copy()}

    def apply(self, command: dict) -> None:
        if "valve" in command:
            self.valve = (np.asarray(command["valve"]) > 0.5).astype(float)
        self.push = np.asarray(command.get("push", np.zeros(3)), dtype=float)


def settle(plant: BeBePlant, valve: np.ndarray, seconds: float) -> np.ndarray:
    """Hold ``valve`` for ``seconds`` (no controller) and return the final target image position."""
    Loop(plant, [], base={"valve": valve}).run(seconds)
    return plant.snapshot()["target_px"]


# ------------------------------------------------------------------------------------- calibration

def calibrate(make_plant, settle_s: float = 1.0) -> np.ndarray:
    """Single-muscle calibration (§4.8.3, Fig. 4.52): view shifts v_i (36, 2) [px].

    For each muscle, from a fresh all-off plant with the target at the centre, switch that muscle
    alone on and record the target's image motion d_i after ``settle_s``; v_i = −d_i (module doc).
    A fresh plant each time, because the thesis measures every muscle "from the all-off state".
    """
    shifts = []
    for i in range(make_plant().model.m):
        plant = make_plant()
        start = plant.snapshot()["target_px"]
        valve = np.zeros(plant.model.m)
        valve[i] = 1.0
        shifts.append(start - settle(plant, valve, settle_s))
    return np.array(shifts)


def superposition_error(make_plant, shifts: np.ndarray, pairs, settle_s: float = 1.0) -> np.ndarray:
    """‖v_ij − (v_i + v_j)‖ / ‖v_i + v_j‖ for muscle pairs: the superposition test of §4.8.3."""
    errors = []
    for i, j in pairs:
        plant = make_plant()
        start = plant.snapshot()["target_px"]
        valve = np.zeros(plant.model.m)
        valve[[i, j]] = 1.0
        both = start - settle(plant, valve, settle_s)
        errors.append(np.linalg.norm(both - shifts[i] - shifts[j]) / np.linalg.norm(shifts[i] + shifts[j]))
    return np.array(errors)


def cooperating_pairs(shifts: np.ndarray, spans: int, cos_threshold: float = COS_THRESHOLD) -> list[tuple[int, int]]:
    """The muscle pairs the superposition test of §4.8.3 is about: two muscles on the *same span*
    (so they act on the same joints) whose single-muscle view shifts point the same way,
    cos∠(v_i, v_j) > ``cos_threshold`` (the rule's own "same direction"). Muscles are numbered span by
    span (``spans`` blocks of equal size). Pairs on different spans act on different joints and
    superpose up to the image geometry and friction; antagonist pairs cancel, so their relative error
    measures the cancellation, not the plant."""
    per = len(shifts) // spans
    unit = shifts / np.maximum(np.linalg.norm(shifts, axis=1, keepdims=True), 1e-12)
    return [(s * per + a, s * per + b) for s in range(spans) for a in range(per) for b in range(a + 1, per)
            if unit[s * per + a] @ unit[s * per + b] > cos_threshold]


def hysteresis_residual(make_plant, muscle: int, settle_s: float = 1.0) -> float:
    """Image offset [px] left after switching one muscle on and off again (structural hysteresis, (4.44))."""
    plant = make_plant()
    start = plant.snapshot()["target_px"]
    valve = np.zeros(plant.model.m)
    valve[muscle] = 1.0
    settle(plant, valve, settle_s)
    return float(np.linalg.norm(settle(plant, np.zeros_like(valve), settle_s) - start))


# ------------------------------------------------------------------------------------------- the rule

def cosines(v: np.ndarray, shifts: np.ndarray) -> np.ndarray:
    """cos∠(v, v_i) for every muscle (0 for a zero shift)."""
    norms = np.linalg.norm(shifts, axis=1) * np.linalg.norm(v)
    return np.divide(shifts @ v, norms, out=np.zeros(len(shifts)), where=norms > 0)


def switch(v: np.ndarray, shifts: np.ndarray, on: np.ndarray, free: np.ndarray,
           cos_threshold: float = COS_THRESHOLD, dead_zone_px: float = 10.0,
           off_first: bool = True) -> tuple[int, bool] | None:
    """One decision of the §4.8.3 rule: ``(muscle, turn_on)`` or None (dead zone / nothing to do).

    ``on`` is the current on/off state, ``free`` marks the muscles the rule may switch (forced-on
    muscles are not free). Same-direction: cos > threshold (strict; the text only gives the value).
    Ties go to the lowest index. ``off_first=False`` is the ablation that switches on before off.
    """
    if np.linalg.norm(v) <= dead_zone_px:
        return None
    cos = cosines(v, shifts)
    same = cos > cos_threshold
    to_off = np.flatnonzero(free & on & ~same)
    to_on = np.flatnonzero(free & ~on & same)
    turn_off = (int(to_off[np.argmin(cos[to_off])]), False) if len(to_off) else None  # largest angle
    turn_on = (int(to_on[np.argmax(cos[to_on])]), True) if len(to_on) else None  # smallest angle
    first, second = (turn_off, turn_on) if off_first else (turn_on, turn_off)
    return first if first is not None else second


class TrackingRule(Module):
    """The per-image-cycle on/off rule of §4.8.3 as a runtime module (one switch per 66-ms cycle).

    Contributes ``{"valve": state}``; forced-on muscles (§4.8.4, Fig. 4.56) are on whenever
    ``forced(t)`` lists them and are never switched by the rule. Logs the switch history.
    """

    period = CYCLE_S

    def __init__(self, shifts: np.ndarray, cos_threshold: float = COS_THRESHOLD, dead_zone_px: float = 10.0,
                 forced=None, off_first: bool = True, name: str = "rule"):
        super().__init__(name)
        self.shifts = np.asarray(shifts, dtype=float)
        self.cos_threshold = cos_threshold
        self.dead_zone_px = dead_zone_px
        self.forced = forced if forced is not None else (lambda t: ())
        self.off_first = off_first
        self.on = np.zeros(len(self.shifts), dtype=bool)
        self.switches: list[tuple[float, int, bool]] = []

    def reset(self, snapshot) -> None:
        self.on = np.asarray(snapshot["valve"]) > 0.5

    def update(self, snapshot) -> dict:
        t = float(snapshot["t"])
        forced = np.zeros(len(self.on), dtype=bool)
        forced[list(self.forced(t))] = True
        self.on |= forced
        v = np.asarray(snapshot["target_px"])
        decision = switch(v, self.shifts, self.on, ~forced, self.cos_threshold, self.dead_zone_px, self.off_first)
        if decision is not None:
            muscle, turn_on = decision
            self.on[muscle] = turn_on
            self.switches.append((t, muscle, turn_on))
        self.log(t, **{f"{self.name}.target_px": v, f"{self.name}.on_count": self.on.sum(),
                       f"{self.name}.in_dead_zone": float(np.linalg.norm(v) <= self.dead_zone_px)})
        return {"valve": self.on.astype(float)}


def same_direction_bound(shifts: np.ndarray, cos_threshold: float = COS_THRESHOLD, samples: int = 7200) -> int:
    """max over directions v of the number of same-direction muscles.

    With off-before-on, a muscle is switched on only when no inverse-direction muscle is on, so every
    free on-muscle is same-direction for that v: this bounds the free on-count (derived).
    """
    angles = np.linspace(0.0, 2 * np.pi, samples, endpoint=False)
    dirs = np.column_stack((np.cos(angles), np.sin(angles)))
    unit = shifts / np.linalg.norm(shifts, axis=1, keepdims=True)
    return int(((dirs @ unit.T) > cos_threshold).sum(axis=1).max())


@dataclass
class Episode:
    """One tracking run: per-cycle image error, on-count and dead-zone flag, plus switch events."""

    t: np.ndarray
    target_px: np.ndarray
    on_count: np.ndarray
    in_dead_zone: np.ndarray
    switches: list = field(default_factory=list)


def track(plant: BeBePlant, shifts: np.ndarray, duration_s: float, dead_zone_px: float = 10.0,
          cos_threshold: float = COS_THRESHOLD, forced=None, push=None, off_first: bool = True,
          recorder: Recorder | None = None, name: str = "rule", progress=None) -> Episode:
    """Run the rule on ``plant`` in the shared Loop for ``duration_s``; ``push(t)`` gives the force [N]."""
    recorder = recorder if recorder is not None else Recorder()
    rule = TrackingRule(shifts, cos_threshold, dead_zone_px, forced, off_first, name=name)
    modules: list[Module] = [rule]
    if push is not None:
        modules.append(FunctionModule(lambda snap: {"push": push(snap["t"])}, name=f"{name}.push"))
    Loop(plant, modules, recorder).run(duration_s, progress=progress)
    get = lambda key: recorder.values(f"{name}.{key}")  # noqa: E731
    return Episode(recorder.times(f"{name}.target_px"), get("target_px"), get("on_count").astype(int),
                   get("in_dead_zone").astype(bool), rule.switches)


def recovery_times(episode: Episode, events) -> np.ndarray:
    """Per event time: seconds until the target is back in the dead zone after leaving it.

    0 if it never left before the next event; inf if it never came back before the next event
    (or the end of the run).
    """
    ends = list(events[1:]) + [np.inf]
    out = []
    for start, end in zip(events, ends):
        window = (episode.t >= start) & (episode.t < end)
        idx = np.flatnonzero(window)
        outside = np.flatnonzero(~episode.in_dead_zone[idx])
        if len(outside) == 0:
            out.append(0.0)
            continue
        back = np.flatnonzero(episode.in_dead_zone[idx[outside[0]:]])
        out.append(float(episode.t[idx[outside[0]] + back[0]] - start) if len(back) else np.inf)
    return np.array(out)


def reversals(switches) -> int:
    """How often a switch is undone by the very next one (same muscle): the two-posture oscillation
    around the centre that the thesis observed (§4.8.4)."""
    return sum(1 for a, b in zip(switches, switches[1:]) if a[1] == b[1] and a[2] != b[2])
