"""Yade's clump operations on fixed inputs: clump() of given spheres (summed, and integrated on
a grid with discretization), clumps with a box or facets, addToClump (a sphere, another clump by
one of its members), releaseFromClump, erasing a member, a checkpoint saved and loaded,
export/ymport.textClumps, replaceByClumps on a regular packing (only what the random
orientation leaves alone: which spheres, masses, radii, member distances to the centroid) and
getRoundness; then a clump of two facets driven by a torque into a free sphere. Runs unchanged in
Yade (`yade -n -x`) and in Talus; prints the results as JSON (tests/dem/core/test_clump_operations.py).

Yade's Law2_ScGeom_FrictPhys_CundallStrack takes a facet's lever arm from radii
(sphericalBodies=True, its default), wrong for a facet that turns; Talus always takes the
contact point's, which Yade does with sphericalBodies=False: the Yade run sets it."""
import json
import os
import tempfile

try:
    O  # noqa: B018  (defined when Yade runs the script)
    lawOptions = {"sphericalBodies": False}
except NameError:
    from talus.dem import *  # noqa: F401,F403
    lawOptions = {}
from yade import export, ymport
from yade.utils import clumpTemplate

out = {}


def props(i):
    s = O.bodies[i].state
    return {"mass": s.mass, "inertia": sorted(list(s.inertia)), "pos": list(s.pos)}


def memberDistances(c):
    return sorted((O.bodies[m].state.pos - O.bodies[c].state.pos).norm() for m in O.bodies[c].shape.members)


mat = O.materials.append(FrictMat(young=1e7, poisson=0.3, density=1000, frictionAngle=0.3))

# Clumps of given spheres: summed (discretization 0) and on grids (overlapping members).
for disc in (0, 5, 10):
    c, _ = O.bodies.appendClumped([sphere((10 * disc, 0, 1), 0.5), sphere((10 * disc + 0.2, 0, 1), 0.5),
                                   sphere((10 * disc, 0.3, 1.1), 0.3)], discretization=disc)
    out["overlap%d" % disc] = props(c)
c, _ = O.bodies.appendClumped([sphere((0, 5, 1), 0.5), sphere((0.7, 5.2, 1.1), 0.4)])
out["pair"] = dict(props(c), distances=memberDistances(c))
# A box turned about an axis in the xy plane with a sphere in that plane: mirror-symmetric, so
# Yade's box inertia (turned by the inverse orientation, R^T I R) has Talus's eigenvalues.
c, _ = O.bodies.appendClumped([box((3, 10, 0), (0.5, 0.1, 0.2), orientation=Quaternion((1, 1, 0), 0.7)),
                               sphere((3.6, 10.2, 0), 0.3)])
out["boxSphere"] = props(c)

# addToClump: a sphere, then another clump by one of its members (that clump goes). Yade
# 2023.02a then leaves the absorbed members with clumpId -1 while its clump lists them (erasing
# the absorbed clump frees them): their clumpIds are reported, not compared.
c1, ids1 = O.bodies.appendClumped([sphere((0, 20, 1), 0.5), sphere((0.9, 20, 1), 0.4)])
c2, ids2 = O.bodies.appendClumped([sphere((3, 21, 2), 0.5), sphere((3.8, 21, 2), 0.3)])
loose = O.bodies.append(sphere((0, 20.9, 1), 0.45))
O.bodies.addToClump([loose], c1)
out["addSphere"] = props(c1)
O.bodies.addToClump([ids2[1]], c1)
out["addClump"] = dict(props(c1), members=sorted(O.bodies[c1].shape.members.keys()), c2Gone=O.bodies[c2] is None,
                       absorbedClumpIds=[O.bodies[i].clumpId for i in ids2])
# releaseFromClump and erasing a member (which leaves the clump's mass as it was).
c3, ids3 = O.bodies.appendClumped([sphere((0, 30, 1), 0.5), sphere((0.9, 30, 1), 0.4), sphere((0, 30.8, 1.2), 0.3),
                                   sphere((-0.7, 30, 0.8), 0.35)])
