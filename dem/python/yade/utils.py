"""``yade.utils``: body constructors, time steps, measurements and helpers under Yade's names
(implemented in talus.dem). ``from yade.utils import *`` is part of a script's namespace under
``talus run``."""

from talus.dem import (PWaveTimeStep, RayleighWaveTimeStep, aabbWalls, avgNumInteractions, bodyStressTensors, box,
                       facet, fabricTensor, getStress, getStressAndTangent, growParticles, porosity,
                       setContactFriction, sphere, unbalancedForce, wall)
from talus.dem.geom import facetBox, facetCylinder

__all__ = ["sphere", "wall", "facet", "box", "aabbWalls", "facetBox", "facetCylinder", "PWaveTimeStep",
           "RayleighWaveTimeStep", "unbalancedForce", "getStress", "getStressAndTangent", "avgNumInteractions",
           "fabricTensor", "bodyStressTensors", "porosity", "growParticles", "setContactFriction"]
