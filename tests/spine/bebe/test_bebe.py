"""BeBe's sensor-based rule (seed 003 §4.8.3) on hand-made cases, and the plant's properties."""

import numpy as np
import pytest

from shintai.core import Body, Loop, declare
from shintai.core.runtime import ChannelError, FunctionModule
from shintai.spine.bebe import body as bebe
from shintai.spine.bebe.constants import SPANS

# Four hand-made view shifts: right, up, left, and a 45° diagonal (right-up).
SHIFTS = np.array([[1.0, 0.0], [0.0, 1.0], [-1.0, 0.0], [1.0, 1.0]])
RIGHT, UP, LEFT, DIAG = range(4)
ALL_FREE = np.ones(4, dtype=bool)


def state(*on):
    s = np.zeros(4, dtype=bool)
    s[list(on)] = True
    return s


def test_switches_on_the_same_direction_muscle_at_the_smallest_angle():
    assert bebe.switch(np.array([50.0, 0.0]), SHIFTS, state(), ALL_FREE) == (RIGHT, True)
    assert bebe.switch(np.array([50.0, 45.0]), SHIFTS, state(), ALL_FREE) == (DIAG, True)


def test_threshold_is_strict_cos_above_0_2():
    v = np.array([50.0, 0.0])
    at = np.array([[0.2, np.sqrt(1 - 0.04)]])  # cos∠(v, v_i) = 0.2 exactly: inverse-direction
    above = np.array([[0.21, np.sqrt(1 - 0.21**2)]])
    one = np.ones(1, dtype=bool)
    assert bebe.switch(v, at, np.zeros(1, dtype=bool), one) is None
    assert bebe.switch(v, above, np.zeros(1, dtype=bool), one) == (0, True)
    assert bebe.switch(v, at, one, one) == (0, False)  # on and inverse-direction: switched off


def test_off_comes_before_on_and_takes_the_largest_angle():
    v = np.array([50.0, 0.0])  # RIGHT and DIAG are same-direction, UP (90°) and LEFT (180°) inverse
    assert bebe.switch(v, SHIFTS, state(UP, LEFT), ALL_FREE) == (LEFT, False)
    assert bebe.switch(v, SHIFTS, state(UP), ALL_FREE) == (UP, False)
    assert bebe.switch(v, SHIFTS, state(UP), ALL_FREE, off_first=False) == (RIGHT, True)  # the ablation


def test_nothing_to_do_when_every_same_direction_muscle_is_on():
    assert bebe.switch(np.array([50.0, 0.0]), SHIFTS, state(RIGHT, DIAG), ALL_FREE) is None


def test_dead_zone_suppresses_every_switch():
    assert bebe.switch(np.array([6.0, 8.0]), SHIFTS, state(LEFT), ALL_FREE, dead_zone_px=10.0) is None
    assert bebe.switch(np.array([6.0, 8.1]), SHIFTS, state(LEFT), ALL_FREE, dead_zone_px=10.0) == (LEFT, False)


def test_forced_muscles_are_never_switched():
    free = ~state(LEFT)
    assert bebe.switch(np.array([50.0, 0.0]), SHIFTS, state(LEFT), free) == (RIGHT, True)


class StillImage(Body):
    """A body whose target sits at a fixed image position; it records the valve commands."""

    channels = declare("valve")

    def __init__(self, target_px, dt=bebe.CYCLE_S / 10):
        self.dt, self.t, self.target_px, self.valve = dt, 0.0, np.asarray(target_px, float), np.zeros(4)
        self.valves = []

    def snapshot(self):
        return {"t": self.t, "target_px": self.target_px, "valve": self.valve}

    def apply(self, command):
        self.valve = command["valve"]
        self.valves.append(self.valve.copy())

    def step(self):
        self.t += self.dt


def test_one_switch_per_66_ms_cycle_in_the_loop():
    body = StillImage([50.0, 10.0])  # RIGHT at 11°, DIAG at 34°, UP at 79° (cos 0.196: inverse)
    rule = bebe.TrackingRule(SHIFTS)
    Loop(body, [rule]).run(1.0)
    valves = np.vstack((np.zeros(4), body.valves))  # the all-off start, then one row per body step
    changes = np.flatnonzero(np.any(np.diff(valves, axis=0) != 0, axis=1))
    assert len(changes) == len(rule.switches) == 2  # then every same-direction muscle is on
    assert np.diff(changes).min() >= 10  # body steps per image cycle
    assert [(m, on) for _, m, on in rule.switches] == [(RIGHT, True), (DIAG, True)]


