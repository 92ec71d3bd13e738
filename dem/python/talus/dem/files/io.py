"""Checkpoints: Yade's ``O.save``, ``O.load``, ``O.saveTmp``, ``O.loadTmp`` for Talus scenes.

A checkpoint is an HDF5 file (see ``docs/dem-io.md`` for its layout) holding everything the
C++ core needs to continue a run bit-identically: clock, materials, every body array, the
periodic cell and the contact list with its full history. It is written atomically (temporary
file, sync, rename): a failed save raises :class:`CheckpointError` and leaves the previous file
untouched.

Engines are Python objects and are not part of the C++ state. ``save`` stores the engine list
as JSON beside the state (each engine's class and constructor parameters, its ``dead`` flag
and its counters, such as a PyRunner's ``iterLast``), and ``load`` rebuilds it when every engine
is a Talus engine whose parameters could be written. A PyRunner whose command is a Python
callable cannot be written to a file: ``save`` warns, and ``load`` then keeps the engines the
scene has (give the command as a string, as in Yade). ``saveTmp``/``loadTmp`` keep their slots
in memory, where callables are kept as they are.

The functions take the scene first (``save(O, "run.h5")``); ``Scene`` offers them as methods
(``O.save("run.h5")``) through :class:`CheckpointMethods`.
"""

from __future__ import annotations

import importlib
import importlib.util
import inspect
import json
import math
import os
import pkgutil
import warnings
import weakref
from pathlib import Path
from typing import TYPE_CHECKING, Any

import numpy as np

from talus import _dem
from talus.dem.files import trust
from talus.dem.geometry.appearance import Appearance
from talus.dem.core.reference import ReferenceStates
from talus.dem.core.scenes import live_scenes

if TYPE_CHECKING:
    from talus.dem.core.scene import Scene

__all__ = ["CheckpointError", "CheckpointWarning", "CheckpointMethods", "available", "save", "load",
           "saveTmp", "loadTmp", "lsTmp", "reload", "owner_scene"]

if hasattr(_dem, "CheckpointError"):
    CheckpointError = _dem.CheckpointError
else:  # built without HDF5
    class CheckpointError(RuntimeError):
        """A checkpoint could not be written or read (the message names the file and why)."""


class CheckpointWarning(UserWarning):
    """Something of the scene could not go into a checkpoint (or come back from it)."""


_ENGINES_FORMAT = 1
_ENGINE_MODES = ("auto", "saved", "current")
# Constructor parameters accepted for Yade compatibility that carry nothing to restore.
_IGNORED_PARAMETERS = {"boundDispatcher"}


def available() -> bool:
    """True if this Talus was built with HDF5, which checkpoints need."""
    return bool(_dem.checkpoints_available())


def _require():
    if not available():
        raise CheckpointError(
            "checkpoints need HDF5, and this Talus was built without it (see `talus info`; install "
            "libhdf5-openmpi-dev and rebuild, or configure with -DTALUS_WITH_HDF5=ON)")


# ------------------------------------------------------------------------------------------------
# Engines <-> plain data.

class _NotSaveable(Exception):
    pass


def _describe(engine) -> str:
    label = getattr(engine, "label", "")
    return f"{type(engine).__name__}" + (f" '{label}'" if label else "")


def _class_path(cls: type) -> str:
    return f"{cls.__module__}:{cls.__qualname__}"


def _import_module(name: str):
    """Checkpoints written before a module of talus.dem moved name its old place (flat,
    talus.dem.engines:ForceResetter, or another sub-package, talus.dem.core.linalg:Vector3); such a
    module is found in the sub-package holding it now."""
    package, _, leaf = name.rpartition(".")
    if package.startswith("talus.dem") and importlib.util.find_spec(name) is None:
        dem_folder = str(Path(__file__).resolve().parents[1])
        for sub in pkgutil.iter_modules([dem_folder]):
            if sub.ispkg and importlib.util.find_spec(f"talus.dem.{sub.name}.{leaf}") is not None:
                return importlib.import_module(f"talus.dem.{sub.name}.{leaf}")
    return importlib.import_module(name)


