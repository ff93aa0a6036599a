"""Finding plugins by name (``load-plugin NAME``) or by file (``load-plugin PATH.py``).

The thesis's plugins are shared objects loaded and unloaded while nervous runs (§6.4.2: "プラグインはダイナ
ミックロード・アンロードが可能な実装 (so … dll …) になっているので、システム全体は停止せずにソフトウェアの変更・
試行が可能"). Here a plugin is a :class:`~shintai.nervous.plugins.base.Plugin` subclass, found

* by name: the ``shintai.nervous.plugins`` entry-point group — shintai declares its own there, and any
  installed package can add plugins (``[project.entry-points."shintai.nervous.plugins"] name =
  "module:Class"``); shintai's own are also known without installed metadata (:data:`BUILTIN`), the thesis's
  file names (``seqplugin`` …) as aliases;
* by file: ``load-plugin path/to/file.py`` imports that file, whose plugin is the ``PLUGIN`` attribute or
  its one Plugin subclass. A file path is code to run, so it is honoured only from the start-up file
  (``--rc``) and for names found in the server's ``--plugin-dir`` folders, never as a path sent by a client.

Modules:

diagnosis — What the autonomous diagnosis plugins of §6.1.2 share: per-muscle readings over time and the checks …
log — ``log`` — logging (App. C.3.6 ``logplugin.c``, "ログ保存に関するプラグイン"): every N-th sensor packet as one line …
null — ``null`` — the test plugin (App. C.3.6 ``nullplugin.c``, "テスト用プラグイン"): it adds nothing and counts the …
overcurrent — ``overcurrent`` — over-current detection and motor stop (§6.1.2: "過電流検出・モータ停止機能")
rotadjust — ``rotadjust`` — posture control by accelerometer (App. C.3.6 ``rotadjustplugin.c``, "加速度センサによる姿勢 …
sensorfault — ``sensorfault`` — tension-sensor and encoder fault detection (§6.1.2: "張力センサ故障検出機能", "エンコーダ故障検出機能")
sequence — ``sequence`` — the seqplugin of nervous (seed 003 §6.3.4, App. C.2.2) on …
servo — ``servo`` — the servo parameters of the body (App. C.3.6 ``servoplugin.c``, "サーボモータに関するプラグイン"; …
slack — ``slack`` — muscle slack detection and take-up (§6.1.2: "筋のたるみ検出・修復機能")
smooth — ``smooth`` — "急激な指令値の変化を滑らかにするプラグイン" (App. C.3.6 ``smoothplugin.c``): the target a plugin set this …
"""

from __future__ import annotations

import importlib
import importlib.metadata
import importlib.util
import sys
from pathlib import Path

from shintai.nervous.plugins.base import Plugin, check_kind

GROUP = "shintai.nervous.plugins"
BUILTIN = {
    "sequence": "shintai.nervous.plugins.sequence:Sequence",
    "smooth": "shintai.nervous.plugins.smooth:Smooth",
    "log": "shintai.nervous.plugins.log:Log",
    "servo": "shintai.nervous.plugins.servo:Servo",
    "null": "shintai.nervous.plugins.null:Null",
    "rotadjust": "shintai.nervous.plugins.rotadjust:RotAdjust",
    "slack": "shintai.nervous.plugins.slack:Slack",
    "overcurrent": "shintai.nervous.plugins.overcurrent:OverCurrent",
    "sensorfault": "shintai.nervous.plugins.sensorfault:SensorFault",
}
ALIASES = {"seqplugin": "sequence", "smoothplugin": "smooth", "logplugin": "log", "servoplugin": "servo",
           "nullplugin": "null", "rotadjustplugin": "rotadjust"}  # App. C.3.6 file names


class PluginNotFound(LookupError):
    def __str__(self) -> str:
        return self.args[0]


def entry_points() -> dict[str, str]:
    """name → "module:Class" of every installed plugin (entry points override nothing of shintai's own)."""
    found = {ep.name: ep.value for ep in importlib.metadata.entry_points(group=GROUP)}
    return {**found, **BUILTIN}


def _load(target: str, name: str) -> type[Plugin]:
    module_name, _, attr = target.partition(":")
    module = importlib.import_module(module_name)
    cls = getattr(module, attr, None) if attr else None
    return _checked(cls, name, target)


def _checked(cls, name: str, where: str) -> type[Plugin]:
    if not (isinstance(cls, type) and issubclass(cls, Plugin)):
        raise PluginNotFound(f"plugin {name!r}: {where} is not a nervous Plugin class")
    check_kind(cls.kind)
    return cls


def from_file(path: str | Path) -> type[Plugin]:
    """Import a plugin from a ``.py`` file (trusted callers only, see the module docstring)."""
    path = Path(path)
    if path.suffix != ".py" or not path.is_file():
        raise PluginNotFound(f"plugin file {str(path)!r}: no such .py file")
    module_name = f"shintai_nervous_plugin_{path.stem}_{abs(hash(str(path.resolve())))}"
    spec = importlib.util.spec_from_file_location(module_name, path)
    module = importlib.util.module_from_spec(spec)
    sys.modules[module_name] = module
    try:
        spec.loader.exec_module(module)
    except Exception:
        sys.modules.pop(module_name, None)
        raise
    cls = getattr(module, "PLUGIN", None)
    if cls is None:
        found = [v for v in vars(module).values()
                 if isinstance(v, type) and issubclass(v, Plugin) and v is not Plugin and v.__module__ == module_name]
        if len(found) != 1:
            raise PluginNotFound(f"plugin file {path.name}: define PLUGIN = YourClass (found {len(found)} classes)")
        cls = found[0]
    return _checked(cls, path.stem, str(path))


def canonical(name: str) -> str:
    """The plugin name a thesis file name stands for (``seqplugin`` → ``sequence``: C.2.2's
    ``load-plugin seqplugin`` is followed by ``create-plugin sequence sequence``)."""
    return ALIASES.get(name, name)


def find(name: str, plugin_dirs=()) -> type[Plugin]:
    """A plugin class by name: an entry point (or shintai's own), an alias, or ``NAME.py`` in a plugin dir."""
    name = canonical(name)
    target = entry_points().get(name)
    if target is not None:
        return _load(target, name)
    for folder in plugin_dirs:
        candidate = Path(folder) / f"{name}.py"
        if candidate.is_file():
            return from_file(candidate)
    known = sorted(entry_points()) + sorted(ALIASES)
    raise PluginNotFound(f"no plugin named {name!r} (known: {', '.join(known)}; or NAME.py in a --plugin-dir)")
