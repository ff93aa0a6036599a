"""Every body's MuJoCo model, exported as MJCF that opens in MuJoCo's own ``simulate`` viewer and any
MuJoCo tool (``shintai model ID --out DIR``, ``shintai model --list``).

A body package registers its models in ``shintai/<body>/models.py`` with :func:`model`: an id, a one-line
summary and a function building the model (an ``MjSpec``, an MJCF string or file, or a :class:`MujocoBody`
built from a spec). :func:`export` writes ``<DIR>/<id>.xml``; models here carry no external asset files
(meshes are inline vertex lists, textures builtin), so the XML is the whole model.
"""

from __future__ import annotations

import importlib
from collections.abc import Callable
from dataclasses import dataclass
from pathlib import Path

import mujoco

import shintai
from shintai.sim.body import MujocoBody


class UnknownModel(KeyError):
    """A model id that no body registered."""


@dataclass(frozen=True)
class ModelEntry:
    id: str
    summary: str
    build: Callable[[], mujoco.MjSpec | str | MujocoBody]


MODELS: dict[str, ModelEntry] = {}


def model(id: str, summary: str):
    """Decorator registering a model builder under ``id`` (e.g. ``"spine.cla"``)."""

    def register(fn):
        MODELS[id] = ModelEntry(id, summary, fn)
        return fn

    return register


def load_models() -> dict[str, ModelEntry]:
    """Import every body's ``models`` module (once) and return the registry."""
    for name in shintai.body_modules("models"):
        importlib.import_module(name)
    return MODELS


def to_spec(built) -> mujoco.MjSpec:
    """The MjSpec of what a builder returned (an MJCF string or path is parsed)."""
    if isinstance(built, MujocoBody):
        if built.spec is None:
            raise TypeError("a MujocoBody built from a compiled MjModel cannot be exported; build it from an MjSpec")
        return with_model_values(built.spec, built.model)
    if isinstance(built, mujoco.MjSpec):
        return built
    if isinstance(built, str) and built.lstrip().startswith("<"):
        return mujoco.MjSpec.from_string(built)
    if isinstance(built, (str, Path)):
        return mujoco.MjSpec.from_file(str(built))
    raise TypeError(f"a model builder returned {type(built).__name__}; expected an MjSpec, MJCF or a MujocoBody")


def with_model_values(spec: mujoco.MjSpec, model: mujoco.MjModel) -> mujoco.MjSpec:
    """``spec`` with what its builder set on the compiled ``model`` afterwards: keyframes (the posture a
    scene starts in) and equality data (the relative poses of holds welded where the robot sits)."""
    for key in spec.keys:
        k = model.key(key.name)
        key.qpos, key.qvel, key.act, key.ctrl = k.qpos, k.qvel, k.act, k.ctrl
        key.mpos, key.mquat, key.time = k.mpos, k.mquat, float(k.time[0])
    for i, eq in enumerate(spec.equalities):
        eq.data, eq.active = model.eq_data[i], bool(model.eq_active0[i])
    return spec


def compiled(model_id: str) -> tuple[mujoco.MjSpec, mujoco.MjModel]:
    entry = load_models().get(model_id)
    if entry is None:
        raise UnknownModel(f"unknown model {model_id!r} (see `shintai model --list`)")
    spec = to_spec(entry.build())
    return spec, spec.compile()


def export(model_id: str, out: str | Path) -> Path:
    """Write ``<out>/<model_id>.xml``; returns its path."""
    spec, _ = compiled(model_id)
    out = Path(out)
    out.mkdir(parents=True, exist_ok=True)
    path = out / f"{model_id}.xml"
    path.write_text(spec.to_xml())
    return path
