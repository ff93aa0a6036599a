"""The bench's sampling profiler: samples charged to the layer that spent the time."""

import signal
import time

import numpy as np
import pytest

from shintai.core import Loop, Module, Recorder
from shintai.core.benchmarks import NullBody
from shintai.scenarios.sampling import LAYERS, line, sampled

pytestmark = pytest.mark.skipif(not hasattr(signal, "SIGPROF"), reason="needs SIGPROF")


def burn(seconds: float) -> None:
    end = time.process_time() + seconds
    while time.process_time() < end:
        pass


class HeavyBody(NullBody):
    def step(self):
        burn(6e-3)  # the "physics": a plain function called from the body's step (burns longer than a 4 ms
        # scheduler tick, at which a loaded kernel delivers SIGPROF: shorter ones alias with it)
        super().step()


class HeavyModule(Module):
    def update(self, snapshot):
        burn(18e-3)
        self.log(snapshot["t"], x=snapshot["x"])
        return {"u": np.zeros(8)}


def test_samples_go_to_the_layer_that_spent_the_time():
    loop = Loop(HeavyBody(), [HeavyModule("heavy")], recorder=Recorder())
    with sampled(0.001) as samples:
        loop.run(0.02)  # 20 steps, ≈0.48 s of CPU
    summary = samples.summary()
    shares = summary["layers"]
    assert list(shares) == list(LAYERS) and sum(shares.values()) == pytest.approx(1.0, abs=0.01)
    assert summary["samples"] > 100
    # three times the CPU in the module as in the body's step, little anywhere else
    assert shares["control"] > shares["physics"] > 0.1
    assert shares["control"] + shares["physics"] > 0.8
    assert "core/runtime.py:step" in " ".join(summary["top"])  # the innermost frame in shintai's own source
    assert line(summary).startswith(f"{summary['samples']} samples: physics")


def test_sampling_stops_and_restores_the_handler():
    before = signal.getsignal(signal.SIGPROF)
    with sampled(0.001) as samples:
        burn(0.05)
    assert signal.getsignal(signal.SIGPROF) == before and signal.getitimer(signal.ITIMER_PROF) == (0.0, 0.0)
    n = samples.count
    burn(0.02)
    assert samples.count == n and samples.layers["other"] == n


def test_nested_sampling_feeds_the_outer_and_gives_it_back_its_timer():
    before = signal.getsignal(signal.SIGPROF)
    with sampled(0.001) as outer:
        burn(0.03)
        with sampled(0.001) as inner:
            burn(0.05)
        n_inner, n_outer = inner.count, outer.count
        assert signal.getitimer(signal.ITIMER_PROF)[1] == pytest.approx(0.001)  # the outer's timer runs again
        burn(0.03)
    assert n_inner > 10 and n_outer >= n_inner  # the inner block's samples reached the outer too
    assert outer.count > n_outer and inner.count == n_inner  # after the inner block only the outer samples
    assert signal.getsignal(signal.SIGPROF) == before and signal.getitimer(signal.ITIMER_PROF) == (0.0, 0.0)


def test_figures_drawn_outside_the_loop_count_as_plotting():
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    with sampled(0.001) as samples:
        end = time.process_time() + 0.15
        while time.process_time() < end:
            fig, ax = plt.subplots()
            ax.plot(np.arange(2000.0), np.sin(np.arange(2000.0)))
            fig.canvas.draw()
            plt.close(fig)
    shares = samples.summary()["layers"]
    assert shares["plotting"] > 0.8 and shares["control"] == 0


def test_a_clock_times_and_counts_a_wrapped_method():
    from shintai.scenarios.sampling import Clock

    class Counter:
        def __init__(self):
            self.n = 0

        def add(self, k):
            self.n += k
            return self.n

    c = Counter()
    clock = Clock([c], "add")
    assert [c.add(2), c.add(3)] == [2, 5] and clock.calls == 2 and clock.seconds > 0.0
