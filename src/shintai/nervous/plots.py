"""The figures of the nervous experiments (``nervous.cla-teach``, ``nervous.clients``, ``nervous.fig-c1``), drawn
with ``ctx.figure``."""

from __future__ import annotations


def plot_cla_teach(ctx, runs) -> None:
    """``nervous.cla-teach``: shoulder roll and whole-spine angle of each variant, the taught postures marked."""
    with ctx.figure("cla_teach", 2, 1, figsize=(8, 6.5), sharex=True) as (fig, ax):
        for i, (variant, run) in enumerate(runs.items()):
            t, roll, whole = run["trace"]
            ax[0].plot(t, roll, color=f"C{i}", lw=0.6, alpha=0.6)
            ax[0].plot([r[2] for r in run["rows"]], [r[3] for r in run["rows"]], "o", color=f"C{i}",
                       label=f"{variant} rotadjust (end of each hold)")
            for j, axis in enumerate(("roll", "pitch", "yaw")):
                ax[1].plot(t, whole[:, j], color=f"C{j + 2}", ls="-" if variant == "without" else ":", lw=1,
                           label=f"{axis}, {variant} rotadjust")
        for k, truth in enumerate(runs["without"]["truth"]):
            ax[1].plot([runs["without"]["rows"][0][2]] * 3, truth, "k_", ms=12, label="taught" if k == 0 else None)
        ax[0].axhline(0, color="0.6", lw=0.8)
        ax[0].set_ylim(-4, 14)
        ax[0].set_ylabel("shoulder roll [deg]\n(clavicle accelerometer)")
        ax[1].set_ylabel("whole-spine angle [deg]\n(simulation truth)")
        ax[1].set_xlabel("body time [s] (teaching by hand until the seat tilts, then playback)")
        ax[0].legend(fontsize=7)
        ax[1].legend(fontsize=6, ncol=3)


def plot_clients(ctx, seen, watchers: int) -> None:
    """``nervous.clients``: the fraction of packets each watcher received, the commander's reply times."""
    with ctx.figure("clients", 1, 2, figsize=(10, 3.8)) as (fig, ax):
        names = [f"watcher{i}" for i in range(watchers)]
        ax[0].bar(names, [seen[n]["received"] / max(seen[n]["span"], 1) for n in names])
        ax[0].set_ylim(0.9, 1.005)
        ax[0].set_ylabel("state lines received / packets")
        rt = seen["commander"]["round_trip_ms"]
        ax[1].plot(rt, "o-")
        ax[1].set_xlabel("commander's propocmd #")
        ax[1].set_ylabel("reply time [ms]")


def plot_fig_c1(ctx, curves, targets) -> None:
    """``nervous.fig-c1``: Fig. C.1's position and velocity per run, the arm joint, ``targets`` (time [ms], position)."""
    with ctx.figure("fig_c1", 2, 1, figsize=(8, 6.5), sharex=True) as (fig, ax):
        styles = {"minjerksequence": ("C0", "-"), "minjerk": ("C1", "--"), "turning": ("C2", ":")}
        for label, (t, x, v, measured) in curves.items():
            color, ls = styles[label]
            ax[0].plot(1e3 * t, x, ls, color=color, label=f"{label} target")
            ax[1].plot(1e3 * t, v, ls, color=color, label=label)
        t, x, v, measured = curves["minjerksequence"]
        ax[0].plot(1e3 * t, measured, color="0.4", lw=0.8, label="minjerksequence, arm joint (servo)")
        for tk, xk in targets:
            ax[0].plot(tk, xk, "ko", ms=4)
            ax[1].axvline(tk, color="0.85", lw=0.8)
        ax[0].plot(0, 0, "ko", ms=4, label="App. C.2.2 targets")
        ax[0].set_ylabel("position [deg]")
        ax[1].set_ylabel("velocity [deg/s]")
        ax[1].set_xlabel("time since the targets were sent [ms]")
        ax[0].legend(fontsize=7)
        ax[1].legend(fontsize=7)
