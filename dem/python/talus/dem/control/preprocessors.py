"""Yade's scene generators ("preprocessors"): ``TriaxialTest`` builds the scene of a triaxial
test from its parameters; ``.load()`` puts it in O, ``.generate(fileName)`` saves it (a Talus
checkpoint under the name given, which ``O.load`` reads)::

    TriaxialTest(numberOfGrains=2000, noFiles=True).generate('/tmp/triax.xml')
    O.load('/tmp/triax.xml'); O.run(1000, True)
"""

from __future__ import annotations

import math

from talus.dem.packing import pack
from talus.dem.core.bodies import sphere, wall
from talus.dem.control.controllers import GlobalStiffnessTimeStepper
from talus.dem.step.engines import (Bo1_Box_Aabb, Bo1_Facet_Aabb, Bo1_Sphere_Aabb, Bo1_Wall_Aabb, ForceResetter,
                               Ig2_Box_Sphere_ScGeom, Ig2_Facet_Sphere_ScGeom, Ig2_Sphere_Sphere_ScGeom,
                               Ig2_Wall_Sphere_ScGeom, InsertionSortCollider, InteractionLoop,
                               Ip2_FrictMat_FrictMat_FrictPhys, Law2_ScGeom_FrictPhys_CundallStrack,
                               NewtonIntegrator)
from talus.dem.core.materials import FrictMat
from talus.dem.control.triaxial import TriaxialCompressionEngine, TriaxialStateRecorder
from talus.dem.core.scenes import default_scene

# Yade's defaults (TriaxialTest in Yade 2023.02a)
_DEFAULTS = {
    "lowerCorner": (0.0, 0.0, 0.0), "upperCorner": (1.0, 1.0, 1.0), "importFilename": "", "Key": "",
    "fixedBoxDims": "", "WallStressRecordFile": "./WallStresses", "internalCompaction": False,
    "biaxial2dTest": False, "autoCompressionActivation": True, "autoUnload": True, "autoStopSimulation": False,
    "noFiles": False, "facetWalls": False, "wallWalls": False, "thickness": 0.001, "maxMultiplier": 1.01,
    "finalMaxMultiplier": 1.001, "radiusStdDev": 0.3, "seed": 0, "radiusMean": -1.0,
    "sphereYoungModulus": 15e6, "sphereKsDivKn": 0.5, "sphereFrictionDeg": 18.0, "compactionFrictionDeg": 18.0,
    "boxYoungModulus": 15e6, "maxWallVelocity": 10.0, "boxKsDivKn": 0.5, "boxFrictionDeg": 0.0, "density": 2600.0,
    "strainRate": 0.1, "defaultDt": -1.0, "dampingForce": 0.2, "dampingMomentum": 0.2, "StabilityCriterion": 0.01,
    "wallOversizeFactor": 1.3, "sigmaIsoCompaction": -50000.0, "sigmaLateralConfinement": -50000.0,
    "timeStepUpdateInterval": 50, "wallStiffnessUpdateInterval": 10, "radiusControlInterval": 10,
    "numberOfGrains": 400, "recordIntervalIter": 20,
}
# Yade's walls are boxes; Talus's are planes at the boxes' inner faces, in Yade's order of ids.
_WALLS = (("bottom", 1, 0), ("top", 1, 1), ("left", 0, 0), ("right", 0, 1), ("back", 2, 0), ("front", 2, 1))


