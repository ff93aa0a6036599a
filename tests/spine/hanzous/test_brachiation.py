"""HanzouS's dynamic body and brachiation (spine/hanzous/body.py, spine/hanzous/brachiation.py, seed 003 §3.3, §5.7)."""

import pickle

import mujoco
import numpy as np
import pytest

from shintai.spine.hanzous import brachiation as B
from shintai.spine.hanzous.body import JOINTS, Grasps, Trunk, build_spec
from shintai.spine.hanzous.constants import DURATIONS_S
from shintai.spine.robots import HANZOUS


def _eq_5_8_bending(cam_deg: float) -> float:
    """E I / l by hand: spring steel 206 GPa, a 30 × 1 mm leaf, l linear in the cam angle 0–180° over 20–80 mm."""
    inertia = 0.030 * 0.001**3 / 12
    length = 0.02 + (0.08 - 0.02) * cam_deg / 180.0
    return 206e9 * inertia / length


def test_hanzous_has_18_servoed_joints_and_a_passive_trunk():
    model = build_spec().compile()
    assert len(JOINTS) == 18 == model.nu == HANZOUS.joints
    assert model.joint("trunk").id not in {int(model.actuator_trnid[i, 0]) for i in range(model.nu)}


def test_trunk_stiffness_changed_during_the_run_follows_eqs_5_4_to_5_8():
    """A constant moment across the trunk, weightless robot hanging from bar 0: the static deflection is M / (E I / l)
    for each cam angle, the cam turned between steps of one run."""
    model = build_spec().compile()
    model.opt.gravity[:] = 0.0
    data = mujoco.MjData(model)
    trunk = Trunk(model)
    dof = model.jnt_dofadr[trunk.joint]
    moment = 0.2  # N m
    for cam in (0.0, 90.0, 180.0):
        trunk.set_cam(cam)
        data.qfrc_applied[dof] = moment
        mujoco.mj_step(model, data, 2500)
        deflection = data.qpos[model.jnt_qposadr[trunk.joint]]
        assert abs(data.qvel[dof]) < 1e-3
        assert moment / deflection == pytest.approx(_eq_5_8_bending(cam), rel=0.02)
    assert _eq_5_8_bending(0.0) / _eq_5_8_bending(180.0) == pytest.approx(4.0)


def test_spline_passes_through_the_8_postures():
    for genome in (None, np.random.default_rng(1).uniform(*B.gene_bounds())):
        postures, knots = B.sequence(genome)
        assert postures.shape == (8, 9) and len(knots) == 8 and np.all(np.diff(knots) > 0)
        np.testing.assert_allclose(B.reference(postures, knots)(knots), postures, atol=1e-12)
    postures, knots = B.sequence(np.zeros(B.N_GENES))
    np.testing.assert_array_equal(postures, B.POSTURES)
    np.testing.assert_allclose(np.diff(knots), DURATIONS_S)
    assert B.N_GENES == 70


def test_grasp_closes_near_a_bar_and_opens_on_release():
    b = B.Brachiator()
    b.reset()
    g: Grasps = b.grasps
    assert g.held("L") == 0 and g.held("R") == 0
    mujoco.mj_step(b.model, b.data, 20)
    assert g.force_n("R") > 1.0  # hanging: the bar carries the hand
    g.update("R", closed=False)
    assert g.held("R") is None and g.force_n("R") == 0.0
    g.update("R", closed=True)  # still within the gripper's mouth: caught again
    assert g.held("R") == 0
    g.update("R", closed=False)
    b.data.ctrl[b.model.actuator("shoulder_pitch_R").id] = 1.5
    mujoco.mj_step(b.model, b.data, 300)
    assert min(g.distance("R", k) for k in range(3)) > HANZOUS.grasp_radius_m
    g.update("R", closed=True)  # commanded closed, but no bar in reach
    assert g.held("R") is None and g.held("L") == 0


def test_stiffness_policies_set_the_cam():
    b = B.Brachiator()
    cams = {}
    for policy in B.POLICIES:
        o = b.run(B.shipped_genome("stiff"), policy, record=True)  # grasps under all three
        cams[policy] = o.log["cam_deg"]
        assert o.success
    assert np.all(cams["stiff"] == 0.0) and np.all(cams["soft"] == HANZOUS.cam_range_deg)
    t = o.log["t"]
    assert np.all(cams["real"][t < o.release_s] == 0.0) and cams["real"][-1] == HANZOUS.cam_range_deg
    with pytest.raises(ValueError, match="policy"):
        b.run(None, "medium")


def test_fitness_does_not_depend_on_what_the_worker_evaluated_before():
    """One Brachiator per worker is reused: a genome's fitness is the same whatever ran before it, so serial,
    process and Ray executors (which order evaluations differently) give the same generations."""
    rng = np.random.default_rng(3)
    genomes = rng.uniform(*B.gene_bounds(), size=(2, B.N_GENES))
    fitness = pickle.loads(pickle.dumps(B.BrachiationFitness("real")))  # as the process and Ray executors ship it
    first = [fitness(g) for g in genomes]
    fitness_soft = B.BrachiationFitness("soft")
    fitness_soft(genomes[1])
    assert [fitness(g) for g in genomes[::-1]] == first[::-1]
    assert B.Brachiator().run(genomes[0], "real").fitness() == first[0]


def test_serial_and_process_pool_evolve_the_same_brachiation():
    """The brachiation fitness in worker processes (one Brachiator each) gives the serial run's generations."""
    from shintai.evolve import GAConfig, GeneticAlgorithm, make_executor

    lo, hi = B.gene_bounds()
    runs = []
    for kind in ("serial", "process"):
        ga = GeneticAlgorithm(B.BrachiationFitness("real"), lo, hi, GAConfig.seed003(generations=2, population=4),
                              seed=5)
        with make_executor(kind, 2) as executor:
            ga.executor = executor
            runs.append(ga.run())
    np.testing.assert_array_equal(runs[0].history.best, runs[1].history.best)
    np.testing.assert_array_equal(runs[0].best_genome, runs[1].best_genome)
