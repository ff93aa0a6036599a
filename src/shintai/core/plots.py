"""The figures of the core experiments (``core.minjerk``, ``core.search-index``), drawn with ``ctx.figure``."""

from __future__ import annotations

import numpy as np


def plot_minjerk(ctx, samples) -> None:
    """``core.minjerk``: position, velocity and acceleration of the re-targeted player (each stays continuous)."""
    t = np.array([s[0] for s in samples])
    with ctx.figure("minjerk", 3, 1, figsize=(8, 7), sharex=True) as (fig, ax):
        for i, label in enumerate(("position", "velocity", "acceleration")):
            ax[i].plot(t, np.array([s[1 + i] for s in samples]), lw=1)
            ax[i].set_ylabel(label)
        ax[2].set_xlabel("t [s] (re-targeted mid-motion: every curve stays continuous)")


def plot_search_index(ctx, e1, r1, e_wrong, e2, J, scalar) -> None:
    """``core.search-index``: error (Eq. 2.22), increments (Eq. 2.28), learning index (Eq. 2.33), steps in (ρ, x)."""
    with ctx.figure("search_index", 2, 2, figsize=(10, 7)) as (fig, ax):
        k = np.arange(len(e1))
        eps = 1e-16  # exact zeros (converged to machine precision) drawn at the floor of the log axis
        ax[0, 0].semilogy(k, np.maximum(np.abs(e1[:, 0]), eps), label="scalar, right sign")
        ax[0, 0].semilogy(k, np.maximum(np.abs(e2[:, 0]), eps), label="coupled x₁")
        ax[0, 0].semilogy(k, np.maximum(np.abs(e2[:, 1]), eps), label="coupled x₂")
        ax[0, 0].semilogy(np.arange(len(e_wrong)), np.abs(e_wrong[:, 0]), "r--", label="scalar, wrong sign")
        ax[0, 0].set(xlabel="step k", ylabel="|x − x_d|", title="error (Eq. 2.22)")
        ax[0, 0].legend(fontsize=8)
        ax[0, 1].semilogy(k[1:], np.maximum(np.abs(np.diff(r1[:, 0])), eps), label="scalar")
        ax[0, 1].set(xlabel="step k", ylabel="|ρ_{k+1} − ρ_k|", title="increments (Eq. 2.28)")
        ax[1, 0].semilogy(np.arange(len(J)), np.maximum(J, eps))
        ax[1, 0].set(xlabel="step k", ylabel="J(x_k)", title="learning index (Eq. 2.33)")
        g, c, xd = scalar["G"][0][0], scalar["c"][0], scalar["x_d"][0]
        rr = np.linspace(min(r1[:, 0].min(), 0) - 0.5, max(r1[:, 0].max(), 0) + 0.5, 50)
        ax[1, 1].plot(rr, g * rr + c, "k-", lw=0.8, label="plant x(ρ)")
        ax[1, 1].axhline(xd, color="g", lw=0.8, label="x_d")
        ax[1, 1].plot(r1[:8, 0], e1[:8, 0] + xd, "o-", ms=3, label="(ρ_k, x_k)")
        ax[1, 1].set(xlabel="ρ", ylabel="x", title="steps in (ρ, x) space (Fig. 2.14)")
        ax[1, 1].legend(fontsize=8)
