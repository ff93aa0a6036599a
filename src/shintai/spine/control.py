"""Muscle control modes L, T, S, LL (seed 003 §4.6, eqs. 4.36–4.42, Table 4.6) and the
interference policy of §4.7, as a :class:`shintai.core.Module` running at ~1 ms.

Sign convention. The thesis's laws are self-consistent only if the duty o > 0 winds the wire in
and ``l`` is the encoder value, which grows as the pulley winds in ("l: muscle length (the motor
encoder value)", §4.6.1): then a muscle longer than its target (l < l_r) gets o > 0 in (4.37), a
tension above target gets o < 0 in (4.38), and the software spring pulls when stretched
(l < l_0 ⇒ T_r > 0 in 4.36). Read as the path length instead, L and T mode would need opposite
output signs. So here ``l`` is the encoder reading in metres of wire wound in since the encoder
zero: l = λ(θ_zero) − λ, with λ the muscle's path length (eq. 4.25). :func:`encoder_targets`
converts model lengths into it, and every equation is used exactly as printed:

    L  (4.37): o = −K_Pl (l − l_r) − K_Il ∫(l − l_r) dt − K_Dl dl/dt
    T  (4.38): o = −K_Pt (T − T_r) − K_Dt dT/dt   if |T − T_r| ≥ T_t, else 0
    S  (4.39): (4.38) with T_r = k_s (l_0 − l)                                  (4.36)
    LL (4.40): (4.37)  if T < T_l, else 0

S mode's spring (4.36) is in the firmware's units when the controller has a :class:`CountSpring`:
"T is the tension sensor's value" (4.38) and k_s is "the ratio of the tension sensor's AD count to
the motor encoder's pulse count" (§4.5.2), so T_r is an ADC count, linear in encoder pulses; read
through the sensor's saturating calibration (Fig. 3.34) it is a hardening spring in newtons.
Without one, k_s is in N/m and the spring is linear in newtons (the earlier law, kept for
comparison). T mode's fixed point T = T_r is the same in counts or newtons (the calibration is
monotone); only its gains, which the thesis does not give, would be rescaled, so it stays in N.

:func:`unified_duty` is eq. 4.41 (with 4.42) for checking; as the thesis advises (§4.6.5) the
controller runs one routine per mode, selected per muscle. Chosen where the thesis is silent:
the output saturates to [−1, 1] (spec §2.6); the length integral is clamped so that its term
alone cannot exceed full duty, is frozen while LL's tension limit holds the output at 0, and is
reset when a muscle enters L or LL; dl/dt and dT/dt are backward differences of the readings.
"""

from __future__ import annotations

from dataclasses import dataclass, field, replace
from enum import IntEnum

import numpy as np

from shintai.core.constants import KGF_N
from shintai.core.runtime import SET, Channel, Module, Snapshot
from shintai.spine.actuators import TensionSensor, pwm_duty


class Mode(IntEnum):
    """§4.6: L length, T tension, S software spring, LL length with tension limit."""

    L = 0
    T = 1
    S = 2
    LL = 3


_L, _T, _S, _LL = (int(m) for m in Mode)  # plain ints for the 1 ms loop (enum lookups are slow)


@dataclass(frozen=True)
class Gains:
    """Table 4.6's parameters (values per muscle or shared). Units: o is a duty in [−1, 1];
    l in m, T in N. The thesis prints no gain (spec §6.9): defaults are chosen for Cla's drive
    (Table 3.2) at a 1 ms period — L: 0.5 mm of error is full duty; T: the tension loop closes in
    ~10 ms through the 10 N/mm wire; dead band 0.05 kgf; LL limit 1 kgf ("small", §4.6.4);
    teaching tension 1 kgf (§4.2.1)."""

    K_Pl: float = 2000.0  # 1/m
    K_Il: float = 2.0e4  # 1/(m s)
    K_Dl: float = 3.0  # s/m
    K_Pt: float = 0.10  # 1/N
    K_Dt: float = 1.0e-3  # s/N
    T_t: float = 0.05 * KGF_N  # N, dead band
    T_l: float = 1.0 * KGF_N  # N, LL limit tension
    k_s: float = 1000.0  # N/m, software spring; ADC counts per encoder pulse with a CountSpring
    T_r: float = 1.0 * KGF_N  # N, T-mode target tension


def law_L(l, l_r, integral, dl, g: Gains) -> np.ndarray:
    """Eq. 4.37: PID on the encoder length, D on the measurement."""
    return -g.K_Pl * (l - l_r) - g.K_Il * integral - g.K_Dl * dl


