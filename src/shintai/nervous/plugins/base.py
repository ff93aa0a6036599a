"""The plugin of nervous (seed 003 §6.3.4): a constructor, a routine run once per sensor packet, a destructor.

§6.3.4: "``plugin`` 構造体を定義し、メンバ関数にコンストラクタ・処理ルーチン・デストラクタを定義し、動作開始の指示
があるとコンストラクタ関数を実行し、センサ情報が入力されるたびに処理ルーチン関数を一度実行し、動作終了の指示が
あるとデストラクタ関数を実行する" — on ``start`` the constructor runs (:meth:`Plugin.start`), every sensor
packet the routine runs once (:meth:`Plugin.process`), on ``stop`` the destructor (:meth:`Plugin.stop`).
``create-plugin INSTANCE PLUGIN ARGS…`` makes the object (``__init__``); C.2.2: a line whose first word is
the instance's name goes to it (:meth:`Plugin.command` → the ``cmd_<method>`` of that name).

What a routine returns (§6.2.4: "並列に出力される自律機能モジュールからのアクチュエータ情報の出力は，絶対的な値では
なく現在値との差分とし，それらを現在値に足し合わせる形にした"): a plugin of kind :data:`ADD` returns a
*difference* added to the target this packet (all differences sum); a plugin of kind :data:`SET` returns the
target itself (the seqplugin's ``target_av``, App. C.2.2), at most one running at a time. ``None``: nothing
this packet. Differences are re-sent every packet (a plugin keeps its own accumulated offset): the seqplugin
rewrites the target every packet, so a one-off change would be lost at the next one.
"""

from __future__ import annotations

from typing import Any

import numpy as np

from shintai.core.runtime import ADD, SET
from shintai.nervous.protocol import ProtocolError

__all__ = ["ADD", "SET", "CommandError", "Plugin"]


class CommandError(ProtocolError):
    """A plugin command that cannot be done: ``error: <message>``, nothing changed."""


class Plugin:
    """Base class of nervous plugins (see the module docstring). Subclasses set :attr:`kind` and
    :attr:`summary`, and define ``cmd_<method>(self, args, call) -> str | None`` for their methods (a
    method name's '-' is '_' here); the first docstring line of each is its help."""

    kind: str = ADD
    summary: str = ""

    def __init__(self, host, instance: str, args: list[str]):
        if args:
            raise CommandError(f"{type(self).__name__} takes no creation arguments, got {' '.join(map(str, args))}")
        self.host = host
        self.instance = instance
        self.running = False

    def start(self, state: dict[str, Any]) -> None:
        """The constructor of §6.3.4: run when the plugin is started."""

    def process(self, state: dict[str, Any]) -> np.ndarray | None:
        """The routine of §6.3.4: once per sensor packet while running."""
        return None

    def stop(self) -> None:
        """The destructor of §6.3.4: run when the plugin is stopped (or unloaded, or it failed)."""

    def command(self, method: str, args: list, call) -> str | None:
        attr = "cmd_" + method.replace("-", "_")
        handler = getattr(self, attr, None) if attr.isidentifier() else None
        if handler is None:
            raise CommandError(f"{self.instance}: unknown method {method!r} (methods: {', '.join(self.methods())})")
        return handler(args, call)

    @classmethod
    def methods(cls) -> dict[str, str]:
        """method name → the first line of its docstring."""
        out = {}
        for attr in dir(cls):
            if attr.startswith("cmd_"):
                doc = (getattr(cls, attr).__doc__ or "").strip().splitlines()
                out[attr[4:].replace("_", "-")] = doc[0] if doc else ""
        return out

    def describe(self) -> str:
        """One line on the plugin's state (``plugins`` lists it)."""
        return ""

    def cmd_help(self, args, call) -> str:
        """list this plugin's methods"""
        return "; ".join(f"{name}: {doc}" for name, doc in self.methods().items())


def check_kind(kind: str) -> str:
    if kind not in (ADD, SET):
        raise ValueError(f"plugin kind must be {ADD!r} or {SET!r}, got {kind!r}")
    return kind
