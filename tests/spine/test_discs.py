"""Cla's pre-compressed hardening discs (seed 003 §3.6.1, §3.5.3; spine.discs) and the upright criterion that fixes
their stiffness (§7.1.1, §4.6.2), both in spine.discs."""

from dataclasses import replace

import numpy as np

from shintai.core.constants import KGF_N
from shintai.spine.bodies import ring_springs
from shintai.spine.bodies_mujoco import SpineBody
from shintai.spine.cla.constants import CLA_DISC_HARDENING, CLA_DISC_K_STAR_NM_RAD, CLA_RING_DISC
from shintai.spine.discs import (
    HardeningDiscs,
    critical_disc_stiffness,
    rest_tangent,
    ring_forces,
    upright_margin,
)
from shintai.spine.geometry import SpineModel
from shintai.spine.robots import CLA

D = CLA_RING_DISC


def pitch_torque(disc, deg):
    return -ring_forces(disc, [[0.0, np.radians(deg), 0.0]])[0, 1]


def test_ring_forces_are_rabbits_ring_law_on_the_captured_ball():
    """Q = J_ringᵀ f(c) of QuasiStaticSpine's ring springs (Rabbit's geometry code) at the design gap, any posture."""
    q = np.random.default_rng(3).uniform(-0.3, 0.3, (CLA.n, 3))
    d, J, _ = SpineModel(CLA.model.chain, ring_springs(CLA.model, D)).derivatives(q.reshape(-1), np.zeros(CLA.n))
    assert np.allclose(ring_forces(D, q).reshape(-1), J.T @ D.force(D.compression(d)), atol=1e-9)


def test_rest_tangent_against_a_hand_calculation():
    """At rest each spring is at c0 = t_free − gap; K ≈ f'(c0) Σ x_k² = (k1 + 3 k3 c0²) N r² / 2 (the faces' geometric
    term is a fraction of a percent). Pre-compressed, the disc pushes back harder at a bend than one just touching
    (§3.5.3's behaviour 2 against 1): both halves of the ring work until asin(c0 / r) = 1.3°."""
    c0 = D.t_free_m - D.gap_m
    hand = (D.k1_n_m + 3 * D.k3_n_m3 * c0**2) * D.n_ring * D.ring_radius_m**2 / 2
    k = rest_tangent(D)
    assert abs(k[1] - hand) < 0.01 * hand and abs(k[0] - k[1]) < 1e-9
    touching = replace(D, gap_m=D.t_free_m)
    assert pitch_torque(D, 1.0) > 2 * pitch_torque(touching, 1.0) and pitch_torque(D, 4.0) > 1.4 * pitch_torque(touching, 4.0)


def test_the_disc_hardens_with_the_bend():
    """Beyond the angle where half the ring unloads (asin(c0 / r) = 1.3°), the tangent grows with the bend: the
    torque at 18° is more than 3 × that at 6° (7 ×), and the neo-Hookean β makes the spring 5.67 × stiffer at 50 %."""
    assert pitch_torque(D, 18.0) > 3 * pitch_torque(D, 6.0) > 0.0  # a linear spring's ratio is 3
    tangent = [(pitch_torque(D, a + 0.01) - pitch_torque(D, a - 0.01)) / np.radians(0.02) for a in (4.0, 10.0, 18.0)]
    assert tangent[0] < tangent[1] < tangent[2]
    c = 0.5 * D.t_free_m
    assert abs((D.k1_n_m + 3 * D.k3_n_m3 * c**2) / D.k1_n_m - 17 / 3) < 1e-9 and CLA_DISC_HARDENING > 6


def test_hardening_discs_apply_the_law_on_the_mujoco_spine():
    """The joint stiffness (the tangent at rest, implicit) plus the hook's qfrc_applied is the ring law plus the
    linear twist spring, at a bent posture."""
    body = SpineBody(CLA)
    hook = HardeningDiscs(body, D)
    q = np.tile(np.radians([4.0, -9.0, 3.0]), CLA.n)
    body.set_theta(q)
    hook()
    m, dofs = body.model, hook.dofs
    joints = [m.jnt_qposadr.tolist().index(a) for a in body.spine_qpos]
    total = -m.jnt_stiffness[joints] * q + body.data.qfrc_applied[dofs]
    want = ring_forces(D, q.reshape(-1, 3)) - np.array([0.0, 0.0, D.k_twist_nm_rad]) * q.reshape(-1, 3)
    assert np.allclose(total, want.reshape(-1), atol=1e-9)
    assert hook in body.before_physics


def test_upright_criterion_fixes_clas_disc():
    """§7.1.1/§4.6.2 on E11's Cla (arms raised, every muscle at 1 kgf): k* as committed; the old linear 4 N m/rad
    leaves upright unstable, the hardening disc's tangent at rest (2 k*, every axis) makes it stable."""
    body = SpineBody(CLA)
    k_star = critical_disc_stiffness(body, KGF_N, tol_nm_rad=0.02)
    assert abs(k_star - CLA_DISC_K_STAR_NM_RAD) < 0.05
    assert upright_margin(body, KGF_N, 4.0) < 0.0 < upright_margin(body, KGF_N, 0.98 * 2 * k_star)
    assert upright_margin(body, KGF_N, k_star - 0.2) < 0.0 < upright_margin(body, KGF_N, k_star + 0.2)
    k = rest_tangent(D)
    assert np.all(np.abs(np.array([k[0], k[1], k[2] + D.k_twist_nm_rad]) - 2 * k_star) < 0.01 * 2 * k_star)


def test_each_joints_disc_forces_depend_on_its_own_angles_only():
    """The compiled law (discs.RingLaw) runs over every joint at once: the five joints' forces are, to the bit,
    five one-joint evaluations, and the hook writes only the spine's hinges of qfrc_applied."""
    q = np.random.default_rng(5).uniform(-0.3, 0.3, (CLA.n, 3))
    assert np.array_equal(ring_forces(D, q), np.vstack([ring_forces(D, qi) for qi in q]))
    body = SpineBody(CLA)
    hook = HardeningDiscs(body, D)
    body.set_theta(q.reshape(-1))
    body.data.qfrc_applied[:] = 7.0
    hook()
    others = np.setdiff1d(np.arange(body.model.nv), hook.dofs)
    assert np.all(body.data.qfrc_applied[others] == 7.0) and not np.any(body.data.qfrc_applied[hook.dofs] == 7.0)
