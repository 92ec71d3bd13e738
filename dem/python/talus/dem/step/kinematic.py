"""Kinematic engines (Yade's KinematicEngine family): impose the velocity of bodies.

Each engine zeroes the velocity and angular velocity of its ``ids`` every step and sets its own
motion; NewtonIntegrator then moves non-dynamic bodies (walls, facets, boxes, clumps created
fixed) with it, and contacts see the body's true velocity at the contact point::

    ids = O.bodies.append(geom.facetCylinder((0, 0, 0), 0.1, 0.2, wallMask=4))
    O.engines = [..., RotationEngine(ids=ids, rotationAxis=(0, 0, 1), angularVelocity=2.0,
                                     rotateAroundZero=True, zeroPoint=(0, 0, 0)),
                 NewtonIntegrator(...)]

A non-dynamic body can also be moved without an engine by setting ``b.state.vel`` and
``b.state.angVel``: they stay as set.
"""

from __future__ import annotations

from typing import Sequence

import numpy as np

from talus import _dem
from talus.dem.step.engines import Engine, finite_vector
from talus.dem.base.linalg import Vector3


def _unit(value, what: str) -> list[float]:
    """The direction of ``value``, normalised when set (as Yade's postLoad does)."""
    v = np.asarray(finite_vector(value, what))
    length = np.linalg.norm(v)
    if length == 0:
        raise ValueError(f"{what} must not be zero")
    return (v / length).tolist()


class KinematicEngine(Engine):
    """Base of the kinematic engines: the bodies ``ids`` it moves."""

    @property
    def ids(self) -> list[int]:
        return list(self._cpp.ids)

    @ids.setter
    def ids(self, ids: Sequence[int]):
        self._cpp.ids = [int(i) for i in ids]

    def _init(self, cpp, ids, label):
        self._cpp = cpp
        self.ids = ids
        self.label = label

    def __add__(self, other: "KinematicEngine") -> "CombinedKinematicEngine":
        """Yade's ``engine + engine``: a CombinedKinematicEngine moving this engine's ids by both."""
        if not isinstance(other, KinematicEngine):
            return NotImplemented
        combined = CombinedKinematicEngine(ids=self.ids)
        combined.comb = [self, other]
        return combined


class TranslationEngine(KinematicEngine):
    """Moves ``ids`` at ``velocity`` along ``translationAxis`` (normalised, as in Yade)."""

    def __init__(self, translationAxis=(1.0, 0.0, 0.0), velocity: float = 0.0, ids: Sequence[int] = (),
                 label: str = ""):
        self._init(_dem.TranslationEngine(), ids, label)
        self.translationAxis = translationAxis
        self.velocity = velocity

    translationAxis = property(lambda s: Vector3(s._cpp.translationAxis),
                               lambda s, v: setattr(s._cpp, "translationAxis", _unit(v, "translationAxis")))
    velocity = property(lambda s: s._cpp.velocity, lambda s, v: setattr(s._cpp, "velocity", float(v)))


class RotationEngine(KinematicEngine):
    """Turns ``ids`` at ``angularVelocity`` (rad/s) about ``rotationAxis``; with
    ``rotateAroundZero`` they also orbit the axis through ``zeroPoint``."""

    def __init__(self, angularVelocity: float = 0.0, rotationAxis=(1.0, 0.0, 0.0), rotateAroundZero: bool = False,
                 zeroPoint=(0.0, 0.0, 0.0), ids: Sequence[int] = (), label: str = ""):
        self._init(_dem.RotationEngine(), ids, label)
        self.angularVelocity = angularVelocity
        self.rotationAxis = rotationAxis
        self.rotateAroundZero = rotateAroundZero
        self.zeroPoint = zeroPoint

    angularVelocity = property(lambda s: s._cpp.angularVelocity,
                               lambda s, v: setattr(s._cpp, "angularVelocity", float(v)))
    rotationAxis = property(lambda s: Vector3(s._cpp.rotationAxis),
                            lambda s, v: setattr(s._cpp, "rotationAxis", finite_vector(v, "rotationAxis")))
    rotateAroundZero = property(lambda s: s._cpp.rotateAroundZero,
                                lambda s, v: setattr(s._cpp, "rotateAroundZero", bool(v)))
    zeroPoint = property(lambda s: Vector3(s._cpp.zeroPoint),
                         lambda s, v: setattr(s._cpp, "zeroPoint", finite_vector(v, "zeroPoint")))


