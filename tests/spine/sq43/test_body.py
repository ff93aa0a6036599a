"""The MuJoCo SQ43 (spine/sq43/body.py) and its gaits (spine/sq43/gaits.py): model, trot generator, the GA on
every executor and its resume."""

from types import SimpleNamespace

import mujoco
import numpy as np
import pytest

from shintai.evolve import make_executor
from shintai.scenarios.experiment import run_rig
from shintai.scenarios.runner import RunContext
from shintai.spine import ga_run
from shintai.spine.sq43 import body as B
from shintai.spine.sq43 import design as sq43
from shintai.spine.sq43 import gaits as G
from shintai.spine.sq43.constants import DUTY, GENE_HI, GENE_LO


def test_model_mass_and_dof():
    model = B.build_spec().compile()
    assert model.body_subtreemass[1] == pytest.approx(1.9)  # §3.2.2: 1.9 kg
    leg_ids, spine_ids = B.actuator_ids(model)
    assert len(leg_ids) == 12 and len(spine_ids) == 6 and model.nu == 18  # 12 leg servos + servo A, B × 3 blocks
    hinges = [mujoco.mj_id2name(model, mujoco.mjtObj.mjOBJ_JOINT, j) for j in range(model.njnt)
              if model.jnt_type[j] == mujoco.mjtJoint.mjJNT_HINGE]
    assert len([h for h in hinges if h[:2] in B.LEGS]) == 12 and len([h for h in hinges if h.startswith("B")]) == 9
    assert {int(model.sensor(n).type[0]) for n in ("acc_shoulder", "acc_hip")} == {int(mujoco.mjtSensor.mjSENS_ACCELEROMETER)}


def test_spine_torsion_matches_the_quasi_static_model():
    """The three torsion hinges in series give sq43.torsional_stiffness of the straight spine."""
    model = B.build_spec().compile()
    k = [model.jnt_stiffness[model.joint(f"B{b}_twist").id] for b in (1, 2, 3)]
    assert 1.0 / sum(1.0 / np.array(k)) == pytest.approx(sq43.torsional_stiffness((0.0, 0.0, 0.0)))


def test_leg_ik_inverts_fk():
    feet = np.array([[0.03, 0.01, -0.21], [-0.04, -0.02, -0.225], [0.0, 0.0, -0.218]])
    for leg in B.LEGS:
        np.testing.assert_allclose(B.leg_fk(B.leg_ik(leg, feet)), feet, atol=1e-9)


def test_stands():
    body = B.SQ43Body()
    for _ in range(500):
        body.step()
    assert body.data.sensor("shoulder_pos").data[2] > 0.2
    assert abs(np.degrees(B.roll_of(body.data.sensor("shoulder_quat").data))) < 0.5


def test_trot_foot_path_follows_the_genes():
    genome = np.array([3.0, 60.0, 218.0, 15.0, 10.0, -20.0])
    t = np.arange(0, 6.0, 0.001)
    for leg in B.LEGS:
        p = G.foot_path(genome, t, leg)
        centre = 10.0 if leg[1] == "F" else -20.0
        assert 1e3 * p[:, 0].min() == pytest.approx(centre - 30.0, abs=0.1)  # stride = fore
        assert 1e3 * p[:, 0].max() == pytest.approx(centre + 30.0, abs=0.1)
        assert 1e3 * p[:, 2].min() == pytest.approx(-218.0)  # natural length
        assert 1e3 * (p[:, 2].max() - p[:, 2].min()) == pytest.approx(15.0)  # height
        lifted = p[:, 2] > p[:, 2].min() + 1e-9
        assert lifted.mean() == pytest.approx(1 - DUTY, abs=0.01)  # duty 0.5
        start = G.START_TIME_S[leg]
        first = t[np.argmax(lifted)]
        assert first == pytest.approx(start, abs=0.002)  # swing starts at the start time
        np.testing.assert_allclose(G.foot_path(genome, t + 3.0, leg), p, atol=1e-9)  # periodic in cycle
    # trot: the diagonal pairs in phase
    np.testing.assert_allclose(G.foot_path(genome, t, "LF")[:, 2], G.foot_path(genome, t, "RH")[:, 2])
    np.testing.assert_allclose(G.foot_path(genome, t, "RF")[:, 2], G.foot_path(genome, t, "LH")[:, 2])


def test_trot_rollout_equals_the_body_replay():
    genome = np.array([3.0, 60.0, 218.0, 15.0, 0.0, 0.0])
    replay = G.trot_result(run_rig(G.trot_rig(genome, 1.0)).log, genome)
    assert G.simulate_trot(genome, 1.0)["fitness"] == replay["fitness"]


def _ctx(tmp_path, **params):
    p = {"generations": 2, "population": 4, "executor": "serial", "workers": 0, "address": "", "resume": True}
    p.update(params)
    tmp_path.mkdir(parents=True, exist_ok=True)
    return RunContext(SimpleNamespace(id="test.sq43", source="test"), p, 5, tmp_path, quiet=True)


FIT = G.TrotFitness(duration_s=1.0)


@pytest.fixture(scope="module")
def serial(tmp_path_factory):
    return _evolve(_ctx(tmp_path_factory.mktemp("serial")), "trot", FIT, GENE_LO, GENE_HI)


@pytest.mark.parametrize("kind", ["process", "ray"])
def test_executors_give_identical_generations(tmp_path, serial, kind):
    result = _evolve(_ctx(tmp_path, executor=kind, workers=2), "trot", FIT, GENE_LO, GENE_HI)
    np.testing.assert_array_equal(result.history.best, serial.history.best)
    np.testing.assert_array_equal(result.best_genome, serial.best_genome)


def test_killed_run_resumes_to_the_same_result(tmp_path):
    straight = _evolve(_ctx(tmp_path / "a", generations=3), "trot", FIT, GENE_LO, GENE_HI)
    _evolve(_ctx(tmp_path / "b", generations=2), "trot", FIT, GENE_LO, GENE_HI)
    resumed = _evolve(_ctx(tmp_path / "b", generations=3), "trot", FIT, GENE_LO, GENE_HI)
    np.testing.assert_array_equal(resumed.history.best, straight.history.best)
    np.testing.assert_array_equal(resumed.best_genome, straight.best_genome)


def test_executor_names():
    with make_executor("serial") as ex:
        assert ex.map(FIT, [GENE_LO]) == [FIT(GENE_LO)]


def _evolve(ctx, *args, **kw):
    """ga_run.evolve with the GA's parameters of ``ctx`` as named arguments (as the experiments pass them)."""
    return ga_run.evolve(ctx, *args, ga=ga_run.GARun(**{k: ctx.params[k] for k in ga_run.GA_KEYS}), **kw)