O.bodies.releaseFromClump(ids3[2], c3)
out["release"] = dict(props(c3), standalone=O.bodies[ids3[2]].isStandalone)
O.bodies.erase(ids3[0])
out["eraseMember"] = dict(props(c3), members=sorted(O.bodies[c3].shape.members.keys()))

# A checkpoint keeps the clumps.
path = os.path.join(tempfile.mkdtemp(), "clumps.yade.gz")
O.save(path)
O.load(path)
out["loaded"] = dict(props(c3), members=sorted(O.bodies[c3].shape.members.keys()),
                     clumpIds=[O.bodies[m].clumpId for m in sorted(O.bodies[c3].shape.members.keys())],
                     c1=dict(props(c1), members=sorted(O.bodies[c1].shape.members.keys())))

# Text files of clumps: written (same text), read back shifted.
text = os.path.join(os.path.dirname(path), "clumps.txt")
out["exported"] = list(export.textClumps(text))
out["text"] = open(text).read()
made = ymport.textClumps(text, shift=Vector3(0, 0, 5))
out["imported"] = [dict(props(c), members=len(m)) for c, m in made]

# replaceByClumps on a regular packing of 60 spheres, then getRoundness.
O.reset()
O.materials.append(FrictMat(young=1e7, poisson=0.3, density=2000, frictionAngle=0.3))
for k in range(60):
    O.bodies.append(sphere((k % 5, (k // 5) % 4, k // 20), 0.2 + 0.01 * (k % 7)))
out["roundnessSpheres"] = O.bodies.getRoundness()
templates = [clumpTemplate(relRadii=[1, 1], relPositions=[[1, 0, 0], [-1, 0, 0]]),
             clumpTemplate(relRadii=[.5, 1, .5], relPositions=[[1, 0, 0], [0, 0, 0], [-1, 0, 0]])]
replaced = O.bodies.replaceByClumps(templates, [.5, .3])
out["erased"] = [i for i in range(60) if O.bodies[i] is None]
out["replaced"] = [dict(mass=O.bodies[c].state.mass, radii=sorted(O.bodies[m].shape.radius for m in ms),
                        distances=memberDistances(c)) for c, ms in replaced]
standalone = [b.id for b in O.bodies if b.isStandalone]
out["roundness"] = O.bodies.getRoundness()
out["roundnessClumps"] = O.bodies.getRoundness(standalone)

# Two facets clumped, driven by a torque about z into a free sphere (test/clump-facet.py's scene).
O.reset()
O.materials.append(FrictMat(young=1e7, density=1000, frictionAngle=0.3))
O.engines = [
    ForceResetter(),
    InsertionSortCollider([Bo1_Sphere_Aabb(), Bo1_Facet_Aabb()]),
    InteractionLoop([Ig2_Sphere_Sphere_ScGeom(), Ig2_Facet_Sphere_ScGeom()], [Ip2_FrictMat_FrictMat_FrictPhys()],
                    [Law2_ScGeom_FrictPhys_CundallStrack(**lawOptions)]),
    NewtonIntegrator(),
]
free = O.bodies.append(sphere((2, 2, 0), 1))
O.bodies.append(sphere((-2, 2, 0), 1, fixed=True))
f1 = facet(((0, 0, -2), (0, 0, 2), (+5, 0, 0)))
f2 = facet(((0, 0, -2), (0, 0, 2), (-5, 0, 0)))
f1.state.mass = f2.state.mass = 1
f2.state.inertia = (1, 1, 1)
clumpId, _ = O.bodies.appendClumped((f1, f2))
out["facets"] = props(clumpId)
s = O.bodies[clumpId].state
s.mass = 5000
s.inertia = 10000 * Vector3(1, 1, 1)
s.blockedDOFs = 'xyzXY'
O.forces.setPermT(clumpId, (0, 0, 5e4))
O.dt = 5e-5
track = []
for k in range(12):
    O.run(1000, True)
    track.append([O.bodies[clumpId].state.angVel[2]] + list(O.bodies[free].state.pos))
out["impact"] = track
print("RESULT " + json.dumps(out))
