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
from talus.dem.engines import Engine
from talus.dem.linalg import Vector3


def _vector(value, what: str) -> list[float]:
    v = np.asarray(value, dtype=float).reshape(-1)
    if v.shape != (3,) or not np.all(np.isfinite(v)):
        raise ValueError(f"{what} must be 3 finite numbers, got {value!r}")
    return v.tolist()


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


class TranslationEngine(KinematicEngine):
    """Moves ``ids`` at ``velocity`` along ``translationAxis`` (normalised, as in Yade)."""

    def __init__(self, translationAxis=(1.0, 0.0, 0.0), velocity: float = 0.0, ids: Sequence[int] = (),
                 label: str = ""):
        self._init(_dem.TranslationEngine(), ids, label)
        self.translationAxis = translationAxis
        self.velocity = velocity

    translationAxis = property(lambda s: Vector3(s._cpp.translationAxis),
                               lambda s, v: setattr(s._cpp, "translationAxis", _vector(v, "translationAxis")))
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
                            lambda s, v: setattr(s._cpp, "rotationAxis", _vector(v, "rotationAxis")))
    rotateAroundZero = property(lambda s: s._cpp.rotateAroundZero,
                                lambda s, v: setattr(s._cpp, "rotateAroundZero", bool(v)))
    zeroPoint = property(lambda s: Vector3(s._cpp.zeroPoint),
                         lambda s, v: setattr(s._cpp, "zeroPoint", _vector(v, "zeroPoint")))


class HarmonicMotionEngine(KinematicEngine):
    """Oscillates ``ids`` as x = A cos(2 pi f t + fi) per axis (amplitudes ``A``, frequencies
    ``f`` in Hz, phases ``fi``; Yade's default phase pi/2 starts at rest position x = 0)."""

    def __init__(self, A=(0.0, 0.0, 0.0), f=(0.0, 0.0, 0.0), fi=(np.pi / 2,) * 3, ids: Sequence[int] = (),
                 label: str = ""):
        self._init(_dem.HarmonicMotionEngine(), ids, label)
        self.A, self.f, self.fi = A, f, fi

    A = property(lambda s: Vector3(s._cpp.A), lambda s, v: setattr(s._cpp, "A", _vector(v, "A")))
    f = property(lambda s: Vector3(s._cpp.f), lambda s, v: setattr(s._cpp, "f", _vector(v, "f")))
    fi = property(lambda s: Vector3(s._cpp.fi), lambda s, v: setattr(s._cpp, "fi", _vector(v, "fi")))


__all__ = ["KinematicEngine", "TranslationEngine", "RotationEngine", "HarmonicMotionEngine"]
