"""``yade.utils``: body constructors, time steps, measurements and helpers under Yade's names
(implemented in talus.dem). ``from yade.utils import *`` is part of a script's namespace under
``talus run``."""

from talus.dem import (PWaveTimeStep, RayleighWaveTimeStep, aabbWalls, avgNumInteractions, bodyStressTensors, box,
                       facet, fabricTensor, getStress, getStressAndTangent, growParticles, porosity,
                       setContactFriction, sphere, unbalancedForce, wall)
from talus.dem import O
from talus.dem.geometry.geom import facetBox, facetCylinder
from talus.dem.core.scene import SpherePWaveTimeStep
from talus.dem.core.clumps import clumpTemplate
from talus.dem.base.linalg import Quaternion
from talus.dem.analysis.measure import (aabbDim, aabbExtrema, angularMomentum, getSpheresMass, getSpheresVolume,
                               kineticEnergy, momentum, sumForces, totalForceInVolume)
from talus.batch import (TableParamReader, loadVars, readParamsFromTable, runningInBatch, saveVars,
                         waitIfBatch)

__all__ = ["sphere", "wall", "facet", "box", "aabbWalls", "facetBox", "facetCylinder", "PWaveTimeStep", "SpherePWaveTimeStep",
           "RayleighWaveTimeStep", "unbalancedForce", "getStress", "getStressAndTangent", "avgNumInteractions",
           "fabricTensor", "bodyStressTensors", "porosity", "growParticles", "setContactFriction",
           "typedEngine", "kineticEnergy", "momentum", "angularMomentum", "sumForces", "totalForceInVolume", "aabbExtrema", "aabbDim",
           "getSpheresVolume", "getSpheresMass",
           "randomOrientation", "randomColor", "clumpTemplate", "calm",
           "readParamsFromTable", "TableParamReader", "saveVars", "loadVars", "waitIfBatch", "runningInBatch"]


def typedEngine(name: str):
    """The first engine of the class ``name`` in O.engines."""
    return O.typedEngine(name)


def randomOrientation() -> Quaternion:
    """A uniformly distributed random orientation (Python's ``random``, as Yade)."""
    import math
    import random
    u1, u2, u3 = random.random(), random.random(), random.random()
    a, b = math.sqrt(1 - u1), math.sqrt(u1)
    return Quaternion(a * math.sin(2 * math.pi * u2), a * math.cos(2 * math.pi * u2),
                      b * math.sin(2 * math.pi * u3), b * math.cos(2 * math.pi * u3))


def calm(mask: int = -1) -> None:
    """Stop the bodies whose mask shares a bit with ``mask`` (all when it is not positive):
    velocity and angular velocity set to zero (Yade's calm)."""
    for b in O.bodies:
        if b is None or (mask > 0 and not b.mask & mask):
            continue
        b.state.vel = (0.0, 0.0, 0.0)
        b.state.angVel = (0.0, 0.0, 0.0)


def randomColor() -> tuple[float, float, float]:
    """A random RGB colour (Python's ``random``)."""
    import random
    return (random.random(), random.random(), random.random())

from yade._scope import module_getattr  # noqa: E402

__getattr__ = module_getattr("yade.utils")
