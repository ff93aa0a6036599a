"""What the autonomous diagnosis plugins of §6.1.2 share: per-muscle readings over time and the checks that
they can run on this robot.

§6.1.2: "不完全性に対応するために、センサの状態を常に監視し、自己状態を診断する系を持つ事が有効である" — the
robot is never assumed whole ("全てのセンサ・アクチュエータが正常な状態である日は少ない"); its examples: slack
detection and take-up, over-current detection and motor stop, tension-sensor and encoder fault detection
(and on-body LAN hang recovery, which a simulation has no counterpart of). §6.4.2 places such modules in
any layer; here they are nervous plugins. The thesis gives no threshold: each is chosen and says why.
"""

from __future__ import annotations

from shintai.nervous.plugins.base import CommandError
from shintai.nervous.protocol import number


def require(host, plugin: str, *sensors: str) -> None:
    """A diagnosis plugin needs per-DOF readings of these sensors."""
    missing = [s for s in sensors if host.description.sensor(s) is None
               or host.description.sensor(s).size != host.description.n]
    if missing:
        raise CommandError(f"{plugin}: needs a per-muscle {' and '.join(missing)} reading; "
                           f"{host.description.robot} has none")


def parameters(plugin: str, args, defaults: dict, limits: dict) -> dict:
    """``key=value`` creation arguments over the defaults, each in its range."""
    p = dict(defaults)
    for arg in args:
        key, _, value = str(arg).partition("=")
        if key not in limits:
            raise CommandError(f"{plugin}: unknown argument {str(arg)[:40]!r} (keys: {', '.join(limits)})")
        p[key] = number(value, f"{plugin} {key}", *limits[key])
    return p


def names(host, indices) -> str:
    return " ".join(host.description.names[i] for i in indices)
