"""SLC (seed 000 §5.3–5.4.1, Eqs. 5.4–5.19, Tables 5.1–5.2)."""

import math

import numpy as np
import pytest

from shintai.core.runtime import Body, Loop, declare
from shintai.humanoid.balance.foot_damping import CHANNELS as DAMPING_CHANNELS
from shintai.humanoid.balance.foot_damping import FootDamping, FootDampingModule, damping_step
from shintai.humanoid.constants import DAMPING_D_FLAT, SLC_D0
from shintai.humanoid.learning.slc import (F_THRE, SLC, LandingWindow, SLCParams, SLCSchedule, slc_cost,
    slc_gradient, slc_update)

DT = 0.004
Q, R, T = 0.1, 1.0e5, 1.5


def open_loop_cost(D, D0, e_rec, delta_rec, k):
    """J_τ(D) at step k under the thesis's virtual open loop (Fig. 5.3), from records taken with D0:
    δ(t; D) = C_τ(s; D) e_τ with the recorded e_τ held fixed (Eq. 5.7), and e_τ(t; D) = C_τ(s; D)⁻¹ δ with the
    recorded δ held fixed (Eq. 5.9) — both in the controller's own discrete form (Euler, Eq. 5.1)."""
    delta = 0.0
    for e in e_rec[: k + 1]:
        delta = damping_step(delta, e, D, T, DT)  # Eq. 5.1 run on the fixed e_τ record
    prev = delta_rec[k - 1]
    e_of_D = D * ((delta_rec[k] - prev) / DT + prev / T)  # Eq. 5.1 solved for e_τ
    return 0.5 * (Q * e_of_D**2 + R * delta**2)


def test_eq_5_13_equals_a_finite_difference_of_J_under_the_open_loop_assumptions():
    rng = np.random.default_rng(13)
    e_rec = np.cumsum(rng.normal(0, 0.3, 300))  # a wandering torque error (N·m)
    D0 = 22.0
    delta_rec, d = [], 0.0
    for e in e_rec:
        d = damping_step(d, e, D0, T, DT)
        delta_rec.append(d)
    for k in (50, 150, 299):
        h = 1e-4
        fd = (open_loop_cost(D0 + h, D0, e_rec, delta_rec, k) - open_loop_cost(D0 - h, D0, e_rec, delta_rec, k)) / (2 * h)
        assert slc_gradient(e_rec[k], delta_rec[k], D0, Q, R) == pytest.approx(fd, rel=1e-5)


def test_update_is_eq_5_17_by_hand_with_Q_prime_eta_Q_and_R_prime_eta_R():
    p = SLCParams()
    assert (p.Q_prime, p.R_prime) == pytest.approx((1e-3, 1e3))  # Eqs. 5.15–5.16 with Table 5.2
    slc = SLC(p)
    D1 = slc.update(e_tau=1.0, delta=0.01)
    assert D1 == pytest.approx(22.0 - 1e-3 * 1.0 / 22.0 + 1e3 * 1e-4 / 22.0, rel=1e-14)
    assert D1 == pytest.approx(slc_update(22.0, 1.0, 0.01, 1e-3, 1e3), rel=1e-14)
    assert D1 == pytest.approx(22.0 - 0.01 * slc_gradient(1.0, 0.01, 22.0))  # Eq. 5.14
    assert slc.J(1.0, 0.01) == pytest.approx(slc_cost(1.0, 0.01))  # Eq. 2.10 with W of Eq. 5.18 is Eq. 5.4


@pytest.mark.parametrize("e, delta, up", [(1.0, 0.01, True), (10.0, 1e-4, False), (0.0, 0.002, True),
                                          (3.0, 0.0, False)])
def test_D_rises_when_R_delta2_exceeds_Q_e2_and_falls_otherwise(e, delta, up):
    slc = SLC()
    assert (R * delta**2 > Q * e**2) == up
    D1 = slc.update(e, delta)
    assert (D1 > SLC_D0) == up and D1 != SLC_D0


def test_an_update_below_D_min_is_refused():
    slc = SLC(SLCParams(D0=2.0, D_min=1.0))
    assert slc.update(e_tau=100.0, delta=0.0) == 2.0  # 2 − 1e-3·1e4/2 = −3 < D_min: kept
    assert slc.index.held_steps == 1


@pytest.mark.parametrize("field, value", [("D0", -22.0), ("D0", 0.0), ("eta", 0.0), ("eta", 1.5), ("eta", math.nan),
                                          ("Q", math.nan), ("R", -1.0), ("D_min", 30.0),
                                          ("air_time", -0.1)])
def test_bad_parameters_raise_one_line_naming_the_field(field, value):
    with pytest.raises(ValueError, match=f"^{field} must") as info:
        SLCParams(**{field: value})
    assert "\n" not in str(info.value)


def run_schedule(fz_pairs, e_pitch=1.0):
    """SLC after the damping of each tick (its e_τ, δ), the damping taking D one tick later (Fig. 5.4's order)."""
    feet = {"L": FootDamping(dt=DT), "R": FootDamping(dt=DT)}
    sched = SLCSchedule()
    states = []
    for i, (fl, fr) in enumerate(fz_pairs):
        for foot in feet.values():
            foot.step([0.0, e_pitch], [0.0, 0.0])
        out = sched.update({"t": i * DT, "f_Lz": fl, "f_Rz": fr, "e_tau": np.concatenate([feet["L"].e_tau, feet["R"].e_tau]),
                            "damping_delta": np.concatenate([feet["L"].delta, feet["R"].delta])})
        feet["L"].D[:], feet["R"].D[:] = out["damping_gain"][:2], out["damping_gain"][2:]
        states.append(sched.state)
    return feet, sched, states


