"""Issue 26's sign chain on a short common-mode foot-pitch step (vboard.sign_chain): the signs each link has on the
code as it stands (the CoM read against the true vertical), so that a change of the chain shows here."""

import numpy as np
import pytest

from shintai.humanoid.vboard.sign_chain import LINKS, probe

# each link's sign at +0.2 s after a +1° toes-down step (notes/vboard-plant-id.md): the scooter answers forward at
# first (+0.05 s) and then rolls back with the rider's CoM lag, p_d and τᵈ to the heel and δ toes-up
SIGN_AT_200MS = {"cmd_pitch": 1, "sole_pitch": -1, "pad_pitch": -1, "wheel_speed": -1, "v": -1, "acc": -1,
                 "com_rel": -1, "p_d": -1, "tau_d": -1, "delta": -1}
SIGN_AT_50MS = {"cmd_pitch": 1, "sole_pitch": 1, "pad_pitch": 1, "wheel_speed": 1, "v": 1, "com_rel": -1}


@pytest.fixture(scope="module")
def short_probe():
    return probe(after=0.25)


def test_every_link_is_read(short_probe):
    assert set(SIGN_AT_200MS) == {k for k, *_ in LINKS}
    assert not short_probe["fallen"]


@pytest.mark.parametrize("link", sorted(SIGN_AT_200MS))
def test_sign_at_200ms(short_probe, link):
    x = short_probe["readings"][f"chain_{link}_200ms"]
    assert np.isfinite(x) and np.sign(x) == SIGN_AT_200MS[link], (link, x)


@pytest.mark.parametrize("link", sorted(SIGN_AT_50MS))
def test_sign_at_50ms(short_probe, link):
    x = short_probe["readings"][f"chain_{link}_50ms"]
    assert np.sign(x) == SIGN_AT_50MS[link], (link, x)


def test_without_the_step_nothing_differs(short_probe):
    tau, diff = short_probe["tau"], short_probe["diff"]
    before = tau < -0.002  # the step fires on the tick at t_step (its snapshot time may be t_step − ε)
    assert before.sum() > 100
    for k, *_ in LINKS:
        assert np.allclose(diff[k][before], 0.0, atol=1e-9), k
