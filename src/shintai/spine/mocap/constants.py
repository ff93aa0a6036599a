"""The numbers of the motion-capture unit's modules — one place per constant (DESIGN.md), each with its
thesis section or the reason it was chosen; grouped by the module that uses them."""

from __future__ import annotations


# --- mocap.plots ---
TILE = (300, 380)  # width, height of each robot's picture

# --- mocap.retarget ---
FPS = 30  # chosen: a common capture rate
DURATION_S = 3.0
TWIST_PEAK_DEG = 55.0  # chosen: a strong human wind-up (shoulders against pelvis); above HRP2's 45° waist yaw
PELVIS_COUNTER_DEG = 10.0  # the pelvis turns the other way in the world (the twist is measured against it)
FLEXION_DEG = 20.0  # forward bend of the spine in the crouch
SIDE_BEND_DEG = 6.0
