"""Tricycle laws of seed 000 ch. 3: active (Eqs. 3.6–3.9), passive (3.13–3.18), switching (3.19),
operation loop (Fig. 3.16, Eq. 3.20) — spec 000-part1 §5.4 checks 1–6, 10, 12, 14."""

import numpy as np
import pytest
from blas import sums_left_to_right
from scipy.integrate import solve_ivp

from shintai.core.runtime import Body, Loop, declare
from shintai.core.search_index import StabilityMonitor, estimate_sign_matrix, offline_index
from shintai.humanoid.constants import (
    CONTROL_PERIOD,
    D_THETA_C,
    D_THETA_H,
    DEG,
    DELTA_C,
    DELTA_T,
    IMPEDANCE,
    T_2PI,
    THETA_C_INIT,
    THETA_H_MAX,
    TRICYCLE,
)
from shintai.humanoid.tricycle.active import (
    R_y,
    crank_angle_of_phase,
    grip_plan,
    in_active_region,
    pedal_offline_index,
    pedal_phase,
    pedal_point,
    pedal_trajectory,
    pedal_update,
    v,
)
from shintai.humanoid.tricycle.operation import LimbPair, OperationSchedule, role_switcher, travel_distance
from shintai.humanoid.tricycle.passive import PASSIVE_SGN, ActiveImpedance, PassiveFunction
from shintai.humanoid.tricycle.switching import (
    SwitchingDiagnostic,
    active_arm,
    active_leg,
    estimate_crank_angle,
    estimate_handle_angle,
    fit_angle,
    switching_angles,
)
from shintai.humanoid.tricycle.vehicle import crank_centre as tricycle_crank_centre
from shintai.humanoid.tricycle.vehicle import grip_position, pedal_position, steer_axis, steer_point

PASSIVE_LEG = IMPEDANCE["passive_leg"]
F_TRG = np.array(PASSIVE_LEG.f_trg)
R = TRICYCLE.crank_radius
CENTRE = tricycle_crank_centre()


def model_pedal_y(leg):
    return (1.0 if leg == "left" else -1.0) * TRICYCLE.pedal_width / 2


def passive(xi0=np.zeros(3), dt=CONTROL_PERIOD, reachable=None):
    g = PASSIVE_LEG
    return PassiveFunction(xi0, g.m, g.d, g.k, g.f_trg, dt, reachable)


def corner_force(xi, walls=np.array([0.1, 0.1, 0.0]), k_wall=2e4):
    """A stiff corner: the walls push back on penetration x > w_x, y > w_y and the floor z < w_z
    (f_z > 0: pressing down on a pedal gives a positive vertical reaction, Table 3.4)."""
    pen = np.maximum(np.asarray(xi) * [1, 1, -1] - walls * [1, 1, -1], 0.0)
    return -k_wall * pen * [1, 1, -1]


def settle_on_wall(law, seconds, acquire_every=None):
    """Run the passive limb against the corner tick by tick; return the force after each tick."""
    n = int(round(seconds / CONTROL_PERIOD))
    forces = []
    f = corner_force(law.xi)
    for k in range(n):
        acquire = acquire_every is not None and k % acquire_every == acquire_every - 1
        law.step(f, acquire)
        f = corner_force(law.xi)
        forces.append(f)
    return np.array(forces)


# --- active function ------------------------------------------------------------------------------


