"""The numbers of the Kenta unit's modules — one place per constant (DESIGN.md), each with its
thesis section or the reason it was chosen; grouped by the module that uses them."""

from __future__ import annotations


# --- kenta.body ---
# chosen: firm human hands per spine joint axis (against 1 kgf muscles and ≈ 5 kg above the spine)
TEACHER_K_NM_RAD, TEACHER_D_NMS_RAD = 300.0, 3.0
# §3.7.1: "各節には過変形防止のハードウェア的なロック機構を設けた" — the spine's joint limits are hard stops; chosen:
# a stop time constant of 4 physics steps (MuJoCo's default 20 ms lets 1 kgf muscles bend joints far past ±10°)
SPINE_STOP_SOLREF_S = 0.002
# chosen: a vertebra's own inertia (≈ 5e-6 kg m²) against its 50 kN/m wires makes a ~3000 rad/s mode that the
# 0.5 ms explicit tendon springs cannot resolve (the internal vertebrae flail past their stops); this armature
# slows it to ≈ 500 rad/s and is < 1 % of the upper body's inertia about any spine joint
SPINE_ARMATURE_KGM2 = 2e-4
TEACHER_GROUP = 5  # actuator group of the teacher's hands, disabled (MjOption.disableactuator) when they let go
TARGET_RADIUS_M = 0.03  # chosen: a coloured ball

# --- kenta.postures ---
# chosen (Fig. 4.1's photographs are not in the text): three whole-spine (roll, pitch, yaw) postures [deg], a
# bend forward with a twist, a side bend, a bend back with the other twist — within a third of §3.7.1's ±90°
KENTA_KEY_POSTURES_DEG = ((0.0, 15.0, 15.0), (15.0, 0.0, 0.0), (0.0, -10.0, -15.0))
KENTA_TAUGHT_S = 1.5  # chosen: each posture is held by the teacher this long before its lengths are read
# chosen: the probe of :func:`locked_hold`, posture 1's forward bend without its twist (whole-spine r, p, y [deg])
KENTA_LOCK_PROBE_DEG = (0.0, 15.0, 0.0)

# --- kenta.tracking (its NN inverse model, §4.4.3) ---
# §3.7.1: "可動範囲は各節 roll,pitch,yaw の 3 軸とも ±10° 程度とした", "脊椎全体の可動範囲は，roll,pitch,yaw に各 ±90°
# 程度": §4.4.3's 7-point teacher grid per joint and axis (Cla: ±15° in 5° steps) scaled inside Kenta's stops
# (chosen: ±9° in 3° steps, ±90° for the whole spine); 7³ = 343 uniform bends as for Cla
KENTA_NN_GRID_DEG = (-9.0, -6.0, -3.0, 0.0, 3.0, 6.0, 9.0)

# --- kenta.statics ---
LOCK_TOLERANCE_M = 1e-6  # the locked reel's play [m] (chosen: an encoder pulse is ≈ 17 µm)
# chosen: the stops' time constant, 2 physics steps (MuJoCo's default 20 ms lets a 100 N wire slip 1.6 mm)
LOCK_SOLREF_S = 1e-3