def _import_class(path: str) -> type:
    module, _, qualname = path.partition(":")
    if not (module == "talus" or module.startswith("talus.")):
        raise _NotSaveable(f"class {path} is not a Talus class")
    obj: Any = _import_module(module)
    for part in qualname.split("."):
        obj = getattr(obj, part)
    if not isinstance(obj, type):
        raise _NotSaveable(f"{path} is not a class")
    return obj


def _encode(value, to_file: bool):
    """Plain data (JSON-ready when ``to_file``) for a constructor argument."""
    from talus.dem.step.engines import Functor, MatchMaker
    if value is None or isinstance(value, (bool, int, str)):
        return value
    if isinstance(value, float):
        return value if math.isfinite(value) else {"__float__": repr(value)}
    if isinstance(value, np.generic):
        return _encode(value.item(), to_file)
    if isinstance(value, np.ndarray):
        return {"__array__": [_encode(v, to_file) for v in value.tolist()]}
    if isinstance(value, tuple):
        return {"__tuple__": [_encode(v, to_file) for v in value]}
    if isinstance(value, list):
        return [_encode(v, to_file) for v in value]
    if isinstance(value, dict) and all(isinstance(k, str) for k in value):
        return {"__dict__": {k: _encode(v, to_file) for k, v in value.items()}}
    if isinstance(value, Functor):
        params = {k: _encode(v if isinstance(v, MatchMaker) else float(v), to_file) for k, v in value._io_params().items()}
        if not to_file:
            return {"__functor__": _class_path(type(value)), "label": value.label, "params": params,
                    "class_object": type(value)}
        return {"__functor__": _class_path(type(value)), "label": value.label, "params": params}
    if isinstance(value, MatchMaker):
        return {"__matchmaker__": {"algo": value.algo, "val": _encode(value.val, to_file),
                                   "matches": [[int(a), int(b), _encode(float(v), to_file)] for a, b, v in value.matches]}}
    if not to_file:
        return {"__object__": value}   # kept by reference in memory slots
    if callable(value):
        raise _NotSaveable("a Python callable cannot be written to a file (give a PyRunner command as a "
                           "string, as in Yade)")
    raise _NotSaveable(f"a value of type {type(value).__name__} cannot be written to a file")


def _decode(value):
    if isinstance(value, list):
        return [_decode(v) for v in value]
    if not isinstance(value, dict):
        return value
    if "__object__" in value:
        return value["__object__"]
    if "__float__" in value:
        return float(value["__float__"])
    if "__array__" in value:
        return np.array(_decode(value["__array__"]))
    if "__tuple__" in value:
        return tuple(_decode(v) for v in value["__tuple__"])
    if "__dict__" in value:
        return {k: _decode(v) for k, v in value["__dict__"].items()}
    if "__matchmaker__" in value:
        from talus.dem.step.engines import MatchMaker
        made = value["__matchmaker__"]
        return MatchMaker(made["algo"], _decode(made["val"]), [[a, b, _decode(v)] for a, b, v in made["matches"]])
    if "__functor__" in value:
        cls = value.get("class_object") or _import_class(value["__functor__"])
        return cls(label=value.get("label", ""), **{k: _decode(v) for k, v in value.get("params", {}).items()})
    raise _NotSaveable(f"unknown value {value!r}")


def _parameter(engine, name: str):
    """The current value of constructor parameter ``name``: the engine's attribute of that name,
    or its C++ engine's."""
    for owner in (engine, getattr(engine, "_cpp", None)):
        if owner is not None:
            try:
                return getattr(owner, name)
            except AttributeError:
                pass
    raise _NotSaveable(f"its parameter {name!r} cannot be read back")