def test_pedal_trajectory_on_its_circle_in_the_active_region():
    """Eq. 3.7: p_i on the circle of radius r about p_0 − r v(δ_c), from δ_c past TDC to δ_c past BDC,
    inside the active region (Eq. 3.6) throughout; Eq. 3.9 rebuilds it step by step."""
    T = 18
    p0 = pedal_point(CENTRE, R, DELTA_C)
    plan = pedal_trajectory(p0, R, DELTA_C, T)
    centre = p0 - R * v(DELTA_C)
    assert np.allclose(centre, CENTRE)
    assert np.allclose(np.linalg.norm(plan - centre, axis=1), R)
    assert np.allclose(plan[-1], pedal_point(CENTRE, R, DELTA_C + np.pi))  # δ_c past BDC
    assert all(in_active_region(p, centre, DELTA_C) for p in plan)
    for i in range(T):  # the pedal angle grows by π/T per sample
        assert np.allclose(plan[i + 1], pedal_point(CENTRE, R, DELTA_C + np.pi * (i + 1) / T))
    p = p0
    for i in range(T):
        p = pedal_update(p, i, R, DELTA_C, T)
        assert np.allclose(p, plan[i + 1])
    assert np.allclose(offline_index(plan), [pedal_offline_index(i, R, DELTA_C, T) for i in range(T)])


def test_active_region_is_delta_c_to_delta_c_plus_pi():
    for phi_deg in range(0, 360, 5):
        inside = in_active_region(pedal_point(CENTRE, R, phi_deg * DEG), CENTRE, DELTA_C, tol=1e-9)
        assert inside == (20 <= phi_deg <= 200), phi_deg


def test_R_y_turns_the_pedal_forward():
    assert np.allclose(R_y(np.pi / 2) @ [0, 0, 1], [1, 0, 0])  # TDC → front


def test_grip_plan_turns_the_grips_about_the_steering_axis():
    """The arms' X_active^ref: grips 0.48 m apart (±0.24 m), at a fixed height along the raked axis,
    turned by θ_h and held within Θ_H = 25° (Eq. 3.2)."""
    axis_point, axis_dir = steer_point(), steer_axis()
    g0 = {arm: grip_plan(0.0, arm) for arm in ("left", "right")}
    g = {arm: grip_plan(THETA_H_MAX, arm) for arm in ("left", "right")}
    assert np.linalg.norm(g["left"] - g["right"]) == pytest.approx(0.48)
    for arm in g:
        assert (g[arm] - axis_point) @ axis_dir == pytest.approx((g0[arm] - axis_point) @ axis_dir)
    assert g["left"][0] < g0["left"][0] and g["right"][0] > g0["right"][0]  # θ_h > 0 turns left
    assert np.allclose(grip_plan(40 * DEG, "left"), g["left"])  # clamped to Θ_H


def test_pedal_point_matches_the_tricycle_model():
    """One crank convention across the package: Eq. 3.8's pedal angle φ_leg = θ_c ± π/2 puts the
    pedal where the tricycle model has it."""
    centre = tricycle_crank_centre()
    for theta in np.linspace(0, 2 * np.pi, 13):
        for leg in ("left", "right"):
            model = pedal_position(theta, leg[0]) - [0.0, model_pedal_y(leg), TRICYCLE.pedal_size[2] / 2]
            assert np.allclose(pedal_point(centre, R, pedal_phase(theta, leg)), model)


# --- passive function ----------------------------------------------------------------------------


def test_sign_matrix_of_the_passive_law_is_minus_identity_by_probing_a_wall():
    """§5.4 check 2: the settled reaction of the impedance-controlled limb against a stiff corner,
    probed along each axis, gives sgn[ξ^ref, f^msr] = −E (Eq. 3.17) — the sgn the law uses."""

    def plant(xi_ref):
        return settle_on_wall(passive(xi_ref), 3.0)[-1]

    inside = np.array([0.1, 0.1, 0.0]) + [0.004, 0.004, -0.004]
    sgn = estimate_sign_matrix(plant, [inside, inside + [0.002, 0.001, -0.002]], step=1e-3, tol=1e-3)
    assert np.array_equal(sgn, PASSIVE_SGN)