class TriaxialTest:
    """Yade's TriaxialTest preprocessor: ``numberOfGrains`` spheres from makeCloud (porosity
    0.8 in the box ``lowerCorner``-``upperCorner``; with ``radiusMean`` > 0 the box is scaled
    for that mean radius, except the axes in ``fixedBoxDims``, and ``seed`` is used), or read
    from ``importFilename``; six frictionless walls (ids 0-5: bottom, top, left, right, back,
    front); ForceResetter, InsertionSortCollider, InteractionLoop (FrictPhys, CundallStrack),
    GlobalStiffnessTimeStepper, a TriaxialCompressionEngine with the test's stresses, rates and
    intervals, a TriaxialStateRecorder (``WallStressRecordFile`` + ``Key`` every
    ``recordIntervalIter`` steps, unless ``noFiles``) and a NewtonIntegrator
    (``dampingForce``). The time step starts at the P-wave step (or ``defaultDt``).

    As in Yade, the spheres' material has the density 1000 while their masses come from
    ``density``, the walls take ``sphereYoungModulus`` and ``sphereKsDivKn``, and
    ``compactionFrictionDeg`` does not follow a ``sphereFrictionDeg`` given alone.
    ``facetWalls`` and ``biaxial2dTest`` are not implemented (an error says so); the box
    parameters that Yade does not use (``boxYoungModulus``, ``boxKsDivKn``, ``dampingMomentum``,
    ``wallOversizeFactor``) are accepted."""

    def __init__(self, **params):
        unknown = set(params) - set(_DEFAULTS)
        if unknown:
            raise TypeError(f"TriaxialTest has no parameter(s) {', '.join(sorted(unknown))}")
        for name, value in {**_DEFAULTS, **params}.items():
            setattr(self, name, value)

    def dict(self) -> dict:
        return {name: getattr(self, name) for name in _DEFAULTS}

    def load(self):
        """Build the scene in O (what was there is replaced)."""
        O = default_scene()
        self._check()
        O.reset()
        self._build(O)

    def generate(self, fileName: str):
        """Build the scene and save it to ``fileName`` (O is left as it is)."""
        from talus.dem.core.scene import Scene
        scene = Scene()
        self._build(scene)
        scene.save(fileName)

    def _packing(self) -> tuple[pack.SpherePack, tuple, tuple]:
        sp = pack.SpherePack()
        lo, hi = tuple(map(float, self.lowerCorner)), tuple(map(float, self.upperCorner))
        if self.importFilename:
            sp.load(self.importFilename)
            lo, hi = (tuple(map(float, c)) for c in sp.aabb())
        elif self.radiusMean <= 0:
            sp.makeCloud(lo, hi, -1, self.radiusStdDev, self.numberOfGrains, False, 0.8)
        else:
            fixed = [axis in self.fixedBoxDims for axis in "xyz"]
            scaled = 3 - fixed[0] + fixed[1] + fixed[2]   # sic: Yade's count of the scaled axes
            if scaled == 0:
                raise ValueError("TriaxialTest: at most 2 (not 3) axes can have fixed dimensions in fixedBoxDims if "
                                 "scaling for given radiusMean.")
            dims = [h - l for l, h in zip(lo, hi)]
            factor = self.radiusMean * (4 / 3 * math.pi * self.numberOfGrains
                                        / (dims[0] * dims[1] * dims[2] * (1 - 0.8))) ** (1 / scaled)
            hi = tuple(l + d * (1 if f else factor) for l, d, f in zip(lo, dims, fixed))
            sp.makeCloud(lo, hi, self.radiusMean, self.radiusStdDev, self.numberOfGrains, False, -1, (), (), False,
                         self.seed)
        return sp, lo, hi

    def _check(self):
        if self.facetWalls and not self.wallWalls:
            raise ValueError("TriaxialTest: facetWalls is not implemented in Talus (use the default walls)")
        if self.biaxial2dTest:
            raise ValueError("TriaxialTest: biaxial2dTest is not implemented in Talus")

    def _build(self, scene):
        self._check()
        sp, lo, hi = self._packing()
        spheres = FrictMat(young=self.sphereYoungModulus, poisson=self.sphereKsDivKn,
                           frictionAngle=math.radians(self.compactionFrictionDeg), density=1000)
        walls = FrictMat(young=self.sphereYoungModulus, poisson=self.sphereKsDivKn,
                         frictionAngle=math.radians(self.boxFrictionDeg), density=0)
        scene.materials.append([spheres, walls])
        triax = TriaxialCompressionEngine(
            warn=1, stiffnessUpdateInterval=self.wallStiffnessUpdateInterval,
            radiusControlInterval=self.radiusControlInterval, sigmaIsoCompaction=self.sigmaIsoCompaction,
            sigmaLateralConfinement=self.sigmaLateralConfinement, max_vel=self.maxWallVelocity,
            thickness=0 if self.wallWalls else (self.radiusMean if self.thickness < 0 else self.thickness),
            strainRate=self.strainRate, StabilityCriterion=self.StabilityCriterion,
            autoCompressionActivation=self.autoCompressionActivation, autoUnload=self.autoUnload,
            autoStopSimulation=self.autoStopSimulation, internalCompaction=self.internalCompaction,
            maxMultiplier=self.maxMultiplier, finalMaxMultiplier=self.finalMaxMultiplier, Key=self.Key,
            noFiles=self.noFiles, frictionAngleDegree=self.sphereFrictionDeg, fixedPoroCompaction=False,
            fixedPorosity=1)
        for name, axis, upper in _WALLS:
            (wall_id,) = scene.bodies.append([wall((hi if upper else lo)[axis], axis, material=walls)])
            setattr(triax, f"wall_{name}_id", wall_id)
        ids = scene.bodies.append([sphere(c, r, material=spheres) for c, r in sp])
        for i, (_, r) in zip(ids, sp):
            body = scene.bodies[i]
            body.state.mass = 4 / 3 * math.pi * r ** 3 * self.density
            body.state.inertia = (0.4 * body.state.mass * r * r,) * 3
        timestepper = GlobalStiffnessTimeStepper(timeStepUpdateInterval=self.timeStepUpdateInterval,
                                                 defaultDt=self.defaultDt)
        engines = [ForceResetter(),
                   InsertionSortCollider([Bo1_Sphere_Aabb(), Bo1_Box_Aabb(), Bo1_Facet_Aabb(), Bo1_Wall_Aabb()],
                                         verletDist=.5 * self.radiusMean),
                   InteractionLoop([Ig2_Sphere_Sphere_ScGeom(), Ig2_Facet_Sphere_ScGeom(), Ig2_Box_Sphere_ScGeom(),
                                    Ig2_Wall_Sphere_ScGeom()], [Ip2_FrictMat_FrictMat_FrictPhys()],
                                   [Law2_ScGeom_FrictPhys_CundallStrack()]),
                   timestepper, triax]
        if self.recordIntervalIter > 0 and not self.noFiles:
            engines.append(TriaxialStateRecorder(file=self.WallStressRecordFile + self.Key,
                                                 iterPeriod=self.recordIntervalIter))
        scene.engines = engines + [NewtonIntegrator(damping=self.dampingForce)]
        # The walls start at maxWallVelocity on a loose cloud, and the time stepper doubles the
        # step on the first contacts: overlaps of about half a radius in the first steps, in Yade
        # too (measured: up to 48 % there); Talus's guard against a too large step would stop it.
        scene.maxOverlapRatio = 1.0
        if self.defaultDt < 0:   # Yade's P-wave step, with the spheres' density as their masses have it
            radius = min(r for _, r in sp)
            scene.dt = timestepper.defaultDt = radius * math.sqrt(self.density / self.sphereYoungModulus)


__all__ = ["TriaxialTest"]