def _engine_spec(engine, to_file: bool) -> dict:
    """Class, parameters, flags and counters of one engine; {"restorable": False, ...} if not."""
    cls = type(engine)
    spec: dict[str, Any] = {"class": _class_path(cls), "describe": _describe(engine)}
    try:
        if to_file:
            _import_class(spec["class"])
        else:
            spec["class_object"] = cls
        params = {}
        if hasattr(engine, "_io_params"):      # engines may say themselves what rebuilds them
            items = dict(engine._io_params()).items()
        else:
            items = []
            for name, p in inspect.signature(cls).parameters.items():
                if p.kind in (p.VAR_POSITIONAL, p.VAR_KEYWORD) or name in _IGNORED_PARAMETERS:
                    continue
                items.append((name, _parameter(engine, name)))
        for name, value in items:
            params[name] = _encode(value, to_file)
        spec["params"] = params
        spec["dead"] = bool(getattr(engine, "dead", False))
        state = {}
        cpp = getattr(engine, "_cpp", None)
        for counter in ("iterLast", "virtLast", "nDone"):   # periodic engines (PyRunner): when they run next
            if cpp is not None and hasattr(cpp, counter):
                state[counter] = getattr(cpp, counter)
        if hasattr(engine, "_io_state"):
            state["custom"] = _encode(engine._io_state(), to_file)
        spec["state"] = state
        spec["restorable"] = True
    except _NotSaveable as e:
        spec = {"class": spec["class"], "describe": spec["describe"], "restorable": False, "reason": str(e)}
    return spec


def _engine_specs(scene: "Scene", to_file: bool) -> list[dict]:
    return [_engine_spec(e, to_file) for e in scene.engines]


def _rebuild(spec: dict):
    cls = spec.get("class_object") or _import_class(spec["class"])
    params = {k: _decode(v) for k, v in spec["params"].items()}
    engine = cls(**params)
    if spec.get("dead"):
        engine.dead = True
    state = spec.get("state", {})
    cpp = getattr(engine, "_cpp", None)
    for counter in ("iterLast", "virtLast", "nDone"):
        if counter in state and cpp is not None:
            setattr(cpp, counter, state[counter])
    if "custom" in state and hasattr(engine, "_io_restore"):
        engine._io_restore(_decode(state["custom"]))
    return engine


def _restore_engines(scene: "Scene", specs: list[dict] | None, mode: str, where: str) -> bool:
    """Set the scene's engines from ``specs`` according to ``mode`` (see :func:`load`); True if
    the saved engines were set."""
    if mode == "current":
        return False
    if specs is None:
        problem = "it holds no engine list"
    else:
        bad = [s for s in specs if not s.get("restorable")]
        problem = "; ".join(f"{s['describe']}: {s['reason']}" for s in bad)
        if not bad:
            try:
                scene.engines = [_rebuild(s) for s in specs]
                return True
            except Exception as e:  # noqa: BLE001  (a class changed since the save, ...)
                problem = f"rebuilding them failed: {type(e).__name__}: {e}"
    message = f"{where}: the saved engines cannot be rebuilt ({problem})"
    if mode == "saved":
        raise CheckpointError(message)
    warnings.warn(message + "; the scene keeps its current engines", CheckpointWarning, stacklevel=3)
    return False


# ------------------------------------------------------------------------------------------------
# Python-side materials: the Python Material objects edit the scene's C++ materials through
# references, which a load replaces.

def _material_class(kind):
    from talus.dem.core.materials import Material
    stack, found = [Material], []
    while stack:
        cls = stack.pop(0)
        if cls is not Material and getattr(cls, "_kind", None) == kind:
            found.append(cls)
        stack.extend(cls.__subclasses__())
    return found[0] if found else Material


def _copy_material(cpp):
    copy = _dem.Material()
    for name in dir(cpp):
        if not name.startswith("_") and not callable(getattr(cpp, name)):
            try:
                setattr(copy, name, getattr(cpp, name))
            except AttributeError:
                pass
    return copy


def _detach_materials(scene: "Scene") -> list:
    """Give each Python material its own copy before the scene's are replaced."""
    objects = list(getattr(scene.materials, "_materials", []))
    for m in objects:
        m._cpp = _copy_material(m._cpp)
    return objects