def test_reference_reset_equals_the_filtered_update_with_the_ode():
    """§5.4 check 3: Eq. 3.14 with ξ(t) from integrating Eq. 3.13 (solve_ivp, force held over each
    tick) gives the same references as the engine's Eq. 3.18 inside PassiveFunction."""
    dt = 0.02
    rng = np.random.default_rng(0)
    forces = F_TRG + rng.normal(0, 30, (60, 3))
    law = passive(dt=dt)
    g = PASSIVE_LEG
    ref, state = np.zeros(3), np.zeros(6)  # state: displacement e = ξ − ξ^ref and its rate, per axis
    for f in forces:
        u = f - F_TRG

        def ode(_, y, u=u):
            e, de = y[:3], y[3:]
            return np.concatenate([de, (u - g.d * de - g.k * e) / g.m])

        state = solve_ivp(ode, (0, dt), state, rtol=1e-11, atol=1e-13).y[:, -1]
        xi = ref + state[:3]  # Eq. 3.15
        ref = xi  # Eq. 3.14, first branch
        law.step(f, acquire=True)
        assert np.allclose(law.xi_ref, ref, atol=1e-9)


def test_one_acquisition_moves_the_reference_by_the_static_compliance():
    """§5.4 check 10 [DERIVED]: after the impedance settles, one acquisition moves ξ^ref by
    (f − f^trg)/K_v — 3.33 mm per newton for the passive K_v = 300 N/m."""
    law = passive()
    f = F_TRG + [0.0, 0.0, 10.0]
    for _ in range(int(30 / CONTROL_PERIOD)):
        law.step(f, acquire=False)
    law.step(f, acquire=True)
    assert law.xi_ref == pytest.approx([0.0, 0.0, 10.0 / PASSIVE_LEG.k], abs=1e-6)


def test_per_phase_acquisition_drives_the_force_to_target_monotonically():
    """Eq. 2.22 along a run: acquiring once per Δt = 0.8 s, the force error against a stiff wall
    shrinks at every phase and ends below 0.1 N; acquiring every 4 ms tick oscillates with a growing
    amplitude (the Routh condition D h (K + k_e) > M k_e of the passive module docstring fails)."""
    start = np.array([0.1, 0.1, 0.0]) + [0.003, -0.002, -0.004]
    every = int(round(DELTA_T / CONTROL_PERIOD))
    forces = settle_on_wall(passive(start), 20 * DELTA_T, acquire_every=every)
    at_phase_end = forces[every - 1::every]
    errors = np.abs(at_phase_end - F_TRG * [0, 0, 1])
    monitor = StabilityMonitor(tol=1e-3)
    for e in errors[:, [0, 2]]:  # y is off the wall: no contact, no error to speak of
        monitor.observe(error=e)
    assert monitor.error_increases == 0
    assert errors[-1, [0, 2]].max() < 0.1 and abs(at_phase_end[-1, 1]) < 1e-9
    per_tick = passive(start)
    settle_on_wall(per_tick, 1.0, acquire_every=1)
    assert per_tick.xi[2] > 1.0  # the oscillation grows until the foot is thrown off the floor


def test_unreachable_displacement_holds_the_reference():
    """§5.4 check 14, Eq. 3.14 second branch: ξ(t) outside the reachable set keeps ξ^ref."""
    law = passive(reachable=lambda xi: xi[2] < 0.01)
    f = F_TRG + [0.0, 0.0, 30.0]  # pushed up: 30 N / 300 N/m = 0.1 m if it could go
    held_at = None
    for k in range(int(20 / CONTROL_PERIOD)):
        law.step(f, acquire=(k % 200 == 199))
        if law.unreachable_holds and held_at is None:
            held_at = law.xi_ref.copy()
    assert held_at is not None and held_at[2] < 0.01
    assert np.allclose(law.xi_ref, held_at) and law.xi[2] >= 0.01


def test_active_impedance_is_stiff_and_offsets_by_the_force_error():
    g = IMPEDANCE["active_leg"]
    law = ActiveImpedance(g.m, g.d, g.k, g.f_trg, CONTROL_PERIOD)
    for _ in range(int(5 / CONTROL_PERIOD)):
        xi = law.step([0.0, 0.0, 0.0], F_TRG + [0.0, 0.0, 30.0])
    assert xi == pytest.approx([0.0, 0.0, 30.0 / g.k], abs=1e-6)  # 1 cm for 30 N at 3000 N/m


