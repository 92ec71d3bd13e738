"""Yade's ResetRandomPosition: spheres that crossed a plane are put back at random places on a
set of facets (a recirculating flow)."""

from __future__ import annotations

import warnings

import numpy as np

from talus import _dem
from talus.dem.base.linalg import Vector3
from talus.dem.step.python_engines import PeriodicPythonEngine, colliderSkin


class _Mt19937Uniform:
    """Yade's (Boost's) uniform reals on [low, high) from a Mersenne twister with its default
    seed 5489: the same numbers as Yade draws."""

    def __init__(self, low: float, high: float):
        self._bits = np.random.MT19937()
        self._bits._legacy_seeding(5489)        # std::mt19937's own seeding
        self.low, self.high = low, high

    def __call__(self) -> float:
        while True:
            value = float(self._bits.random_raw()) / 4294967296.0 * (self.high - self.low) + self.low
            if value < self.high:
                return value


class _MinstdIndex:
    """Yade's (Boost's) uniform integers in [0, n) from minstd_rand with its default seed 1."""

    def __init__(self, n: int):
        self._state, self._n = 1, n
        self._bucket = 2147483646 // n     # (the engine's range + 1) / (range of the result + 1)

    def __call__(self) -> int:
        if self._n == 1:
            return 0
        while True:
            self._state = self._state * 48271 % 2147483647
            index = (self._state - 1) // self._bucket
            if index < self._n:
                return index


# As in Yade, the two real-number generators are shared by every ResetRandomPosition of the
# process and never reseeded: a script's draws are the same in each run.
_unit = _Mt19937Uniform(0.0, 1.0)
_symmetric = _Mt19937Uniform(-1.0, 1.0)


class ResetRandomPosition(PeriodicPythonEngine):
    """When it runs (a periodic engine: ``virtPeriod``, ``iterPeriod``, ...), each of
    ``subscribedBodies`` (spheres) whose centre is behind the plane through ``point`` of
    ``normal`` is moved to a random point of a random facet of ``factoryFacets`` (with
    ``volumeSection``: between two such points), trying up to ``maxAttempts`` places that touch
    no other body nor a sphere moved in the same run; its velocity becomes ``velocity`` +/-
    ``velocityRange``, its angular velocity ``angularVelocity`` +/- ``angularVelocityRange``
    (uniform in each component). When no place is found, it stays, with Yade's warning, and the
    other bodies wait for the next run. The random numbers are Yade's (its generators have fixed
    seeds), so the same script moves the same spheres to the same places.

    As in Yade 2023.02a, a place is refused when the sphere's bounding box where it was (grown by
    the collider's skin) does not start beyond the new place's along x: Yade's collider probe
    then finds the sphere itself in the way. Spheres thus only come back at smaller x than they
    left; Talus keeps that, so that scripts recirculate as they do in Yade. Yade refuses still
    more places than this rule explains (after a sphere was moved, the next one often finds no
    place in that run): the first re-insertions are Yade's to round-off, later ones may differ."""

    _VECTORS = ("point", "normal", "velocity", "velocityRange", "angularVelocity", "angularVelocityRange")

    def __init__(self, factoryFacets=(), subscribedBodies=(), point=(0.0, 0.0, 0.0), normal=(0.0, 1.0, 0.0),
                 volumeSection: bool = False, maxAttempts: int = 20, velocity=(0.0, 0.0, 0.0),
                 velocityRange=(0.0, 0.0, 0.0), angularVelocity=(0.0, 0.0, 0.0), angularVelocityRange=(0.0, 0.0, 0.0),
                 iterPeriod: int = 0, virtPeriod: float = 0.0, realPeriod: float = 0.0, nDo: int = -1,
                 initRun: bool = False, label: str = "", dead: bool = False):
        super().__init__(iterPeriod, virtPeriod, realPeriod, nDo, initRun, label, dead)
        self.factoryFacets, self.subscribedBodies = [int(i) for i in factoryFacets], [int(i) for i in subscribedBodies]
        self.point, self.normal, self.velocity, self.velocityRange = point, normal, velocity, velocityRange
        self.angularVelocity, self.angularVelocityRange = angularVelocity, angularVelocityRange
        self.volumeSection, self.maxAttempts = bool(volumeSection), int(maxAttempts)
        self._facetIndex = None   # made at the first run, as Yade's

    def __setattr__(self, name, value):
        if name in self._VECTORS:
            value = Vector3(np.asarray(value, dtype=float).reshape(3))
        super().__setattr__(name, value)

    def _action(self, scene):
        skin = colliderSkin(scene, "ResetRandomPosition")
        if self._facetIndex is None:
            if not self.factoryFacets:
                raise ValueError("ResetRandomPosition.factoryFacets is empty: no surface to put the spheres on")
            self._facetIndex = _MinstdIndex(len(self.factoryFacets))
        point, normal = np.asarray(self.point), np.asarray(self.normal)
        for id in self.subscribedBodies:
            body = scene.bodies[id]
            if body is None or body.shape.__class__.__name__ != "Sphere":
                raise ValueError(f"ResetRandomPosition: subscribed body {id} is not a sphere of the scene")
            old = np.asarray(body.state.pos)
            if (old - point).dot(normal) >= 0:
                continue
            radius = body.shape.radius
            for _ in range(self.maxAttempts):
                place = self._volume_point(scene) if self.volumeSection else self._surface_point(scene)
                # Tried with the body there, as Yade does: the spheres moved before in this run
                # are where they were put. Yade's collider also finds the sphere itself there
                # unless its bound, sorted along x from where it was, starts beyond the place.
                body.state.pos = place
                findsItself = old[0] - radius - skin <= place[0] + radius
                if not findsItself and not _dem.bodies_touching_sphere(scene._cpp, place, radius, id):
                    break
            else:
                warnings.warn(f"ResetRandomPosition: can't place sphere {id} during {self.maxAttempts} attempts.",
                              RuntimeWarning, stacklevel=2)
                body.state.pos = old
                return
            body.state.vel = self._around(self.velocity, self.velocityRange)
            body.state.angVel = self._around(self.angularVelocity, self.angularVelocityRange)

    @staticmethod
    def _around(mean, halfWidth) -> np.ndarray:
        # Yade's compiler evaluates the three components last to first.
        draws = [_symmetric() for _ in range(3)][::-1]
        return np.asarray(mean) + np.asarray(halfWidth) * draws

    def _surface_point(self, scene) -> np.ndarray:
        facet = self.factoryFacets[self._facetIndex()]
        t1 = _unit()
        t2 = _unit() * (1 - t1)
        v0, v1, v2 = (np.asarray(v) for v in scene.bodies[facet].shape.vertices)
        position = np.asarray(scene.bodies[facet].state.pos)
        return t1 * (v1 - v0) + t2 * (v2 - v0) + v0 + position

    def _volume_point(self, scene) -> np.ndarray:
        p1, p2 = self._surface_point(scene), self._surface_point(scene)
        return p1 + _unit() * (p2 - p1)


__all__ = ["ResetRandomPosition"]
