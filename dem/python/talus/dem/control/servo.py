"""Yade's ServoPIDController: a translation driven by a PID controller on the force."""

from __future__ import annotations

from typing import Sequence

from talus import _dem
from talus.dem.step.engines import finite_vector
from talus.dem.step.kinematic import KinematicEngine
from talus.dem.base.linalg import Vector3


def _number(name: str, kind=float):
    """The C++ engine's attribute ``name``."""
    return property(lambda s: getattr(s._cpp, name), lambda s, v: setattr(s._cpp, name, kind(v)))


class ServoPIDController(KinematicEngine):
    """Moves ``ids`` along ``axis`` at a speed that a PID controller sets every ``iterPeriod``
    steps so that the force they bear along ``axis`` reaches ``target``: with the error e = (norm
    of the force's components along axis) - target, speed = kP e + kI (sum of e) + kD (change
    of e), capped at ``maxVelocity`` (a positive speed moves along +axis, away from the load).
    A kinematic engine: combine it with others by ``+``. Read-outs as Yade: ``current`` (the
    force's components along axis), ``curVel``, ``errorCur``, ``errorPrev``, ``iTerm``,
    ``iterPrevStart``."""

    _STATE = ("iterPrevStart", "errorCur", "errorPrev", "iTerm", "curVel")

    def __init__(self, axis=(0.0, 0.0, 0.0), target: float = 0.0, maxVelocity: float = 0.0, kP: float = 0.0,
                 kI: float = 0.0, kD: float = 0.0, iterPeriod: int = 100, ids: Sequence[int] = (), label: str = ""):
        if int(iterPeriod) < 0:
            raise ValueError(f"ServoPIDController: iterPeriod must be >= 0, got {iterPeriod}")
        self._init(_dem.ServoPIDController(), ids, label)
        self.axis, self.target, self.maxVelocity = axis, target, maxVelocity
        self.kP, self.kI, self.kD, self.iterPeriod = kP, kI, kD, iterPeriod

    target, maxVelocity, kP, kI, kD = (_number(n) for n in ("target", "maxVelocity", "kP", "kI", "kD"))
    iterPeriod, iterPrevStart = _number("iterPeriod", int), _number("iterPrevStart", int)
    errorCur, errorPrev, iTerm, curVel = (_number(n) for n in ("errorCur", "errorPrev", "iTerm", "curVel"))
    axis = property(lambda s: Vector3(s._cpp.axis), lambda s, v: setattr(s._cpp, "axis", finite_vector(v, "axis")),
                    doc="direction of the motion and of the force controlled (normalised when it runs)")
    current = property(lambda s: Vector3(s._cpp.current), doc="force components along axis at the last update")
    translationAxis = property(lambda s: Vector3(s._cpp.translationAxis), doc="axis, as last applied")
    velocity = property(lambda s: s._cpp.velocity, doc="speed, as last applied")

    def _io_state(self):
        return {name: getattr(self._cpp, name) for name in self._STATE}

    def _io_restore(self, state):
        for name, value in state.items():
            setattr(self._cpp, name, value)

__all__ = ["ServoPIDController"]
