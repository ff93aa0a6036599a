"""The compiled chain IK (sim.ik_chain) against MuJoCo's kinematics and sim.ik's search, on HRP2's arms."""

from __future__ import annotations

import mujoco
import numpy as np
import pytest

from shintai.humanoid.robots import hrp2
from shintai.sim import ik
from shintai.sim.ik_chain import ChainIK, chain_fk

ARM = {s: [f"{s}_{j}" for j in ("shoulder_pitch", "shoulder_roll", "shoulder_yaw", "elbow_pitch", "wrist_yaw",
                                "wrist_roll", "wrist_pitch")] for s in "lr"}
BAR = np.array([1.0, 0.0, 0.0])  # the grasp site's x axis, the tricycle hands' bar (hrp2_limbs.BAR_IN_HAND)

# a chain with what HRP2's arm lacks: turned bodies, hinge anchors off the body origin, non-zero refs (qpos0), an
# offset inertial frame, and the site on two fixed bodies after the last joint
TWISTED = """
<mujoco><compiler angle="radian"/>
  <worldbody>
    <body name="base" pos="0.1 -0.2 0.3" quat="0.9 0.1 -0.3 0.2">
      <freejoint name="root"/>
      <geom size="0.05"/>
      <body name="b1" pos="0.05 0.02 0.1" euler="0.3 -0.5 0.7">
        <inertial pos="0.03 0.01 -0.02" quat="0.7 0.1 0.7 0" mass="1" diaginertia="0.01 0.02 0.03"/>
        <joint name="j1" axis="0.2 1 0.3" pos="0.01 -0.03 0.02" ref="0.4" range="-1.5 1.5"/>
        <body name="b2" pos="0.2 0 0.05" axisangle="1 1 0 0.9">
          <joint name="j2" axis="1 0 0" pos="-0.02 0.04 0.01" ref="-0.7" range="-2 2"/>
          <geom size="0.02" pos="0.1 0 0"/>
          <body name="b3" pos="0 0.15 0.1" euler="-0.2 1.0 0.1">
            <joint name="j3" axis="0 0.3 1" pos="0.05 0 -0.03" range="-1 1.2"/>
            <geom size="0.02"/>
            <body name="fixed" pos="0.07 -0.02 0.03" euler="0.5 0.2 -0.3">
              <geom size="0.01"/>
              <body name="fixed2" pos="0.01 0.02 0.03" quat="0.5 0.5 0.5 0.5">
                <site name="tip" pos="0.02 0.01 -0.04" euler="0.25 -0.4 0.6"/>
              </body>
            </body>
          </body>
        </body>
      </body>
    </body>
  </worldbody>
</mujoco>"""


@pytest.fixture(scope="module")
def robot():
    body = hrp2.build_hrp2()
    return body, {s: ChainIK(body.model, f"{s}_grasp", ARM[s]) for s in "lr"}


def _random_qpos(model, rng, scale):
    q = model.qpos0.copy()
    q[7:] += rng.normal(scale=scale, size=model.nq - 7)
    q[3:7] = rng.normal(size=4)
    q[3:7] /= np.linalg.norm(q[3:7])  # the free root turned too: the chain's parent anywhere
    return q


def test_forward_kinematics_is_mujocos(robot):
    body, chains = robot
    model, data, rng = body.model, mujoco.MjData(body.model), np.random.default_rng(0)
    for _ in range(100):
        data.qpos[:] = _random_qpos(model, rng, 0.6)
        mujoco.mj_kinematics(model, data)
        for side, c in chains.items():
            c.data.qpos[:] = data.qpos
            mujoco.mj_kinematics(model, c.data)
            joints, axes, site_p, site_r = np.zeros((7, 3)), np.zeros((7, 3)), np.zeros(3), np.zeros((3, 3))
            chain_fk(c._parent_xpos, c._parent_xmat.reshape(3, 3), c.geometry, c.n, c.site, data.qpos[c.coords].copy(),
                     joints, axes, site_p, site_r)
            site = model.site(f"{side}_grasp").id
            assert np.abs(site_p - data.site_xpos[site]).max() < 1e-12
            assert np.abs(site_r.ravel() - data.site_xmat[site]).max() < 1e-12
            for k, name in enumerate(ARM[side]):
                j = model.joint(name).id
                assert np.abs(joints[k] - data.xanchor[j]).max() < 1e-12
                assert np.abs(axes[k] - data.xaxis[j]).max() < 1e-12