# --- switching -----------------------------------------------------------------------------------


def test_switching_angles_and_role_tables():
    """§5.4 check 6: crank switching angles 110° and 290° (Eq. 3.19, δ_c = 20°), the leg role table
    changes exactly there, and the active leg's pedal is in its active region (Eq. 3.6)."""
    assert np.allclose(switching_angles(THETA_C_INIT, 0, 2 * np.pi) / DEG, [110, 290])
    assert np.allclose(switching_angles(0.0, -THETA_H_MAX, THETA_H_MAX + 1e-9), [0.0])
    for deg in np.arange(0, 360, 0.5):
        leg = active_leg(deg * DEG, DELTA_C)
        assert leg == ("right" if 110 <= deg < 290 else "left"), deg
        phi = pedal_phase(deg * DEG, leg)
        assert in_active_region(pedal_point(CENTRE, R, phi), CENTRE, DELTA_C, tol=1e-9)
        assert crank_angle_of_phase(phi, leg) == pytest.approx(deg * DEG)
    assert active_arm(-5 * DEG, heading=1.0) == "left" and active_arm(5 * DEG, heading=-1.0) == "right"
    assert active_arm(0.0, heading=-D_THETA_H) == "left" and active_arm(0.0, heading=D_THETA_H) == "right"


@pytest.mark.parametrize("theta_deg", [0.0, 37.0, 110.0, 200.5, 289.9, 359.0])
def test_crank_angle_from_foot_points(theta_deg):
    """Method (a): the crank angle fitted to noisy foot points (1 mm) and to one foot alone."""
    rng = np.random.default_rng(int(theta_deg * 10))
    theta = theta_deg * DEG
    feet = {leg: pedal_point(CENTRE, R, pedal_phase(theta, leg)) + rng.normal(0, 0.001, 3)
            for leg in ("left", "right")}
    est = estimate_crank_angle(feet, CENTRE)
    assert abs(np.angle(np.exp(1j * (est - theta)))) < 1.0 * DEG
    one = estimate_crank_angle({"right": feet["right"] + [0, 0.05, 0]}, CENTRE)  # off-plane: ignored
    assert abs(np.angle(np.exp(1j * (one - theta)))) < 1.0 * DEG


def test_handle_angle_from_hand_points_on_the_raked_axis():
    for theta in np.linspace(-THETA_H_MAX, THETA_H_MAX, 7):
        hands = {arm: grip_plan(theta, arm) for arm in ("left", "right")}
        assert estimate_handle_angle(hands) == pytest.approx(theta, abs=1e-12)
        assert estimate_handle_angle({"right": hands["right"]}) == pytest.approx(theta, abs=1e-12)
    with pytest.raises(ValueError, match="undefined"):
        fit_angle([steer_point()], [[1.0, 0, 0]], steer_point(), steer_axis())


def test_method_a_fit_and_role_table_are_their_numpy_formulas_bit_for_bit():
    """fit_angle (every step on Python floats, the dot products summed left to right) gives atan2(Σ a·(z × w), Σ z·w)
    exactly as the NumPy expressions do (BLAS ddot, np.cross) where the BLAS sums left to right (tests/blas.py), to
    rounding elsewhere; active_leg's modulo is np.mod's (the estimates feed the role switches and the hands' IK
    targets)."""
    exact = sums_left_to_right()
    rng = np.random.default_rng(7)
    for _ in range(5000):
        axis = rng.normal(size=3)
        a = axis / np.linalg.norm(axis)
        centre, points, zeros = rng.normal(size=3), rng.normal(size=(2, 3)), rng.normal(size=(2, 3))
        zs = [z - a * (a @ z) for z in zeros]
        num = den = 0.0
        for p, z in zip(points, zs):
            w = p - centre
            w = w - a * float(a @ w)
            num += float(a @ np.cross(z, w))
            den += float(z @ w)
        got, want = fit_angle(list(points), list(zeros), centre, axis), float(np.arctan2(num, den))
        assert got == want if exact else abs(got - want) < 1e-12
    for theta in np.concatenate([rng.uniform(-20, 20, 2000), np.arange(-8, 9) * np.pi / 2 + DELTA_C]):
        phase = np.mod(theta, 2 * np.pi)
        expected = "right" if np.pi / 2 + DELTA_C <= phase < 3 * np.pi / 2 + DELTA_C else "left"
        assert active_leg(float(theta), DELTA_C) == expected


