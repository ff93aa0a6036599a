"""The stabilizer reads τ, the CoM and the ZMP in the stance feet's frame when the feet yaw (seed 000 §5.2.2: δ is
the foot frame's roll/pitch displacement and τ the sole sensors'); on the V-BOARD the feet turn with the scooter."""

import math

import pytest

from shintai.core.runtime import Loop
from shintai.humanoid.balance import stabilizer
from shintai.humanoid.balance.stabilizer import into_yawed, mean_yaw
from shintai.humanoid.vboard.ride import VboardRide


def test_into_yawed_turns_a_world_vector_into_the_yawed_frame():
    psi = math.radians(30.0)
    # the yawed frame's own x axis, seen in the world, is its (1, 0)
    assert into_yawed(math.cos(psi), math.sin(psi), psi) == pytest.approx((1.0, 0.0))
    # a foot yawed by ψ exerting a pure pitch torque p about its own y axis reads (−p sin ψ, p cos ψ) in world axes
    p = 3.0
    assert into_yawed(-p * math.sin(psi), p * math.cos(psi), psi) == pytest.approx((0.0, p))
    assert into_yawed(0.4, -0.2, 0.0) == (0.4, -0.2)


def test_the_stance_feet_mean_yaw_wraps_at_180_degrees():
    assert mean_yaw([math.radians(179.0), math.radians(-179.0)]) == pytest.approx(math.radians(180.0))
    assert mean_yaw([0.2, 0.4]) == pytest.approx(0.3) and mean_yaw([-0.5]) == -0.5


def world_axes(x: float, y: float, psi: float) -> tuple[float, float]:
    """The reading the stabilizer had before: world axes whatever the feet's yaw."""
    return x, y


def yaw_after(seconds: float, sole_creep: bool = False) -> float:
    """The scooter's yaw (deg) after ``seconds`` of level 2 lowered from the lift (no sensor noise)."""
    r = VboardRide(level=2, noise=False, sole_creep=sole_creep)
    Loop(r.body, stages=r.stages, channels=r.channels).run(seconds)
    m = r.body.data.body("vboard").xmat
    return math.degrees(math.atan2(m[3], m[0]))


def test_the_foot_frame_cuts_the_level2_yaw_runaway(monkeypatch):
    """Measured with the soles creeping on the pads (``sole_creep``, the rides before MuJoCo's no-slip passes, whose
    differential creep drives the turn: vboard.sole_creep): at 9 s the scooter has turned 36° with the torques read in
    world axes (the pitch/roll mix ∝ sin ψ feeds the differential board pitch) and 12° in the feet's frame, the
    stabilizer's only reading. With no-slip both keep the two sides' θ_O turn: −9° and −11°."""
    feet, feet_held = yaw_after(9.0, sole_creep=True), yaw_after(9.0)
    monkeypatch.setattr(stabilizer, "into_yawed", world_axes)
    world, world_held = yaw_after(9.0, sole_creep=True), yaw_after(9.0)
    assert abs(world) > 25.0 and abs(feet) < 16.0
    assert abs(feet_held) < 12.0 and abs(world_held) < 15.0