def _attach_materials(scene: "Scene", objects: list):
    """Bind Python materials to the scene's C++ materials again: the objects that were there keep
    their index when the kind matches, others are created."""
    count = scene._cpp.materialCount()
    bound = []
    for i in range(count):
        cpp = scene._cpp.material(i)
        cls = _material_class(cpp.kind)
        # (kinds, not classes: an ElastMat is stored as a frictionless FrictMat)
        obj = objects[i] if i < len(objects) and getattr(objects[i], "_kind", None) == cpp.kind else cls()
        obj._bind(scene, cpp)
        bound.append(obj)
    for obj in objects[count:]:
        obj._scene = None
    scene.materials._materials = bound


def _body_data(scene: "Scene") -> dict:
    """The per-body data kept beside the C++ state: the look and the reference configuration
    (each only when there is something to keep)."""
    data = {"appearance": scene._appearance.to_json(), "reference": scene._reference.to_json()}
    return {name: text for name, text in data.items() if text}


def _load_state(scene: "Scene", loader) -> dict:
    objects = _detach_materials(scene)
    try:
        extras = loader()
    finally:
        _attach_materials(scene, objects)
    scene._appearance = Appearance.from_json(extras.get("appearance"))
    scene._reference = ReferenceStates.from_json(extras.get("reference"))
    return extras


def owner_scene(engine):
    """The scene whose engine list holds ``engine`` (for engines written in Python, such as
    ``VTKRecorder``, whose command is called without arguments). ``O`` is tried first; the
    answer is remembered while the engine stays in that scene."""
    ref = getattr(engine, "_owner_scene", None)
    scene = ref() if ref is not None else None
    if scene is not None and any(e is engine for e in scene.engines):
        return scene
    for candidate in live_scenes():
        if any(e is engine for e in candidate.engines):
            object.__setattr__(engine, "_owner_scene", weakref.ref(candidate))
            return candidate
    raise RuntimeError(f"{_describe(engine)} is not in the engine list of any scene")


# ------------------------------------------------------------------------------------------------
# Public functions.

_memory: "weakref.WeakKeyDictionary[Any, dict]" = weakref.WeakKeyDictionary()


def _scene_memory(scene) -> dict:
    return _memory.setdefault(scene, {"slots": {}, "last": None})


def last_file(scene) -> str | None:
    """The file last saved or loaded by ``scene`` (``:memory:<slot>`` for a saveTmp slot, as
    Yade names them), None if none."""
    last = _scene_memory(scene)["last"]
    if last is None:
        return None
    return f":memory:{last}" if isinstance(last, _Slot) else str(last)


def save(scene: "Scene", path: str | os.PathLike, *, engines: bool = True) -> None:
    """Write a checkpoint of ``scene`` to ``path`` (conventionally ``*.h5``), atomically.

    ``engines``: also store the engine list (as JSON) so that :func:`load` can rebuild it.
    Engines that cannot be written (a PyRunner with a callable command, a class that is not
    Talus's) give a :class:`CheckpointWarning`; the state is saved all the same.
    Raises :class:`CheckpointError` naming the file if it cannot be written; a file already at
    ``path`` is then left as it was.

    Under mpirun every process calls it (as every process runs the script): one file, written by
    all of them, in the layout of a serial checkpoint (docs/distributed-dem.md, Checkpoints).
    """
    _require()
    path = os.fspath(path)
    extras = {}
    if engines:
        specs = _engine_specs(scene, to_file=True)
        bad = [s for s in specs if not s["restorable"]]
        if bad:
            warnings.warn(f"O.save({path!r}): " + "; ".join(f"{s['describe']}: {s['reason']}" for s in bad)
                          + "; O.load will keep the engines the scene has then", CheckpointWarning, stacklevel=2)
        extras["engines"] = json.dumps({"format": _ENGINES_FORMAT, "engines": specs})
        signature = trust.signature_for(extras["engines"], getattr(scene, "_held_commands", set()))
        if signature is not None:
            extras["engines_signature"] = signature
    extras.update(_body_data(scene))
    from talus.dem import distributed
    # a scene yade.mpy merged is whole on every process until its next split: rank 0 writes it
    merged = distributed.ACTIVE and distributed.domain(scene) is None and getattr(scene, "_merged", False)
    if distributed.ACTIVE and not merged:
        if isinstance(distributed.domain(scene), distributed.HeldRows):
            distributed.refuse("O.save of a scene holding a packing read in slabs, before its first step (save it "
                               "after the first step, once the scene is split)")
        from talus import _distributed_checkpoint
        _distributed_checkpoint.save(distributed.domain(scene), scene._cpp, path, extras)
    elif not merged or distributed.rank() == 0:
        _dem.save_checkpoint(scene._cpp, path, extras)
    _scene_memory(scene)["last"] = path