def test_forced_on_muscles_are_held_on_by_the_module():
    body = StillImage([50.0, 0.0])
    rule = bebe.TrackingRule(SHIFTS, forced=lambda t: [LEFT])
    Loop(body, [rule]).run(0.5)
    assert np.all(np.array(body.valves)[:, LEFT] == 1.0)


def test_same_direction_bound_of_four_orthogonal_shifts():
    assert bebe.same_direction_bound(SHIFTS[:3].tolist() + [[0.0, -1.0]]) == 2


def test_recovery_times_and_reversals_on_a_synthetic_episode():
    t = np.arange(0.0, 6.0, 0.5)
    inside = np.array([1, 1, 0, 0, 1, 1, 1, 1, 1, 1, 0, 0], dtype=bool)
    ep = bebe.Episode(t, np.zeros((len(t), 2)), np.zeros(len(t), int), inside)
    assert bebe.recovery_times(ep, [0.5, 3.0, 4.5]).tolist() == [1.5, 0.0, np.inf]
    switches = [(0.0, 3, True), (0.1, 3, False), (0.2, 4, True), (0.3, 5, True), (0.4, 5, False)]
    assert bebe.reversals(switches) == 2


@pytest.fixture(scope="module")
def plant_and_shifts():
    def make(target=None):
        return bebe.BeBePlant(target=target, rng=np.random.default_rng(0))
    return make, bebe.calibrate(make, settle_s=0.5)


def test_plant_has_hysteresis_and_does_not_superpose(plant_and_shifts):
    make, shifts = plant_and_shifts
    assert shifts.shape == (36, 2)
    assert bebe.hysteresis_residual(make, 0, 0.5) > 0.5  # eq. 4.44: the history matters
    names = make().model.muscles.names
    pair = (names.index("int-oblique-L/waist-abdomen 1"), names.index("int-oblique-R/waist-abdomen 1"))
    assert bebe.superposition_error(make, shifts, [pair], 0.5)[0] > 0.1


def test_cooperating_pairs_are_same_span_and_same_direction():
    shifts = np.array([[1.0, 0.0], [1.0, 0.5], [-1.0, 0.0], [1.0, 0.0], [0.0, 1.0], [1.0, 0.1]])
    assert bebe.cooperating_pairs(shifts, spans=2) == [(0, 1), (3, 5)]  # never (0, 3): other span


def test_cooperating_muscles_on_one_span_do_not_superpose(plant_and_shifts):
    """§4.8.3: two co-operating McKibben muscles on the same joints shorten each other, so each pulls
    less than alone; the same kind on another span (other joints) superposes far better."""
    make, shifts = plant_and_shifts
    names = make().model.muscles.names
    same = (names.index("rectus-L/waist-abdomen 1"), names.index("ext-oblique-L/waist-abdomen 1"))
    assert same in bebe.cooperating_pairs(shifts, len(SPANS))
    other = (names.index("rectus-L/waist-abdomen 1"), names.index("rectus-L/abdomen 1-shoulder"))
    e_same, e_other = bebe.superposition_error(make, shifts, [same, other], 0.5)
    assert e_same > 0.05 and e_same > 2 * e_other


def test_plant_rejects_unknown_channels():
    """The plant declares valve and push; anything else is the Loop's one ChannelError."""
    with pytest.raises(ChannelError, match="pressure"):
        Loop(bebe.BeBePlant(), [FunctionModule(lambda snap: {"pressure": np.zeros(36)}, name="bad")]).run(0.1)


def test_rule_brings_an_offset_target_into_the_dead_zone(plant_and_shifts):
    make, shifts = plant_and_shifts
    plant = make(target=lambda t: np.array([0.0, 0.06, -0.04]))  # ~35 px off centre
    assert np.linalg.norm(plant.snapshot()["target_px"]) > 25.0
    ep = bebe.track(plant, shifts, 3.0, dead_zone_px=15.0)
    assert ep.in_dead_zone[-1]
    assert ep.on_count.max() <= bebe.same_direction_bound(shifts)