def law_T(T, T_r, dT, g: Gains) -> np.ndarray:
    """Eq. 4.38: PD on the tension with a dead band ±T_t."""
    err = T - T_r
    return np.where(np.abs(err) >= g.T_t, -g.K_Pt * err - g.K_Dt * dT, 0.0)


def software_spring(l, l_0, k_s) -> np.ndarray:
    """Eq. 4.36: T_r = k_s (l_0 − l), the reference tension of the software spring."""
    return k_s * (l_0 - l)


@dataclass(frozen=True)
class CountSpring:
    """Eq. 4.36 as the thesis writes it (§4.5.2): T_r [ADC counts] = k_s (l_0 − l) [encoder
    pulses] / ``fixed_point``, k_s in counts per pulse (50 … 400 in Figs. 4.14–4.17).

    ``fixed_point`` is the firmware's scale of k_s, not in the text (with k_s = 100 read literally,
    one pulse = 17 µm of wire would ask 100 counts ≈ 3 N at low tension, ~180 kN/m). The controller
    works in the SI units of the rest of the model, so the count reference is turned back into
    newtons through ``sensor``'s calibration table (the same read-back as the measured T, so
    T = T_r ⇔ count = count_r); below zero counts (a slack spring) it continues linearly with
    the table's zero-tension slope, as the count error of (4.38) would; above the sensor's range
    (the table's top count) the reference is the table's top tension, unreachable: full duty.
    """

    sensor: TensionSensor  # its calibration table only (the firmware knows no drift)
    pulse_m: float  # wire per encoder pulse (MotorSpec.encoder_step_m, Table 3.2)
    fixed_point: float  # thesis k_s units per (count / pulse)

    @classmethod
    def matching(cls, sensor: TensionSensor, pulse_m: float, n_m_per_unit: float) -> CountSpring:
        """The scale that makes the spring, linearised at its rest point (l = l_0, T_r = 0), as
        stiff as ``n_m_per_unit`` N/m per thesis unit: the earlier newton-linear law is then this
        law's small-displacement limit."""
        return cls(sensor, pulse_m, 1.0 / (n_m_per_unit * pulse_m * sensor.zero_slope_counts_n))

    def counts(self, l, l_0, k_s) -> np.ndarray:
        """The reference ADC count for wire length l (eq. 4.36 in counts and pulses)."""
        return k_s * (np.asarray(l_0) - np.asarray(l)) / self.pulse_m / self.fixed_point

    def reference(self, l, l_0, k_s) -> np.ndarray:
        """The reference count as a tension [N] through the calibration table."""
        c = self.counts(l, l_0, k_s)
        s = self.sensor
        return np.where(c >= 0.0, np.interp(c, s.table_adc, s.table_tension), c / s.zero_slope_counts_n)

    def stiffness_n_m(self, tension_n, k_s) -> np.ndarray:
        """The spring's local stiffness in newtons at a tension: (k_s / fixed_point / pulse) divided
        by the sensor's local slope dcount/dT — rises with tension as the sensor saturates."""
        return k_s / self.fixed_point / self.pulse_m / self.sensor.slope_counts_n(tension_n)


def law_S(T, l, l_0, dT, g: Gains, spring: CountSpring | None = None) -> np.ndarray:
    """Eq. 4.39: the tension law (4.38) tracking the software spring (4.36), in counts with a
    :class:`CountSpring`, else linear in newtons."""
    T_r = software_spring(l, l_0, g.k_s) if spring is None else spring.reference(l, l_0, g.k_s)
    return law_T(T, T_r, dT, g)


def law_LL(l, l_r, integral, dl, T, g: Gains) -> np.ndarray:
    """Eq. 4.40: length PID while T < T_l, output 0 once the tension reaches the limit."""
    return np.where(T < g.T_l, law_L(l, l_r, integral, dl, g), 0.0)


def step_function(x) -> np.ndarray:
    """Eq. 4.42: f(x) = 1 for x > 0, else 0."""
    return (np.asarray(x) > 0).astype(float)


def unified_duty(l, l_r, integral, dl, T, T_r, dT, l_0, g: Gains) -> np.ndarray:
    """Eq. 4.41, all modes in one expression; the mode is chosen by the parameters (Table 4.6):
    L: K_Pt = K_Dt = 0, k_s = 0, T_l = ∞; T: length gains 0, k_s = 0; S: length gains 0, T_r = 0;
    LL: tension gains 0."""
    spring_ref = T_r + g.k_s * (l_0 - l)
    length_part = step_function(g.T_l - T) * (g.K_Pl * (l - l_r) + g.K_Il * integral + g.K_Dl * dl)
    tension_part = step_function(np.abs(T - spring_ref) - g.T_t) * (g.K_Pt * (T - spring_ref) + g.K_Dt * dT)
    return -length_part - tension_part