# --- operation loop ------------------------------------------------------------------------------


def test_revolution_time_and_travel_from_the_schedule():
    """§5.4 checks 5 and 12: 36 crank samples of 2Δt make T_2π = 57.6 s (Eq. 3.20); one revolution
    rolls D_c = 2.45 m (App. A.1.1)."""
    sched = OperationSchedule(0.0, 0.0, [(0.0, 2 * np.pi)], DELTA_T, D_THETA_H, D_THETA_C)
    assert len(sched.samples) == 36
    assert sched.duration == pytest.approx(57.6) == pytest.approx(T_2PI)  # 36 · 2 · 0.8 s = 2π · 2Δt / Δθ_c
    advance = sched.samples[-1].theta_c - sched.theta_c0
    assert travel_distance(advance, TRICYCLE.travel_per_rev) == pytest.approx(2.45)
    assert sched.at(0.0) == (0, "active") and sched.at(0.81) == (0, "passive") and sched.at(57.6) is None


def test_simultaneous_mode_removes_the_stationary_steering():
    """E3 slalom (θ_h = −25° over the first half turn, +25° over the second): sequential mode
    steers while stopped (5 + 18 + 10 + 18 samples); E7's simultaneous mode steers while pedalling
    (18 + 18) and waits 80 % as long."""
    goals = [(-THETA_H_MAX, np.pi), (THETA_H_MAX, 2 * np.pi)]
    seq = OperationSchedule(0.0, 0.0, goals, DELTA_T, D_THETA_H, D_THETA_C)
    sim = OperationSchedule(0.0, 0.0, goals, DELTA_T, D_THETA_H, D_THETA_C, simultaneous=True, wait_fraction=0.8)
    assert len(seq.samples) == 51 and len(sim.samples) == 36
    assert seq.samples[4].moves == {"handle"} and seq.samples[5].moves == {"crank"}
    assert sim.samples[0].moves == {"handle", "crank"} and sim.duration == pytest.approx(36 * 2 * 0.64)
    assert max(abs(s.theta_h) for s in seq.samples) == pytest.approx(THETA_H_MAX)


class QuasiStatic(Body):
    """A massless device between two position-commanded limbs (the quasi-static backend of spec
    §5.2): each limb is tied to its contact point ``points_of(θ)[side]`` by a stiff spring, the
    device takes the angle that minimises their energy (the least-squares ``fit(points)``), and
    f^msr is the spring force on the limb."""

    def __init__(self, theta, points_of, fit, k_contact=2e4, dt=CONTROL_PERIOD):
        self.dt, self.t, self.k = dt, 0.0, k_contact
        self.theta, self.points_of, self.fit = theta, points_of, fit
        self.limbs = {side: p.copy() for side, p in points_of(theta).items()}
        self.channels = declare(*self.limbs)

    def snapshot(self):
        snap = {"t": self.t, "theta": self.theta}
        for side, p in self.points_of(self.theta).items():
            snap[f"{side}_point"] = self.limbs[side].copy()
            snap[f"{side}_force"] = self.k * (p - self.limbs[side])
        return snap

    def apply(self, command):
        for side, xi in command.items():
            self.limbs[side] = np.asarray(xi, dtype=float)

    def step(self):
        self.theta = self.fit(self.limbs)
        self.t += self.dt


def crank_points(theta_c, centre=CENTRE):
    return {leg: pedal_point(centre, R, pedal_phase(theta_c, leg)) for leg in ("left", "right")}


def crank_body():
    return QuasiStatic(0.0, crank_points, lambda feet: estimate_crank_angle(feet, CENTRE))


