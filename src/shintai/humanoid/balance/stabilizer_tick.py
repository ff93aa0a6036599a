"""The stabilizer's per-tick arithmetic as compiled kernels (issue 30): the feet's exerted wrenches from the ankle F/T
sensors and the LIP tracking of [55] Eq. 26 in the foot-origin frame — step 1 and the sensing of
:mod:`~shintai.humanoid.balance.stabilizer` (its module docstring holds the method, the frames and the sign convention;
:class:`~shintai.humanoid.balance.stabilizer.StabilizerModule` calls these every 4 ms).

Compiled without fast-math, these are the same IEEE operations in the same order as the Python-float code they
replaced (62ab338): tests/humanoid/balance/test_stabilizer_tick.py runs each kernel's source under Python
(``.py_func``) against the compiled kernel, and the replacement was checked against the old code on every humanoid
scenario (identical metrics and logs at smoke size) and on the module's options (identical states). One exception:
the ``"imu"`` CoM reading's 3×3 attitude product is written out as sums, where NumPy's ``@`` may fuse them.

The state vector (one float array of :data:`STATE_SIZE` the module owns; its slots below) carries, between ticks, the
CoM of the last tick and its filtered velocity, the CoM reference of the last tick, and the ``"feet"``/``"imu"``
reading's last offset, its filtered velocity and its support code.
"""

from __future__ import annotations

import math

from numba import njit

# the state's slots: CoM (3), CoM velocity (3), last CoM reference (3), has-reference flag, reading's last (x, y), its
# velocity (x, y), has-reading flag, the reading's support code
COM, COM_VEL, REF, HAS_REF, READ, READ_VEL, HAS_READ, READ_SUPPORT = 0, 3, 6, 9, 10, 12, 14, 15
STATE_SIZE = 16
# the LIP kernel's outputs: p_d (x, y), measured ZMP (x, y), the reading (x, ẋ), the frame's cos ψ, sin ψ, its
# actual origin a (x, y) and reference origin r (x, y), and 1.0 when Eq. 26 ran (LIP tracking on, a foot loaded)
OUT_SIZE = 13
READINGS = {"world": 0, "feet": 1, "imu": 2}  # the CoM reading's code


@njit(cache=True)
def foot_wrench_rows(w, sensors, site_xmat, site_xpos, subtree_com, rows, weights):
    """Both feet's exerted wrenches into ``w`` (2 × 7, left then right): (f_z, τ roll, τ pitch, sole point x, y, z,
    sole yaw) — hrp2's ``ft_reaction`` (the foot's weight compensated) moved from the sensor site to the sole point
    and negated. ``rows``: per foot (sensor site, sole site, foot body, force adr, torque adr); ``weights`` the
    foot's subtree mass × gravity (world)."""
    for k in range(2):
        site, sole, link, f_adr, t_adr = rows[k, 0], rows[k, 1], rows[k, 2], rows[k, 3], rows[k, 4]
        gx, gy, gz = weights[k, 0], weights[k, 1], weights[k, 2]
        r = site_xmat[site]
        fx, fy, fz = sensors[f_adr], sensors[f_adr + 1], sensors[f_adr + 2]
        tx, ty, tz = sensors[t_adr], sensors[t_adr + 1], sensors[t_adr + 2]
        px, py, pz = site_xpos[site, 0], site_xpos[site, 1], site_xpos[site, 2]
        cx, cy, cz = subtree_com[link, 0] - px, subtree_com[link, 1] - py, subtree_com[link, 2] - pz
        # reaction about the sensor: f = −R f_s − m g, τ = −R τ_s − (c × m g)
        Fx = -(r[0] * fx + r[1] * fy + r[2] * fz) - gx
        Fy = -(r[3] * fx + r[4] * fy + r[5] * fz) - gy
        Fz = -(r[6] * fx + r[7] * fy + r[8] * fz) - gz
        Tx = -(r[0] * tx + r[1] * ty + r[2] * tz) - (cy * gz - cz * gy)
        Ty = -(r[3] * tx + r[4] * ty + r[5] * tz) - (cz * gx - cx * gz)
        sx, sy, sz = site_xpos[sole, 0], site_xpos[sole, 1], site_xpos[sole, 2]
        lx, ly, lz = px - sx, py - sy, pz - sz  # sensor − sole point
        tau_x = Tx + ly * Fz - lz * Fy  # the reaction torque about the sole point
        tau_y = Ty + lz * Fx - lx * Fz
        q = site_xmat[sole]
        w[k, 0], w[k, 1], w[k, 2] = Fz, -tau_x, -tau_y
        w[k, 3], w[k, 4], w[k, 5], w[k, 6] = sx, sy, sz, math.atan2(q[3], q[0])


@njit(cache=True)
def _wrap_pi(angle):
    """:func:`shintai.core.geometry.wrap_pi` (π − ((π − a) mod 2π), Python's floored float modulo, as numba's is),
    written here: numba's disk cache of a kernel is keyed on its own file only, so a callee compiled from another
    file could go stale in it (tests/humanoid/balance/test_stabilizer_tick.py holds the two equal bit for bit)."""
    return math.pi - (math.pi - angle) % (2 * math.pi)


