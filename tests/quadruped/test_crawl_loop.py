"""The batched crawl on the shared runtime: CrawlBody (one step = one walking cycle), the action network
as the set-point stage and the swing order as the next (episode.py, issue 12 item 6)."""

import numpy as np
import pytest

from shintai.core.runtime import ChannelError, Loop, Module
from shintai.quadruped import constants as C
from shintai.quadruped import fitness as F
from shintai.quadruped import robot as R
from shintai.quadruped import training as T
from shintai.quadruped import world as W
from shintai.quadruped.episode import (DISPLACEMENT, ActionModule, CrawlBody, GenomePolicy, SwingOrderModule,
                                       action_inputs, crawl_loop, obstacle_features, rollout)
from shintai.quadruped.swing_order import CRAWL, ORDERS


def reference_rollout(envs, policy, order_policy=None, max_cycles=C.MAX_CYCLES):
    """The walking-cycle loop written out by hand (the form rollout had before the Loop)."""
    n = len(envs)
    state, active = R.CrawlState.initial(n), np.ones(n, bool)
    cycles, reached, failed = np.zeros(n, int), np.zeros(n, bool), np.zeros(n, bool)
    for k in range(max_cycles):
        rows = np.flatnonzero(active)
        if len(rows) == 0:
            break
        st, env = state.take(rows), envs.take(rows)
        zr = R.body_height(st.pose, st.feet, env)
        command = np.clip(np.asarray(policy(action_inputs(st, zr, env), rows), float), *C.COMMAND_RANGE)
        order = np.full(len(rows), CRAWL) if order_policy is None else np.asarray(order_policy(zr, command))
        out = R.crawl_cycle(st, command, ORDERS[order], zr, env)
        ok = ~out.failed
        state.put(rows[ok], out.state.take(ok))
        cycles[rows] = k + 1
        failed[rows] |= out.failed
        reached[rows[ok]] = W.length(env.destination[ok] - out.state.pose[ok, :2]) <= C.GOAL_RADIUS
        active[rows[out.failed]] = False
        active[rows[ok & reached[rows]]] = False
    return cycles, reached, envs.destination - state.pose[:, :2]


@pytest.mark.parametrize("stage", ["action", "free"])
def test_the_loop_gives_the_hand_written_cycle_loop_bit_for_bit(stage):
    envs = T.training_envs(8)
    policy = GenomePolicy(F.ACTION_NET, T.load_action(stage=stage)[None], len(envs))
    order = T.load_order() if stage == "free" else None
    ep = rollout(envs, policy, order)
    cycles, reached, error = reference_rollout(envs, policy, order)
    assert np.array_equal(ep.cycles, cycles) and np.array_equal(ep.reached, reached)
    assert np.array_equal(ep.final_error, error)


def test_the_swing_order_stage_sees_the_clipped_displacement_of_the_same_cycle():
    seen = []

    def action(x, rows):
        return np.tile([1.0, 1.0, 1.0], (len(rows), 1))  # far outside the range: clipped

    def order(zr, command):
        seen.append(command.copy())
        return np.full(len(zr), CRAWL)

    ep = rollout(W.EnvBatch.of([W.scenario_421()]), action, order, max_cycles=2)
    assert len(seen) == ep.cycles[0]
    assert np.array_equal(seen[0][0], np.asarray(C.COMMAND_RANGE[1]))
    assert np.array_equal(ep.commands[0, 0], np.asarray(C.COMMAND_RANGE[1]))


def test_one_step_is_one_cycle_and_the_snapshot_is_taken_once_per_cycle():
    calls = []

    class Counting:
        def reset(self, envs):
            pass

        def __call__(self, k, rows, state, envs):
            calls.append(k)
            return obstacle_features(state.pose, envs)

    body = CrawlBody(W.EnvBatch.of([W.scenario_421()]), max_cycles=3, perception=Counting())
    policy = GenomePolicy(F.ACTION_NET, T.load_action()[None], 1)
    steps = crawl_loop(body, policy).run(3 * body.dt, until=lambda _: body.done)
    assert steps == 3 and body.t == 3.0 and calls == [0, 1, 2]
    assert body.finish().cycles[0] == 3


def test_the_order_is_a_set_channel_with_one_writer():
    body = CrawlBody(W.EnvBatch.of([W.scenario_421()]), max_cycles=1)
    policy = GenomePolicy(F.ACTION_NET, T.load_action()[None], 1)

    class SecondOrder(Module):
        def update(self, snapshot):
            return {"order": np.full(1, CRAWL)}

    loop = Loop(body, stages=[[ActionModule(policy)], [SwingOrderModule(), SecondOrder()]], channels=[DISPLACEMENT])
    with pytest.raises(ChannelError, match="two writers"):
        loop.step()