def test_slc_starts_at_the_left_landing_and_stops_at_the_right_landing():
    stand, lift, air = 280.0, 0.0, 30  # 30 ticks = 0.12 s in the air ≥ SLC_AIR_TIME
    phases = ([(stand, stand)] * 5  # Phase 1: both feet loaded on the floor — no start
              + [(lift, stand)] * air  # Phase 2: left foot swings
              + [(30.0, stand)] * 5  # Phase 3: left lands on the board (> 25 N): start; right still loaded
              + [(stand, lift)] * air  # Phase 4: right foot swings
              + [(stand, 30.0)] * 3)  # Phase 5: right lands: stop
    feet, sched, states = run_schedule(phases)
    start = 5 + air
    assert states[:start] == ["waiting"] * start
    assert states[start:start + 5 + air] == ["learning"] * (5 + air)
    assert states[start + 5 + air:] == ["done"] * 3
    assert sched.updates == 5 + air and sched.duration == pytest.approx((5 + air) * DT)
    learned = sched.slc.D
    assert learned != SLC_D0
    assert feet["L"].D[1] == learned and feet["R"].D[1] == learned  # right pitch takes the learned D
    assert feet["L"].D[0] == DAMPING_D_FLAT and feet["R"].D[0] == DAMPING_D_FLAT  # roll stays at 22.0


def test_a_foot_unloading_before_it_lifts_does_not_fire_the_guards():
    """The jitter of HRP2 boarding the V-BOARD (measured): f_Lz crosses 25 N up and down while the left foot
    unloads (25.2 → 24.8 → 25.3 → 24.7 N at t ≈ 1.2 s) and the right foot rattles 12 ↔ 54 N as it lifts; SLC
    starts only at the left foot's placement on the board and stops at the right foot's (§5.4.1)."""
    stand = 280.0
    unload_l = [150.0, 60.0, 25.2, 24.8, 25.3, 24.7, 10.0]  # t = 0.02 … : the rising edge 24.8 → 25.3 is no landing
    swing = [3.0, -7.0, 12.0, 19.0, -2.0] * 35  # 0.7 s in the air, inertial readings below F_thre
    land = [58.0, 200.0, 400.0]
    rattle_r = [54.8, 14.9, 72.6, 54.5, 12.7, 54.1, 12.0, 52.9, 10.5]  # the right foot lifting: 4–8 ms bounces
    fl = [stand] * 5 + unload_l + swing + land + [stand] * (len(rattle_r) + len(swing)) + [stand] * 3
    n_before_r = 5 + len(unload_l) + len(swing) + len(land)
    fr = [stand] * n_before_r + rattle_r + swing + [37.0, 120.0, 250.0]
    _, sched, _ = run_schedule(list(zip(fl, fr)))
    t_land_l = (5 + len(unload_l) + len(swing)) * DT
    t_land_r = (n_before_r + len(rattle_r) + len(swing)) * DT
    assert sched.t_start == pytest.approx(t_land_l) and sched.t_stop == pytest.approx(t_land_r)
    # without the airborne arming the unloading's rising edge (index 5 + 4) would have started it
    eager = LandingWindow(SLCParams(air_time=0.0))
    for i, (a, b) in enumerate(zip(fl, fr)):
        eager.step({"t": i * DT, "f_Lz": a, "f_Rz": b})
    assert eager.t_start == pytest.approx(9 * DT) and eager.t_stop < t_land_r


def test_no_landing_no_learning():
    _, sched, states = run_schedule([(F_THRE, 300.0)] * 3 + [(F_THRE, 0.0)] * 3)  # never rises above 25 N
    assert set(states) == {"waiting"} and sched.updates == 0


class TorqueBody(Body):
    """A toy: scripted ankle torques and sole forces; the left pitch torque lags its reference."""

    channels = declare("foot_damping")

    def __init__(self):
        self.dt, self.t, self.delta = DT, 0.0, np.zeros(4)

    def snapshot(self):
        f_l = 0.0 if self.t < 0.1 else 200.0
        f_r = 200.0 if self.t < 0.3 else (0.0 if self.t < 1.3 else 200.0)
        return {"t": self.t, "tau_d_L": np.array([0.0, 5.0]), "tau_L": np.array([0.0, 5.0 - 2.0]),
                "tau_d_R": np.zeros(2), "tau_R": np.zeros(2), "f_Lz": f_l, "f_Rz": f_r}

    def apply(self, command):
        self.delta = command["foot_damping"]

    def step(self):
        self.t = round(self.t + self.dt, 9)


def test_slc_after_the_damping_writes_d_its_one_writer_one_tick_later():
    """SLC a stage after the damping: D(t+Δt) from e_τ(t), δ(t), reaching the damping on ``damping_gain`` one
    tick later (Fig. 5.4 steps 1–3)."""
    sched = SLCSchedule()
    module = FootDampingModule()
    loop = Loop(TorqueBody(), stages=[[module], [sched]], channels=DAMPING_CHANNELS.values())
    loop.run(until=1.6)
    assert sched.t_start == pytest.approx(0.1) and sched.t_stop == pytest.approx(1.3)
    assert sched.duration == pytest.approx(1.2)
    assert sched.D[3] == sched.slc.D > SLC_D0  # δ grows under a steady error: R′δ² wins
    assert np.array_equal(module.feet["R"].D, sched.D[2:]) and np.array_equal(module.feet["L"].D, sched.D[:2])
    before = module.feet["L"].D.copy()
    sched.D[1] += 1.0  # what SLC writes now, the damping uses on the next tick, not this one
    loop.step()
    assert np.array_equal(module.feet["L"].D, before)
