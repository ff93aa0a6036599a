"""The operation algorithm of the tricycle experiments as runtime modules (seed 000 §3.5.1–3.5.4,
Fig. 3.16, Eq. 3.20; E7's simultaneous mode).

Fig. 3.16, per command sample:
  1. the target handle angle θ_h and crank angle θ_c go into the vehicle's kinematic model;
  2. the active limb moves to the inverse kinematics of the target (transition Δt);
  3. the passive limb moves following the real handle/crank (transition Δt) — Eq. 3.14's acquisition;
  4. θ_h ← θ_h ± Δθ_h, θ_c ← θ_c ± Δθ_c.

Steps 1 and 4 are an :class:`OperationSchedule` (the operator's goals, stepped by Δθ_h = 5°,
Δθ_c = 10°); steps 2 and 3 are :class:`LimbPair` modules, one per role configuration, which a
:func:`role_switcher` swaps by the switching diagnostic of Fig. 3.14. Every command sample costs
2Δt, so one crank revolution takes T_2π = 2π · 2Δt / Δθ_c = 57.6 s (Eq. 3.20).

In the first outdoor run (E6) steering and pedalling were separate samples (steering while stopped);
the improved run (E7) generated both in the same sample and waited 80 % as long for each motion
("simultaneous" mode, ``wait_fraction``; the thesis does not give the original wait, so the fraction
scales Δt here).

A robot plugs in through :class:`Limb`: its forward kinematics of the contact point, its measured
contact force and its inverse kinematics to command channels.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass
from typing import Protocol

import numpy as np

from shintai.core.interpolation import SequencePlayer
from shintai.core.runtime import Module, Switcher
from shintai.humanoid.tricycle.passive import ActiveImpedance, PassiveFunction
from shintai.humanoid.tricycle.switching import SwitchingDiagnostic

DEVICES = ("handle", "crank")
SIDES = ("left", "right")


def other(side: str) -> str:
    return "right" if side == "left" else "left"


@dataclass(frozen=True)
class Sample:
    """One command sample of Fig. 3.16: its active phase starts at ``t0``, its passive phase one
    phase (Δt · wait fraction) later; ``moves`` holds the devices whose target changed."""

    t0: float
    theta_h: float
    theta_c: float
    moves: frozenset


def step_toward(value: float, goal: float, step: float) -> float:
    """Fig. 3.16 step 4: θ ← θ ± Δθ toward the operator's goal (the last step may be shorter)."""
    return value + float(np.clip(goal - value, -step, step))


class OperationSchedule:
    """Fig. 3.16 steps 1 and 4 for a list of operator goals ``[(θ_h, θ_c), ...]`` (joystick targets).

    Each goal is reached in steps of at most Δθ_h, Δθ_c. Sequential mode (E1–E6): the handle steps
    first, then the crank, one device per sample. Simultaneous mode (E7): both in the same sample.
    A sample lasts 2 · Δt · ``wait_fraction`` (active phase, then passive phase).
    """

    def __init__(self, theta_h0: float, theta_c0: float, goals: Sequence[tuple[float, float]],
                 dt_transition: float, d_theta_h: float, d_theta_c: float,
                 simultaneous: bool = False, wait_fraction: float = 1.0):
        if dt_transition <= 0 or d_theta_h <= 0 or d_theta_c <= 0 or not 0 < wait_fraction <= 1:
            raise ValueError("schedule needs Δt > 0, Δθ_h > 0, Δθ_c > 0 and 0 < wait_fraction <= 1")
        self.phase = dt_transition * wait_fraction
        self.theta_h0, self.theta_c0 = theta_h0, theta_c0
        self.samples: list[Sample] = []
        h, c = theta_h0, theta_c0
        for goal_h, goal_c in goals:
            while not (np.isclose(h, goal_h) and np.isclose(c, goal_c)):
                move_h = not np.isclose(h, goal_h)
                move_c = not np.isclose(c, goal_c) and (simultaneous or not move_h)
                h = step_toward(h, goal_h, d_theta_h) if move_h else h
                c = step_toward(c, goal_c, d_theta_c) if move_c else c
                moves = frozenset(d for d, m in zip(DEVICES, (move_h, move_c)) if m)
                self.samples.append(Sample(len(self.samples) * 2 * self.phase, h, c, moves))

    @property
    def duration(self) -> float:
        return len(self.samples) * 2 * self.phase

    def at(self, t: float) -> tuple[int, str] | None:
        """(sample index, "active" or "passive") at time t, or None after the last sample."""
        k = math.floor(t / (2 * self.phase) + 1e-9)  # = int(np.floor(...)), without the NumPy scalar
        if k >= len(self.samples):
            return None
        return k, "active" if t - self.samples[k].t0 < self.phase - 1e-9 else "passive"

    def phase_end(self, t: float) -> float:
        k, phase = self.at(t)
        return self.samples[k].t0 + (self.phase if phase == "active" else 2 * self.phase)

    def target(self, k: int, device: str) -> float:
        return self.samples[k].theta_h if device == "handle" else self.samples[k].theta_c


def travel_distance(theta_c_advance: float, travel_per_revolution: float) -> float:
    """Distance the tricycle rolls for a crank advance (no slip, §3.5.1; D_c = 2.45 m/rev, App. A.1.1)."""
    return travel_per_revolution * theta_c_advance / (2 * np.pi)