def _refuse_split(scene: "Scene", what: str) -> None:
    """Memory slots hold one process's rows: refused once the scene is split over processes."""
    from talus.dem import distributed
    if distributed.domain(scene) is not None:
        distributed.refuse(f"{what} (a memory slot; O.save and O.load work under mpirun)")


def _engine_list(extras: dict, where: str) -> list[dict] | None:
    text = extras.get("engines")
    if text is None:
        return None
    try:
        data = json.loads(text)
    except ValueError as e:
        raise CheckpointError(f"{where}: the engine list is not valid JSON ({e})") from None
    if not isinstance(data, dict) or data.get("format") != _ENGINES_FORMAT or not isinstance(data.get("engines"), list):
        raise CheckpointError(f"{where}: the engine list has an unknown format")
    return data["engines"]


def load(scene: "Scene", path: str | os.PathLike, *, engines: str = "auto", trusted: bool | None = None) -> None:
    """Restore ``scene`` from the checkpoint at ``path``: bodies, materials, contacts, periodic
    cell and clock; the next step re-detects contacts and continues as the saved run would have.

    ``engines``: ``"auto"`` rebuilds the saved engine list when possible and otherwise keeps the
    scene's engines with a :class:`CheckpointWarning`; ``"saved"`` requires the saved list
    (:class:`CheckpointError` if it cannot be rebuilt); ``"current"`` keeps the scene's engines.
    Raises :class:`CheckpointError` naming the file if it is missing, truncated, corrupted, not a
    Talus checkpoint or of another format version; the scene is then unchanged.

    ``trusted``: whether the saved engines' Python commands (PyRunner commands, hooks) may run.
    By default (None) only those of a file the user saved (its engine list carries the user's
    signature), or of every file under ``talus run --trust-checkpoints``; the others are loaded but held, with a
    :class:`CheckpointWarning` listing them, and one that comes due stops the run with
    :class:`talus.dem.files.trust.UntrustedCommandError` (see :mod:`talus.dem.files.trust`).

    Under mpirun every process reads the whole file (written at any process count, or by a run
    in one process) and the scene is split again when its next step starts.
    """
    _require()
    if engines not in _ENGINE_MODES:
        raise ValueError(f"O.load: engines must be one of {_ENGINE_MODES}, got {engines!r}")
    path = os.fspath(path)
    where = f"checkpoint {path!r}"
    from talus.dem import distributed
    if distributed.ACTIVE:
        from talus import _distributed_checkpoint
        extras = _load_state(scene, lambda: _distributed_checkpoint.load(scene._cpp, path))
        scene._domain = None      # the whole scene is here again: split at the next step
    else:
        extras = _load_state(scene, lambda: _dem.load_checkpoint(scene._cpp, path))
    if trusted is None:
        trusted = trust.trusted_by_default(extras.get("engines"), extras.get("engines_signature"))
    if trusted:
        if _restore_engines(scene, _engine_list(extras, where), engines, where):
            scene._held_commands = set()
    else:
        with trust.holding(path) as held:
            restored = _restore_engines(scene, _engine_list(extras, where), engines, where)
        if restored:
            scene._held_commands = {command for _, command in held}
        if restored and held:
            listed = "; ".join(f"{what}: {command!r}" for what, command in held)
            warnings.warn(f"{where} holds Python commands, loaded but not run: {listed}. A checkpoint's commands "
                          f"run as code with your permissions; {trust.allow_hint(path)}", CheckpointWarning,
                          stacklevel=3)
    _scene_memory(scene)["last"] = path