class PointFoot:
    def __init__(self, leg):
        self.name = leg

    def point(self, snap):
        return snap[f"{self.name}_point"]

    def force(self, snap):
        return snap[f"{self.name}_force"]

    def command(self, xi, snap):
        return {self.name: xi}


def crank_plan(leg, centre=CENTRE):
    return lambda theta_c: pedal_point(centre, R, pedal_phase(theta_c, leg)) - [0.0, 0.0, 0.005]


def test_role_switcher_pedals_one_revolution_on_the_quasi_static_crank():
    """Fig. 3.16 + Fig. 3.14 as modules: one revolution in T_2π = 57.6 s, the legs swap exactly
    twice, at measured crank angles of 110° and 290° (§5.4 check 6), and the passive leg holds the
    150 N target within 5 % at the end of its passive phases (§5.4 check 8, first item)."""
    sched = OperationSchedule(0.0, 0.0, [(0.0, 2 * np.pi)], DELTA_T, D_THETA_H, D_THETA_C)
    body = crank_body()
    feet = {leg: PointFoot(leg) for leg in ("left", "right")}
    diag = SwitchingDiagnostic(lambda s: estimate_crank_angle({k: s[f"{k}_point"] for k in feet}, CENTRE),
                               lambda a: active_leg(a, DELTA_C), hysteresis=0.5 * DEG)
    gains = {"active": IMPEDANCE["active_leg"], "passive": IMPEDANCE["passive_leg"]}
    legs = role_switcher("legs", "crank", feet, {leg: crank_plan(leg) for leg in feet}, diag,
                         active_leg(0.0, DELTA_C), sched, gains, CONTROL_PERIOD)
    loop = Loop(body, [legs])
    passive_end_force = []
    for sample in sched.samples:
        loop.run(2 * sched.phase)
        passive_side = "left" if legs.active == "legs:right-active" else "right"
        passive_end_force.append(body.snapshot()[f"{passive_side}_force"][2])
    assert body.t == pytest.approx(57.6)
    assert abs(np.angle(np.exp(1j * body.theta))) < 2 * DEG  # back at 0 after one revolution
    assert [name for _, _, name in legs.transitions_log] == ["legs:right-active", "legs:left-active"]
    swap_angles = np.mod([a for _, a, _ in diag.log], 2 * np.pi) / DEG
    assert swap_angles == pytest.approx([110.5, 290.5], abs=0.2)
    assert np.abs(np.array(passive_end_force) - 150.0).max() < 7.5


def test_only_active_legs_fight_over_a_mismodelled_crank():
    """§5.4 check 8, second item: with the crank centre mis-modelled by 1 cm, two active legs
    build a larger force error than the passive leg of the active/passive pair."""
    sched = OperationSchedule(0.0, 0.0, [(0.0, np.pi / 2)], DELTA_T, D_THETA_H, D_THETA_C)
    wrong = CENTRE + [0.01, 0.0, 0.0]
    gains = {"active": IMPEDANCE["active_leg"], "passive": IMPEDANCE["passive_leg"]}
    feet = {leg: PointFoot(leg) for leg in ("left", "right")}
    errors = {}
    for label, roles in (("both", {"left": "active", "right": "active"}), ("pair", {"left": "active", "right": "passive"})):
        body = crank_body()
        pair = LimbPair(label, "crank", feet, roles, {leg: crank_plan(leg, wrong) for leg in feet}, sched, gains,
                        CONTROL_PERIOD)
        loop = Loop(body, [pair])
        fz = []
        for _ in sched.samples:
            loop.run(2 * sched.phase)
            fz.append(body.snapshot()["right_force"][2])
        errors[label] = np.sqrt(np.mean((np.array(fz) - 150.0) ** 2))
    assert errors["both"] > 3 * errors["pair"]


