"""A quasi-static linear plant x = G ρ + c for the online search index (seed 000 §2.5, spec §2.5 [DERIVED]),
and the update rules of Eqs. 2.14 and 2.15 run on it in the shared Loop."""

from __future__ import annotations

import numpy as np

from shintai.core.runtime import Body, Loop, declare
from shintai.core.search_index import (MatrixGain, QuadraticCost, SearchIndex, SearchIndexModule, StabilityMonitor,
                                       learning_index_chain)


class LinearPlant(Body):
    """Quasi-static plant x = G ρ + c: the locally linear model of spec §2.5 [DERIVED].

    The command channel ``rho`` sets ρ; after a step the snapshot shows the x it produced.
    """

    channels = declare("rho")

    def __init__(self, G, c, rho0, dt: float = 1.0):
        self.G = np.atleast_2d(np.asarray(G, dtype=float))
        self.c = np.atleast_1d(np.asarray(c, dtype=float))
        self.rho = np.atleast_1d(np.asarray(rho0, dtype=float)).copy()
        self.dt, self.t = dt, 0.0
        self.x = self.G @ self.rho + self.c

    def snapshot(self):
        return {"t": self.t, "x": self.x.copy(), "rho": self.rho.copy()}

    def apply(self, command):
        if "rho" in command:
            self.rho = np.asarray(command["rho"], dtype=float).copy()

    def step(self):
        self.x = self.G @ self.rho + self.c
        self.t += self.dt


def run_control_index(G, c, x_d, rho0, sgn, A, steps: int):
    """Run Eq. 2.14 through the Loop; return the error and ρ per step, and the monitor."""
    law = SearchIndex(rho0, MatrixGain(A), sgn=sgn, x_d=x_d)
    loop = Loop(LinearPlant(G, c, rho0), [SearchIndexModule(law, lambda s: s["x"], "rho", name="osi")])
    errors, rhos = [], []

    def keep(snap):
        errors.append(snap["x"] - x_d)
        rhos.append(snap["rho"])

    loop.run(steps * loop.body.dt, every={1: keep})
    errors, rhos = np.array(errors), np.array(rhos)
    monitor = StabilityMonitor()
    for e, d in zip(errors[1:], np.diff(rhos, axis=0)):
        monitor.observe(error=e, drho=d)
    return errors, rhos, monitor


def run_learning_index(G, c, x_d, rho0, W, rate: float, steps: int):
    """Gain learning Eq. 2.15 with f_l = (∂x/∂ρ)ᵀ ∂J/∂x on the same plant; returns J per step."""
    cost = QuadraticCost(np.atleast_2d(W), np.atleast_1d(x_d))
    G = np.atleast_2d(G)
    law = SearchIndex(rho0, rate * np.eye(np.size(rho0)), gradient=lambda x, rho: learning_index_chain(cost, x, G))
    loop = Loop(LinearPlant(G, c, rho0), [SearchIndexModule(law, lambda s: s["x"], "rho", name="learn")])
    J = []
    loop.run(steps * loop.body.dt, every={1: lambda snap: J.append(cost(snap["x"]))})
    J = np.array(J)
    monitor = StabilityMonitor()
    for j in J:
        monitor.observe(J=j)
    return J, monitor