def reload(scene: "Scene", *, engines: str = "auto", trusted: bool | None = None) -> None:
    """Load again the file or memory slot last saved or loaded by this scene (Yade's
    ``O.reload()``); ``trusted`` as for :func:`load` (memory slots are always trusted)."""
    last = _scene_memory(scene)["last"]
    if last is None:
        raise CheckpointError("O.reload: this scene has not been saved or loaded yet")
    if isinstance(last, _Slot):
        loadTmp(scene, last.name, engines=engines)
    else:
        load(scene, last, engines=engines, trusted=trusted)


class _Slot(str):
    """The memory slot last saved or loaded, for reload (as Yade's ``:memory:`` file names)."""

    @property
    def name(self) -> str:
        return str(self)


def saveTmp(scene: "Scene", slot: str = "") -> None:
    """Keep the scene's state and engines in memory slot ``slot`` (Yade's ``O.saveTmp``)."""
    _require()
    _refuse_split(scene, "O.saveTmp")
    image = _dem.save_checkpoint_image(scene._cpp, _body_data(scene))
    _scene_memory(scene)["slots"][str(slot)] = (image, _engine_specs(scene, to_file=False))
    _scene_memory(scene)["last"] = _Slot(slot)


def loadTmp(scene: "Scene", slot: str = "", *, engines: str = "auto") -> None:
    """Restore the state and engines kept by :func:`saveTmp` in ``slot`` (Yade's ``O.loadTmp``).
    ``engines`` as for :func:`load`."""
    _require()
    _refuse_split(scene, "O.loadTmp")
    if engines not in _ENGINE_MODES:
        raise ValueError(f"O.loadTmp: engines must be one of {_ENGINE_MODES}, got {engines!r}")
    slots = _scene_memory(scene)["slots"]
    if str(slot) not in slots:
        known = ", ".join(repr(s) for s in slots) or "none"
        raise CheckpointError(f"O.loadTmp: no slot {str(slot)!r} saved by O.saveTmp (slots: {known})")
    image, specs = slots[str(slot)]
    where = f"saveTmp slot {str(slot)!r}"
    _load_state(scene, lambda: _dem.load_checkpoint_image(scene._cpp, image, where))
    _restore_engines(scene, specs, engines, where)
    _scene_memory(scene)["last"] = _Slot(slot)


def lsTmp(scene: "Scene") -> list[str]:
    """Names of the memory slots of ``scene`` (Yade's ``O.lsTmp()``)."""
    return list(_scene_memory(scene)["slots"])


class CheckpointMethods:
    """Yade's ``O.save``/``O.load``/``O.saveTmp``/``O.loadTmp``/``O.reload``/``O.lsTmp`` as
    methods: a base class of ``Scene``."""

    # ``quiet`` (Yade's: no "Loading..." message) is accepted; Talus prints none anyway.
    def save(self, path: str | os.PathLike, quiet: bool = False, *, engines: bool = True) -> None:
        """Write a checkpoint (HDF5, atomic); see :func:`talus.dem.files.io.save`."""
        save(self, path, engines=engines)

    def load(self, path: str | os.PathLike, quiet: bool = False, *, engines: str = "auto",
             trusted: bool | None = None) -> None:
        """Restore a checkpoint written by ``save``; see :func:`talus.dem.files.io.load`."""
        load(self, path, engines=engines, trusted=trusted)

    def reload(self, quiet: bool = False, *, engines: str = "auto", trusted: bool | None = None) -> None:
        """Load again the file last saved or loaded; see :func:`talus.dem.files.io.reload`."""
        reload(self, engines=engines, trusted=trusted)

    def saveTmp(self, slot: str = "", quiet: bool = False) -> None:
        """Keep the state in a memory slot; see :func:`talus.dem.files.io.saveTmp`."""
        saveTmp(self, slot)

    def loadTmp(self, slot: str = "", quiet: bool = False, *, engines: str = "auto") -> None:
        """Restore a memory slot; see :func:`talus.dem.files.io.loadTmp`."""
        loadTmp(self, slot, engines=engines)

    def lsTmp(self) -> list[str]:
        """Names of the memory slots; see :func:`talus.dem.files.io.lsTmp`."""
        return lsTmp(self)