class Limb(Protocol):
    """A robot limb as the laws see it (hand on a grip, foot on a pedal)."""

    name: str

    def point(self, snapshot) -> np.ndarray:
        """Forward kinematics of the contact point, world frame [m]."""

    def force(self, snapshot) -> np.ndarray:
        """f^msr: the environment's force on the end effector, world frame [N]."""

    def command(self, xi: np.ndarray, snapshot) -> dict:
        """Inverse kinematics: the command channels that put the contact point at ξ."""


class LimbPair(Module):
    """One role configuration of a limb pair on a device (Fig. 3.16 steps 2 and 3).

    ``roles`` gives each side "active" or "passive" (both "active" is the only-active comparison of
    E4); ``gains`` maps "active"/"passive" to a Table 3.4 column
    (:class:`~shintai.humanoid.constants.Impedance`). In a sample that moves ``device``: an active
    limb's reference goes by minimum jerk (the SequencePlayer) to ``plans[side](target)`` during
    the active phase, under the active impedance (Eq. 3.13); a passive limb runs the passive
    impedance every tick, acquires its reference once, at the start of the passive phase (Eq. 3.14),
    and moves to it by minimum jerk during that phase (Fig. 3.16 step 3, "transition Δt"), its
    impedance displacement added on top. Between samples both hold. ``dt`` is the control period
    the module runs at.
    """

    def __init__(self, name: str, device: str, limbs: dict, roles: dict, plans: dict,
                 schedule: OperationSchedule, gains: dict, dt: float, reachable: dict | None = None):
        super().__init__(name, dt)
        if device not in DEVICES:
            raise ValueError(f"device must be one of {DEVICES}, got {device!r}")
        self.device, self.limbs, self.roles, self.plans = device, limbs, roles, plans
        self.schedule, self.gains, self.dt = schedule, gains, dt
        self.reachable = reachable or {}
        self._keys = {side: (f"{limb.name}.x_ref", f"{limb.name}.xi") for side, limb in limbs.items()}

    def reset(self, snapshot) -> None:
        self._t = float(snapshot["t"])
        self._phase = None
        self.players, self.active_imp, self.passive_fn = {}, {}, {}
        for side, role in self.roles.items():
            g = self.gains[role]
            x0 = self.limbs[side].point(snapshot)
            self.players[side] = SequencePlayer(x0)
            if role == "active":
                self.active_imp[side] = ActiveImpedance(g.m, g.d, g.k, g.f_trg, self.dt)
            else:
                self.passive_fn[side] = PassiveFunction(x0, g.m, g.d, g.k, g.f_trg, self.dt,
                                                        self.reachable.get(side))

    def update(self, snapshot):
        t = float(snapshot["t"])
        now = self.schedule.at(t)
        starts = now is not None and now != self._phase and self.device in self.schedule.samples[now[0]].moves
        self._phase = now
        command, logged = {}, {}
        dt = t - self._t
        for side, role in self.roles.items():
            limb, player = self.limbs[side], self.players[side]
            f_msr = limb.force(snapshot)
            if role == "active":
                if starts and now[1] == "active":
                    self._move(player, self.plans[side](self.schedule.target(now[0], self.device)), t)
                x_ref = player.advance(dt)
                xi = self.active_imp[side].step(x_ref, f_msr)
            else:
                law = self.passive_fn[side]
                law.step(f_msr, acquire=starts and now[1] == "passive")
                if starts and now[1] == "passive":
                    self._move(player, law.xi_ref, t)
                x_ref = player.advance(dt)
                xi = x_ref + law.displacement
            k_ref, k_xi = self._keys[side]
            logged[k_ref], logged[k_xi] = x_ref, xi
            command.update(limb.command(xi, snapshot))
        if self.recorder is not None:  # = self.log(...): both limbs' signals in one record, the keys formed once
            self.recorder.record(t, **logged)
        self._t = t
        return command

    def _move(self, player: SequencePlayer, target, t: float) -> None:
        """A transition to ``target`` by the end of the current phase (Δt from its start)."""
        player.push(target, max(self.schedule.phase_end(t) - t, self.dt), clear=True)


def role_switcher(name: str, device: str, limbs: dict, plans: dict, diagnostic: SwitchingDiagnostic,
                  initial_active: str, schedule: OperationSchedule, gains: dict, dt: float,
                  reachable: dict | None = None) -> Switcher:
    """The active/passive switching of Fig. 3.14 for one limb pair as a :class:`Switcher`.

    Children ``"<name>:left-active"`` and ``"<name>:right-active"``; the diagnostic's guards move
    between them when the measured angle passes a switching angle (Eq. 3.19), and the new
    configuration starts from the limbs' current points (the new passive limb's reference is where
    it is, the new active limb goes to the plan from there).
    """
    pairs = [LimbPair(f"{name}:{side}-active", device, limbs, {side: "active", other(side): "passive"},
                      {side: plans[side]}, schedule, gains, dt, reachable) for side in SIDES]
    transitions = [(f"{name}:{side}-active", f"{name}:{other(side)}-active", diagnostic.guard_to(other(side)))
                   for side in SIDES]
    return Switcher(pairs, transitions, initial=f"{name}:{initial_active}-active", name=name, period=dt)