def table_4_6_gains(mode: Mode, g: Gains) -> Gains:
    """The parameter set that makes :func:`unified_duty` one mode (Table 4.6; "—" entries set to
    values that make them inactive, e.g. T_l = ∞ for L mode, spec §6.11)."""
    zero_len = dict(K_Pl=0.0, K_Il=0.0, K_Dl=0.0)
    zero_ten = dict(K_Pt=0.0, K_Dt=0.0)
    if mode == Mode.L:
        return replace(g, **zero_ten, k_s=0.0, T_l=np.inf)
    if mode == Mode.T:
        return replace(g, **zero_len, k_s=0.0)
    if mode == Mode.S:
        return replace(g, **zero_len, T_r=0.0)
    return replace(g, **zero_ten, k_s=0.0)


def encoder_targets(model_lengths, zero_lengths) -> np.ndarray:
    """Model muscle lengths λ (eq. 4.25) → encoder targets l_r = λ(θ_zero) − λ (see the module
    docstring); ``zero_lengths`` are the model lengths at the posture the encoders were zeroed in."""
    return np.asarray(zero_lengths, dtype=float) - np.asarray(model_lengths, dtype=float)


def interference_modes(lengths_from, lengths_to, lengthening: Mode) -> np.ndarray:
    """§4.7.2: going from posture θ0 (model lengths l_r0) to θ1 (l_r1), *shortening* muscles
    (l_r1 < l_r0) generate the change and are length controlled (L); *lengthening* ones get the
    tension-limited ``lengthening`` mode (LL, T or S) so their interference can escape. A muscle
    whose model length does not change is treated as shortening (chosen)."""
    shortening = np.asarray(lengths_to) <= np.asarray(lengths_from)
    return np.where(shortening, Mode.L, lengthening).astype(int)


# §4.7.3's recommendations (and the §4.9.1 summary): which (shortening, lengthening) modes to use
RECOMMENDED = {
    "normal": (Mode.L, Mode.LL),  # normal motion; also the lowest current
    "stiff": (Mode.L, Mode.L),  # stiffness or large force; roll-only motion or near the basic posture
    "light_load": (Mode.LL, Mode.LL),  # arms down, small deformation: smallest model error
    "flexible": (Mode.S, Mode.S),  # flexibility needed, k_s tuned via eq. 4.35
}


# The upper layer's set-points of :class:`MuscleControl` (§4.6.5: "the upper layer selects the routine and
# sends the targets"): loop channels a player, teacher or sequence writes in an earlier stage and the
# controller reads in a later stage of the same tick. Each has one writer; on a tick nobody writes one, the
# controller keeps the last value it was given (as the firmware keeps its target registers).
SETPOINTS = (
    Channel("mode", SET, doc="per-muscle Mode (L, T, S, LL)"),
    Channel("l_r", SET, doc="target encoder lengths of L and LL muscles [m]"),
    Channel("T_r", SET, doc="target tensions of T muscles [N]"),
    Channel("l_0", SET, doc="natural lengths of the software springs of S muscles [m]"),
)


@dataclass
class MuscleState:
    """Per-muscle controller memory: the length integral and the previous readings."""

    integral: np.ndarray
    l_prev: np.ndarray | None = None
    T_prev: np.ndarray | None = None
    mode: np.ndarray = field(default_factory=lambda: np.zeros(0, dtype=int))