class HarmonicMotionEngine(KinematicEngine):
    """Oscillates ``ids`` as x = A cos(2 pi f t + fi) per axis (amplitudes ``A``, frequencies
    ``f`` in Hz, phases ``fi``; Yade's default phase pi/2 starts at rest position x = 0)."""

    def __init__(self, A=(0.0, 0.0, 0.0), f=(0.0, 0.0, 0.0), fi=(np.pi / 2,) * 3, ids: Sequence[int] = (),
                 label: str = ""):
        self._init(_dem.HarmonicMotionEngine(), ids, label)
        self.A, self.f, self.fi = A, f, fi

    A = property(lambda s: Vector3(s._cpp.A), lambda s, v: setattr(s._cpp, "A", finite_vector(v, "A")))
    f = property(lambda s: Vector3(s._cpp.f), lambda s, v: setattr(s._cpp, "f", finite_vector(v, "f")))
    fi = property(lambda s: Vector3(s._cpp.fi), lambda s, v: setattr(s._cpp, "fi", finite_vector(v, "fi")))


class CombinedKinematicEngine(KinematicEngine):
    """Kinematic engines moving the same bodies ``ids`` together (Yade's CombinedKinematicEngine):
    the velocities are zeroed once, then each engine of ``comb`` that is not dead adds its
    motion. ``a + b`` makes one from two engines; ``combined + c`` appends ``c`` (as Yade's
    ``__add__``, it returns the same engine). The engines of ``comb`` keep their own parameters
    (``combined.comb[0].velocity = ...`` changes the motion); their own ids are not used."""

    def __init__(self, ids: Sequence[int] = (), comb: Sequence[KinematicEngine] = (), label: str = ""):
        self._init(_dem.CombinedKinematicEngine(), ids, label)
        self.comb = comb

    @property
    def comb(self) -> list[KinematicEngine]:
        return list(self._comb)

    @comb.setter
    def comb(self, engines: Sequence[KinematicEngine]):
        engines = list(engines)
        for e in engines:
            if not isinstance(e, KinematicEngine):
                raise TypeError(f"CombinedKinematicEngine.comb takes kinematic engines, got {e!r}")
        self._comb = engines
        self._cpp.comb = [e._cpp for e in engines]

    def __add__(self, other: KinematicEngine) -> "CombinedKinematicEngine":
        if not isinstance(other, KinematicEngine):
            return NotImplemented
        self.comb = self._comb + [other]
        return self


class HelixEngine(RotationEngine):
    """A screw motion (Yade's HelixEngine): RotationEngine's rotation about ``rotationAxis``
    through ``zeroPoint`` (the bodies always orbit it) plus ``linearVelocity`` along the axis;
    ``angleTurned`` adds up the angle."""

    def __init__(self, linearVelocity: float = 0.0, angularVelocity: float = 0.0, rotationAxis=(1.0, 0.0, 0.0),
                 zeroPoint=(0.0, 0.0, 0.0), angleTurned: float = 0.0, rotateAroundZero: bool = True,
                 ids: Sequence[int] = (), label: str = ""):
        self._init(self._make(), ids, label)
        self.angularVelocity, self.rotationAxis, self.zeroPoint = angularVelocity, rotationAxis, zeroPoint
        self.rotateAroundZero = rotateAroundZero
        self.linearVelocity, self.angleTurned = linearVelocity, angleTurned

    @staticmethod
    def _make():
        return _dem.HelixEngine()

    linearVelocity = property(lambda s: s._cpp.linearVelocity,
                              lambda s, v: setattr(s._cpp, "linearVelocity", float(v)))
    angleTurned = property(lambda s: s._cpp.angleTurned, lambda s, v: setattr(s._cpp, "angleTurned", float(v)))


class InterpolatingHelixEngine(HelixEngine):
    """HelixEngine whose angular velocity is read from ``times`` and ``angularVelocities`` at
    the current time (linear between readings, the first before them and the last after them;
    with ``wrap`` the table repeats), with linearVelocity = ``slope`` x angularVelocity (Yade's
    InterpolatingHelixEngine)."""

    def __init__(self, times: Sequence[float] = (), angularVelocities: Sequence[float] = (), wrap: bool = False,
                 slope: float = 0.0, **helix):
        super().__init__(**helix)
        self.times, self.angularVelocities, self.wrap, self.slope = times, angularVelocities, wrap, slope

    @staticmethod
    def _make():
        return _dem.InterpolatingHelixEngine()

    times = property(lambda s: list(s._cpp.times), lambda s, v: setattr(s._cpp, "times", [float(x) for x in v]))
    angularVelocities = property(lambda s: list(s._cpp.angularVelocities),
                                 lambda s, v: setattr(s._cpp, "angularVelocities", [float(x) for x in v]))
    wrap = property(lambda s: s._cpp.wrap, lambda s, v: setattr(s._cpp, "wrap", bool(v)))
    slope = property(lambda s: s._cpp.slope, lambda s, v: setattr(s._cpp, "slope", float(v)))


__all__ = ["KinematicEngine", "TranslationEngine", "RotationEngine", "HarmonicMotionEngine", "CombinedKinematicEngine",
           "HelixEngine", "InterpolatingHelixEngine"]
