"""Force engines (Yade's ForceEngine family) and the InteractionLoop's callbacks.

Each engine adds a force to the force its bodies ``ids`` get this step: place it after the
InteractionLoop (or anywhere after ForceResetter) and before NewtonIntegrator::

    O.engines = [ForceResetter(), ..., InteractionLoop(...),
                 ForceEngine(ids=[1], force=(-20, 0, 0), label='push'),
                 NewtonIntegrator()]
"""

from __future__ import annotations

from typing import Sequence

import numpy as np

from talus import _dem
from talus.dem.step.engines import Engine, finite_vector as _vector
from talus.dem.core.masks import group_mask
from talus.dem.base.linalg import Vector2i, Vector3


def _table(value, what: str) -> list[float]:
    v = np.asarray(value, dtype=float).reshape(-1)
    if not np.all(np.isfinite(v)):
        raise ValueError(f"{what} must be finite numbers, got {value!r}")
    return v.tolist()


class ForceEngine(Engine):
    """Adds ``force`` to the bodies ``ids`` every step (Yade's ForceEngine)."""

    def __init__(self, force=(0.0, 0.0, 0.0), ids: Sequence[int] = (), label: str = ""):
        self._cpp = self._make()
        self.ids, self.force, self.label = ids, force, label

    @staticmethod
    def _make():
        return _dem.ForceEngine()

    ids = property(lambda s: list(s._cpp.ids), lambda s, v: setattr(s._cpp, "ids", [int(i) for i in v]))
    force = property(lambda s: Vector3(s._cpp.force), lambda s, v: setattr(s._cpp, "force", _vector(v, "force")))


class InterpolatingDirectedForceEngine(ForceEngine):
    """A force along ``direction`` (normalised when run, as in Yade) whose magnitude is read from
    ``times`` and ``magnitudes`` at the current time: linear between readings, the first before
    them and the last after them; with ``wrap`` the table repeats. ``force`` reads the force of
    the last step (Yade's InterpolatingDirectedForceEngine)."""

    def __init__(self, times: Sequence[float] = (), magnitudes: Sequence[float] = (), direction=(1.0, 0.0, 0.0),
                 wrap: bool = False, ids: Sequence[int] = (), label: str = ""):
        super().__init__(ids=ids, label=label)
        self.times, self.magnitudes, self.direction, self.wrap = times, magnitudes, direction, wrap

    @staticmethod
    def _make():
        return _dem.InterpolatingDirectedForceEngine()

    times = property(lambda s: list(s._cpp.times), lambda s, v: setattr(s._cpp, "times", _table(v, "times")))
    magnitudes = property(lambda s: list(s._cpp.magnitudes),
                          lambda s, v: setattr(s._cpp, "magnitudes", _table(v, "magnitudes")))
    direction = property(lambda s: Vector3(s._cpp.direction),
                         lambda s, v: setattr(s._cpp, "direction", _vector(v, "direction")))
    wrap = property(lambda s: s._cpp.wrap, lambda s, v: setattr(s._cpp, "wrap", bool(v)))


class HarmonicForceEngine(ForceEngine):
    """The force A_k sin(2 pi f_k t + fi_k) along each axis k on the bodies ``ids`` (amplitudes
    ``A``, frequencies ``f`` in Hz, phases ``fi``; Yade's HarmonicForceEngine)."""

    def __init__(self, A=(0.0, 0.0, 0.0), f=(0.0, 0.0, 0.0), fi=(0.0, 0.0, 0.0), ids: Sequence[int] = (),
                 label: str = ""):
        super().__init__(ids=ids, label=label)
        self.A, self.f, self.fi = A, f, fi

    @staticmethod
    def _make():
        return _dem.HarmonicForceEngine()

    A = property(lambda s: Vector3(s._cpp.A), lambda s, v: setattr(s._cpp, "A", _vector(v, "A")))
    f = property(lambda s: Vector3(s._cpp.f), lambda s, v: setattr(s._cpp, "f", _vector(v, "f")))
    fi = property(lambda s: Vector3(s._cpp.fi), lambda s, v: setattr(s._cpp, "fi", _vector(v, "fi")))