class MuscleControl(Module):
    """All muscles' L/T/S/LL laws at the control period, as a runtime module.

    Reads ``snapshot["encoder"]`` (l, m) and ``snapshot["tension"]`` (T, N) and contributes
    ``{"duty": o}``. Modes and targets are per muscle: they arrive on the :data:`SETPOINTS` channels
    (when present in the snapshot, before the tick's duty is computed), or are set between runs
    (:meth:`set_modes`, :meth:`set_targets`); gains are a :class:`Gains` whose fields may be
    scalars or (m,) arrays. Each tick's duty is kept as ``last_duty``.
    """

    def __init__(self, m: int, gains: Gains | None = None, period: float = 1e-3, name: str = "muscles",
                 spring: CountSpring | None = None):
        super().__init__(name, period)
        self.m = m
        self.gains = gains or Gains()
        self.spring = spring  # S mode in ADC counts (k_s in counts / pulse), or None: in N/m
        self.l_r = np.zeros(m)
        self.T_r = np.full(m, self.gains.T_r, dtype=float)
        self.l_0 = np.zeros(m)
        self.state = MuscleState(np.zeros(m), mode=np.full(m, int(Mode.L)))
        self.last_duty = np.zeros(m)
        self._masks = None  # per-mode masks of the current mode array (rebuilt when modes change)

    @property
    def modes(self) -> np.ndarray:
        return self.state.mode

    def set_modes(self, modes) -> None:
        """Switch modes per muscle (§4.6.5: the upper layer selects the routine). The length
        integral restarts for muscles entering L or LL. The mode array is replaced, never edited
        in place (the tick caches its per-mode masks per array)."""
        new = np.broadcast_to(np.asarray(modes, dtype=int), (self.m,)).copy()
        entering = (new != self.state.mode) & np.isin(new, (Mode.L, Mode.LL))
        self.state.integral[entering] = 0.0
        self.state.mode = new

    def set_targets(self, l_r=None, T_r=None, l_0=None) -> None:
        """Target length (L, LL), target tension (T) and spring natural length (S), per muscle."""
        for name, value in (("l_r", l_r), ("T_r", T_r), ("l_0", l_0)):
            if value is None:
                continue
            if isinstance(value, np.ndarray) and value.dtype == float and value.shape == (self.m,):
                setattr(self, name, value.copy())  # the per-tick case: already one value per muscle
            else:
                setattr(self, name, np.broadcast_to(np.asarray(value, dtype=float), (self.m,)).copy())

    def set_gains(self, **changes) -> None:
        """Change gains at run time (Table 4.6: all are dynamically adjustable)."""
        self.gains = replace(self.gains, **changes)

    def spring_reference(self, l) -> np.ndarray:
        """S mode's reference tension [N] at wire length l (eq. 4.36, see :func:`law_S`)."""
        if self.spring is None:
            return software_spring(l, self.l_0, self.gains.k_s)
        return self.spring.reference(l, self.l_0, self.gains.k_s)

    def reset(self, snapshot: Snapshot) -> None:
        self.state.l_prev = np.asarray(snapshot["encoder"], dtype=float).copy()
        self.state.T_prev = np.asarray(snapshot["tension"], dtype=float).copy()

    def duty(self, l, T, dt: float) -> np.ndarray:
        """One control tick for all muscles: the per-mode laws, saturated and PWM-quantised.

        The same laws as :func:`law_L`, :func:`law_T`, :func:`law_S` and :func:`law_LL`
        (a test checks the two agree), written with masks cached per mode set for the 1 ms loop."""
        g, s = self.gains, self.state
        if self._masks is None or self._masks[0] is not s.mode or self._masks[1] is not g:
            mode = s.mode
            is_l, is_ll, is_s = mode == _L, mode == _LL, mode == _S
            tension_mode = (mode == _T) | is_s
            # per mode set and gains: the masks, which of them are empty or full, the integral's clamp
            self._masks = (mode, g, is_l, is_ll, bool(is_ll.any()), bool(is_l.all()), tension_mode,
                           bool(tension_mode.any()), bool(tension_mode.all()), is_s, bool(is_s.any()),
                           1.0 / np.maximum(g.K_Il, 1e-12))
        _, _, is_l, is_ll, any_ll, all_l, tension_mode, any_tension, all_tension, is_s, any_s, limit = self._masks
        length_mode = is_l | (is_ll & (T < g.T_l)) if any_ll else is_l
        every = all_l or bool(length_mode.all())  # np.where over an all-true mask is its first operand
        o = np.zeros(self.m)
        if every or length_mode.any():
            err = l - self.l_r
            integral = np.minimum(np.maximum(s.integral + err * dt, -limit), limit)
            s.integral = integral if every else np.where(length_mode, integral, s.integral)
            law = -g.K_Pl * err - g.K_Il * s.integral - g.K_Dl * ((l - s.l_prev) / dt)
            o = law if every else np.where(length_mode, law, o)
        if any_tension:
            e = T - (np.where(is_s, self.spring_reference(l), self.T_r) if any_s else self.T_r)
            tension_law = np.where(np.abs(e) >= g.T_t, -g.K_Pt * e - g.K_Dt * ((T - s.T_prev) / dt), 0.0)
            o = tension_law if all_tension else np.where(tension_mode, tension_law, o)
        s.l_prev, s.T_prev = l, T
        self.last_duty = pwm_duty(o)
        return self.last_duty

    def update(self, snapshot: Snapshot):
        if "mode" in snapshot:
            self.set_modes(snapshot["mode"])
        if "l_r" in snapshot or "T_r" in snapshot or "l_0" in snapshot:
            self.set_targets(snapshot.get("l_r"), snapshot.get("T_r"), snapshot.get("l_0"))
        l = np.asarray(snapshot["encoder"], dtype=float)
        T = np.asarray(snapshot["tension"], dtype=float)
        return {"duty": self.duty(l, T, self.period)}