def test_forward_kinematics_and_search_on_a_twisted_chain():
    model = mujoco.MjModel.from_xml_string(TWISTED)
    joints, rng = ["j1", "j2", "j3"], np.random.default_rng(5)
    c, data = ChainIK(model, "tip", joints), mujoco.MjData(model)
    assert np.abs(model.qpos0[7:]).max() > 0.3  # the refs are qpos0
    for i in range(60):
        data.qpos[:] = model.qpos0
        data.qpos[:3], data.qpos[3:7] = rng.normal(size=3), rng.normal(size=4)
        data.qpos[3:7] /= np.linalg.norm(data.qpos[3:7])
        data.qpos[7:] = rng.uniform(-1.0, 1.0, 3)
        mujoco.mj_kinematics(model, data)
        c.data.qpos[:] = data.qpos
        mujoco.mj_kinematics(model, c.data)
        anchors, axes, site_p, site_r = np.zeros((3, 3)), np.zeros((3, 3)), np.zeros(3), np.zeros((3, 3))
        chain_fk(c._parent_xpos, c._parent_xmat.reshape(3, 3), c.geometry, c.n, c.site, data.qpos[c.coords].copy(),
                 anchors, axes, site_p, site_r)
        tip = model.site("tip").id
        assert np.abs(site_p - data.site_xpos[tip]).max() < 1e-12
        assert np.abs(site_r.ravel() - data.site_xmat[tip]).max() < 1e-12
        for k, name in enumerate(joints):
            assert np.abs(anchors[k] - data.xanchor[model.joint(name).id]).max() < 1e-12
            assert np.abs(axes[k] - data.xaxis[model.joint(name).id]).max() < 1e-12
        start = data.qpos.copy()
        start[7:] += rng.normal(scale=0.2, size=3)
        pos, local = data.site_xpos[tip].copy(), np.array([0.0, 0.0, 1.0])
        world = data.site_xmat[tip].reshape(3, 3) @ local
        for axis in (None, (local, world)):
            new = c.solve(start, pos, axis)
            old = ik.solve(model, {"tip": ik.Target(pos=pos, axis=axis)}, start, joints)
            assert new.ok == old.ok
            if old.ok:
                assert np.abs(new.q - old.q).max() < 1e-9


@pytest.mark.parametrize("reach", ["reachable", "beyond"])
def test_the_search_is_sim_iks(robot, reach):
    """The same answers as ik.solve (position + axis targets, from a nearby start): the same verdict, and where it
    converges joint angles within 1e-9 rad. Beyond the arm's reach the best iterates, against clamped joints (the
    active set), agree within 1e-8 rad; a search that wanders its 300 iterations without settling (a quarter of the
    reachable targets from these starts) amplifies rounding, so there only the verdict is compared."""
    body, chains = robot
    model, rng = body.model, np.random.default_rng(1 if reach == "reachable" else 2)
    data, clamped = mujoco.MjData(model), 0
    for _ in range(40):
        goal = _random_qpos(model, rng, 0.4)
        data.qpos[:] = goal
        mujoco.mj_kinematics(model, data)
        start = goal.copy()
        for side, c in chains.items():
            start[c.coords] += rng.normal(scale=0.15, size=7)
            site = model.site(f"{side}_grasp").id
            pos = data.site_xpos[site] + (rng.normal(scale=0.5, size=3) if reach == "beyond" else 0.0)
            world = data.site_xmat[site].reshape(3, 3) @ BAR
            new = c.solve(start, pos, (BAR, world))
            old = ik.solve(model, {f"{side}_grasp": ik.Target(pos=pos, axis=(BAR, world))}, start, ARM[side])
            assert new.ok == old.ok
            if old.ok or reach == "beyond":
                assert np.abs(new.q - old.q).max() < (1e-9 if old.ok else 1e-8)
                assert new.residual == pytest.approx(old.residual, rel=1e-6, abs=1e-12)
            lo, hi = c.limits[:, 0], c.limits[:, 1]
            clamped += bool(np.any((new.q[c.coords] <= lo) | (new.q[c.coords] >= hi)))
    if reach == "beyond":
        assert clamped > 5  # the limits' active set was exercised


def test_a_position_only_target(robot):
    body, chains = robot
    model, data = body.model, mujoco.MjData(body.model)
    data.qpos[:] = _random_qpos(model, np.random.default_rng(0), 0.3)
    mujoco.mj_kinematics(model, data)
    pos = data.site_xpos[model.site("r_grasp").id].copy()
    start = data.qpos.copy()
    start[chains["r"].coords] += 0.1
    new = chains["r"].solve(start, pos)
    old = ik.solve(model, {"r_grasp": pos}, start, ARM["r"])
    assert new.ok and old.ok and np.abs(new.q - old.q).max() < 1e-9


def test_bad_chains_fail_with_one_clear_line(robot):
    body, _ = robot
    with pytest.raises(ValueError, match="hinge"):
        ChainIK(body.model, "r_grasp", ["root"])
    with pytest.raises(ValueError, match="child body"):
        ChainIK(body.model, "r_grasp", ["r_shoulder_pitch", "r_elbow_pitch"])
    with pytest.raises(ValueError, match="rigidly"):
        ChainIK(body.model, "l_grasp", ARM["r"])
    chain = ChainIK(body.model, "r_grasp", ARM["r"])
    with pytest.raises(ValueError, match="damping"):
        chain.solve(body.model.qpos0, np.zeros(3), damping=0.0)
    with pytest.raises(ValueError, match="axis target"):
        chain.solve(body.model.qpos0, np.zeros(3), (BAR, np.zeros(3)))
    with pytest.raises(ValueError, match="axis target"):
        chain.solve(body.model.qpos0, np.zeros(3), (BAR, [np.nan, 0.0, 1.0]))
