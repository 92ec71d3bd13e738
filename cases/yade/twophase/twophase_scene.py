# What the two-phase scripts run by Yade (and Talus) share: cases/yade/twophase/twophase_drainage.py,
# twophase_injection.py and tests/flow/twophase/twophase_yade_reference.py. Yade's `-x` puts no script folder on sys.path: a script
# first adds this folder.
from yade import *
from yade.minieigenHP import Vector3
from yade.utils import aabbWalls, sphere


def read_spheres(path):
    """The spheres of a sphere file (x y z r per line) and the corners (lo, hi) of their bounding box."""
    spheres = [tuple(map(float, l.split()[:4])) for l in open(path) if l.strip() and not l.startswith("#")]
    lo = [min(s[k] - s[3] for s in spheres) for k in range(3)]
    hi = [max(s[k] + s[3] for s in spheres) for k in range(3)]
    return spheres, lo, hi


def reservoir_engine(spheres, lo, hi, engine=None, **attributes):
    """A fresh scene: the spheres, fixed, in the six walls of the box lo-hi, and a TwoPhaseFlowEngine
    (or the class `engine`) with the wetting reservoir at ymin and the non-wetting one at ymax
    (pressure 0), then the `attributes` set in their order (not initialized)."""
    O.reset()
    O.bodies.append(aabbWalls([Vector3(*lo), Vector3(*hi)], thickness=0))
    for x, y, z, r in spheres:
        O.bodies.append(sphere((x, y, z), r, fixed=True))
    tp = (engine or TwoPhaseFlowEngine)()
    tp.bndCondIsPressure = [0, 0, 1, 1, 0, 0]
    tp.bndCondValue = [0, 0, 0, 0, 0, 0]
    for name, value in attributes.items():
        setattr(tp, name, value)
    return tp


def invade(tp, pcs):
    """For each capillary pressure in turn, the wetting pressure -pc at ymin and invasion(); returns
    the saturation after each (side pores excluded, Yade's default)."""
    saturations = []
    for pc in pcs:
        tp.bndCondValue = [0, 0, -pc, 0, 0, 0]
        tp.invasion()
        saturations.append(tp.getSaturation(False))
    return saturations