class GravityEngine(Engine):
    """Adds ``gravity`` x mass to every body (clumps through their members) each step (Yade's
    GravityEngine, which Yade deprecates in favour of ``NewtonIntegrator(gravity=...)``); with
    ``O.trackEnergy`` it books ``gravWork`` as Yade, -m g.v dt with the velocity of the step's
    start. Yade's notice that it is deprecated is printed at the first step unless ``warnOnce``
    is False. ``mask`` nonzero: only the bodies whose group mask (Body.mask) shares a bit with it."""

    def __init__(self, gravity=(0.0, 0.0, 0.0), warnOnce: bool = True, mask: int = 0, label: str = "",
                 dead: bool = False):
        self._cpp = _dem.GravityEngine()
        self.gravity, self.warnOnce, self.mask, self.label, self.dead = gravity, warnOnce, mask, label, dead

    gravity = property(lambda s: Vector3(s._cpp.gravity),
                       lambda s, v: setattr(s._cpp, "gravity", _vector(v, "gravity")))
    warnOnce = property(lambda s: s._cpp.warnOnce, lambda s, v: setattr(s._cpp, "warnOnce", bool(v)))
    mask = property(lambda s: s._cpp.mask,
                    lambda s, v: setattr(s._cpp, "mask", group_mask(v, "GravityEngine.mask")))


class HdapsGravityEngine(Engine):
    """Gravity following a laptop's tilt, read from its hdaps accelerometer (Yade's
    HdapsGravityEngine): ``hdapsDir``/position (and ``hdapsDir``/calibrate unless
    ``calibrated``) at most every ``msecUpdate`` ms; a reading moved more than
    ``updateThreshold`` from the last one followed turns ``zeroGravity`` by half of it in
    degrees. Adds gravity x mass to every body (clumps through their members). Without the
    device the first step stops with Yade's error, "unable to open file ..."."""

    def __init__(self, hdapsDir: str = "/sys/devices/platform/hdaps", msecUpdate: float = 50,
                 updateThreshold: int = 4, calibrate=(0, 0), calibrated: bool = False, zeroGravity=(0.0, 0.0, -1.0),
                 label: str = ""):
        self._cpp = _dem.HdapsGravityEngine()
        self.hdapsDir, self.msecUpdate, self.updateThreshold = hdapsDir, msecUpdate, updateThreshold
        self.calibrate, self.calibrated, self.zeroGravity, self.label = calibrate, calibrated, zeroGravity, label

    hdapsDir = property(lambda s: s._cpp.hdapsDir, lambda s, v: setattr(s._cpp, "hdapsDir", str(v)))
    msecUpdate = property(lambda s: s._cpp.msecUpdate, lambda s, v: setattr(s._cpp, "msecUpdate", float(v)))
    updateThreshold = property(lambda s: s._cpp.updateThreshold,
                               lambda s, v: setattr(s._cpp, "updateThreshold", int(v)))
    calibrate = property(lambda s: Vector2i(s._cpp.calibrate),
                         lambda s, v: setattr(s._cpp, "calibrate", [int(x) for x in v]))
    calibrated = property(lambda s: s._cpp.calibrated, lambda s, v: setattr(s._cpp, "calibrated", bool(v)))
    zeroGravity = property(lambda s: Vector3(s._cpp.zeroGravity),
                           lambda s, v: setattr(s._cpp, "zeroGravity", _vector(v, "zeroGravity")))
    gravity = property(lambda s: Vector3(s._cpp.gravity), doc="the gravity of the last reading")
    accel = property(lambda s: Vector2i(s._cpp.accel), doc="the reading followed, less the calibration")


class SumIntrForcesCb:
    """A callback of the InteractionLoop (``loop.callbacks = [SumIntrForcesCb()]``, Yade's):
    at the start of each step it writes "(sum,count)" to standard error, the sum of the
    magnitudes of the previous step's non-zero contact forces and their number."""

    def __init__(self, label: str = ""):
        self._cpp = _dem.SumIntrForcesCb()
        self.label = label

    force = property(lambda s: s._cpp.force)
    numIntr = property(lambda s: s._cpp.numIntr)

    def __repr__(self):
        return "SumIntrForcesCb()"


__all__ = ["ForceEngine", "InterpolatingDirectedForceEngine", "HarmonicForceEngine", "GravityEngine",
           "HdapsGravityEngine", "SumIntrForcesCb"]