@njit(cache=True)
def lip_tracking(out, state, w, com, cr, zr, soles, code, k1, k2, k3, dt, vel_filter, contact_fz, lip, reading,
                 err, ankle, ankles, ankle_dx):
    """One tick of the stabilizer's step 1 (stabilizer module docstring) into ``out`` (:data:`OUT_SIZE`), ``state``
    (:data:`STATE_SIZE`, the slots above) updated: the CoM velocity filter (ẋ ← f ẋ + (1 − f) Δx/Δt), the foot-origin frame of the
    stance feet (``code``: 0 both, 1 left, −1 right; their mean point and mean yaw, re-expressed on the reference
    soles ``soles``), the measured ZMP of the feet in contact (f_z > ``contact_fz``), the CoM reading (``reading``:
    0 world, 1 feet, 2 imu with the attitude error ``err``) and Eq. 26 (``lip``; p_d = p_ref without it or with no
    foot loaded). With ``ankle`` (hrpsys's ankle foot origin) ``ankles`` (2 × 2, left, right: the ankle links' x, y)
    replace the sole points as the frame's origin and ``ankle_dx`` moves the reference origin."""
    # the CoM and its filtered velocity (world)
    a = 1.0 - vel_filter
    for i in range(3):
        v = vel_filter * state[COM_VEL + i] + a * (com[i] - state[COM + i]) / dt
        state[COM_VEL + i] = v
        state[COM + i] = com[i]
    if state[HAS_REF] == 0.0:
        state[REF], state[REF + 1], state[REF + 2], state[HAS_REF] = cr[0], cr[1], cr[2], 1.0
    vr_x, vr_y = (cr[0] - state[REF]) / dt, (cr[1] - state[REF + 1]) / dt
    state[REF], state[REF + 1], state[REF + 2] = cr[0], cr[1], cr[2]
    # the stance feet: their mean point and yaw (the first foot's yaw plus the mean wrapped difference)
    first, n = 0, 0
    ax = ay = az = rx = ry = bx = by = turn = 0.0
    for k in range(2):
        if (k == 0 and code >= 0) or (k == 1 and code <= 0):
            if n == 0:
                first = k
            else:
                turn += _wrap_pi(w[k, 6] - w[first, 6])
            ax += w[k, 3]
            ay += w[k, 4]
            az += w[k, 5]
            rx += soles[k, 0]
            ry += soles[k, 1]
            bx += ankles[k, 0]
            by += ankles[k, 1]
            n += 1
    psi = w[first, 6] + turn / n
    ax, ay, az, rx, ry = ax / n, ay / n, az / n, rx / n, ry / n
    if ankle:  # hrpsys's foot origin: the ankle links' origins
        ax, ay = bx / n, by / n
        rx += ankle_dx
    c, s = math.cos(psi), math.sin(psi)
    # the measured ZMP of the feet in contact: Σ(a f + (τ_y, −τ_x)) / Σ f, into the reference stance frame
    num_x = num_y = total = 0.0
    for k in range(2):
        fz = w[k, 0]
        if fz > contact_fz:
            num_x += w[k, 3] * fz + w[k, 2]
            num_y += w[k, 4] * fz - w[k, 1]
            total += fz
    act_x = act_y = math.nan
    if total > 0:
        x, y = num_x / total - ax, num_y / total - ay
        act_x, act_y = c * x + s * y + rx, -s * x + c * y + ry
    cx = vx = math.nan
    tracked = lip and total > 0
    if tracked:
        x, y = com[0] - ax, com[1] - ay
        cx, cy = c * x + s * y + rx, -s * x + c * y + ry
        u, v = state[COM_VEL], state[COM_VEL + 1]
        vx, vy = c * u + s * v, -s * u + c * v
        if reading != 0:  # the offset (x, y) from the stance feet ("imu": through the estimated attitude)
            if reading == 2:  # err (x, y, z) as sums (NumPy's @ may fuse them: float rounding)
                z = com[2] - az
                x, y = err[0, 0] * x + err[0, 1] * y + err[0, 2] * z, err[1, 0] * x + err[1, 1] * y + err[1, 2] * z
                cx, cy = c * x + s * y + rx, -s * x + c * y + ry
            if state[HAS_READ] != 0.0 and state[READ_SUPPORT] == code:
                f = vel_filter
                state[READ_VEL] = f * state[READ_VEL] + (1 - f) * (cx - state[READ]) / dt
                state[READ_VEL + 1] = f * state[READ_VEL + 1] + (1 - f) * (cy - state[READ + 1]) / dt
            state[READ], state[READ + 1], state[HAS_READ], state[READ_SUPPORT] = cx, cy, 1.0, code
            vx, vy = state[READ_VEL], state[READ_VEL + 1]
        # [55] Eq. 26
        pd_x = zr[0] + k1 * (cr[0] - cx) + k2 * (vr_x - vx) + k3 * (zr[0] - act_x)
        pd_y = zr[1] + k1 * (cr[1] - cy) + k2 * (vr_y - vy) + k3 * (zr[1] - act_y)
    else:
        pd_x, pd_y = zr[0], zr[1]
    out[0], out[1], out[2], out[3], out[4], out[5] = pd_x, pd_y, act_x, act_y, cx, vx
    out[6], out[7], out[8], out[9], out[10], out[11] = c, s, ax, ay, rx, ry
    out[12] = 1.0 if tracked else 0.0