def handle_body(axis_error=np.zeros(3)):
    """Grips on a handle whose true steering axis passes ``axis_error`` away from the nominal one,
    the grips starting at their nominal places (the handle-model error of E1)."""
    a, pivot = steer_axis(), steer_point() + axis_error
    grips0 = {arm: grip_position(0.0, arm[0]) for arm in ("left", "right")}

    def grips(theta_h):
        c, s = np.cos(theta_h), np.sin(theta_h)
        return {arm: pivot + (w := g - pivot) * c + np.cross(a, w) * s + a * (a @ w) * (1 - c)
                for arm, g in grips0.items()}

    return QuasiStatic(0.0, grips, lambda hands: fit_angle(list(hands.values()),
                                                           [grips0[k] - pivot for k in hands], pivot, a))


def test_role_switcher_steers_from_minus_to_plus_theta_h_max():
    """E1 on the quasi-static handle: −25° → +25°, the left arm active on the negative side and the
    right arm after the measured handle passes θ_h^init = 0 (Eq. 3.19, §5.4 check 6); the handle
    reaches both limits (§5.4 check 7) and the passive arm ends each passive phase near f^trg = 0."""
    sched = OperationSchedule(0.0, 0.0, [(-THETA_H_MAX, 0.0), (THETA_H_MAX, 0.0)], DELTA_T, D_THETA_H, D_THETA_C)
    body = handle_body()
    hands = {arm: PointFoot(arm) for arm in ("left", "right")}
    diag = SwitchingDiagnostic(lambda s: estimate_handle_angle({k: s[f"{k}_point"] for k in hands}),
                               active_arm, hysteresis=0.5 * DEG)
    gains = {"active": IMPEDANCE["active_arm"], "passive": IMPEDANCE["passive_arm"]}
    arms = role_switcher("arms", "handle", hands, {arm: (lambda th, a=arm: grip_plan(th, a)) for arm in hands}, diag,
                         active_arm(0.0, heading=-1.0), sched, gains, CONTROL_PERIOD)
    loop = Loop(body, [arms])
    theta, passive_force = [], []
    for _ in sched.samples:
        loop.run(2 * sched.phase)
        theta.append(body.theta)
        passive_arm = "left" if arms.active == "arms:right-active" else "right"
        passive_force.append(np.linalg.norm(body.snapshot()[f"{passive_arm}_force"]))
    assert len(sched.samples) == 15
    assert min(theta) == pytest.approx(-THETA_H_MAX, abs=0.5 * DEG) and theta[-1] == pytest.approx(THETA_H_MAX, abs=0.5 * DEG)
    assert [name for _, _, name in arms.transitions_log] == ["arms:right-active"]
    assert diag.log[0][1] == pytest.approx(0.5 * DEG, abs=0.1 * DEG)
    assert max(passive_force) < 2.0


def test_active_passive_arms_keep_the_internal_force_low_on_a_mismodelled_handle():
    """§5.4 check 9 [PROPOSAL]: with the true steering axis 1 cm off the model, two active arms
    squeeze the handle; active + passive keeps the force between the hands near f^trg = 0."""
    sched = OperationSchedule(0.0, 0.0, [(-THETA_H_MAX, 0.0)], DELTA_T, D_THETA_H, D_THETA_C)
    gains = {"active": IMPEDANCE["active_arm"], "passive": IMPEDANCE["passive_arm"]}
    hands = {arm: PointFoot(arm) for arm in ("left", "right")}
    squeeze = {}
    for label, roles in (("both", {"left": "active", "right": "active"}), ("pair", {"left": "active", "right": "passive"})):
        body = handle_body(axis_error=np.array([0.01, 0.0, 0.0]))
        pair = LimbPair(label, "handle", hands, roles, {arm: (lambda th, a=arm: grip_plan(th, a)) for arm in hands},
                        sched, gains, CONTROL_PERIOD)
        loop = Loop(body, [pair])
        loop.run(sched.duration)
        squeeze[label] = np.linalg.norm(body.snapshot()["right_force"])
    assert squeeze["both"] > 4 * squeeze["pair"] and squeeze["pair"] < 2.0  # 8.9 N vs 1.4 N
