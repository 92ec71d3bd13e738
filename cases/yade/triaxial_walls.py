"""Scenario: drained triaxial compression in a box of six walls (Yade's triax-tutorial, session 1).
Runs unchanged in Yade (`yade -n -x`) and in Talus; parameters from $TALUS_SCENARIO (JSON), result
printed as one `RESULT {json}` line (see talus.twin).

1. A loose seeded cloud (makeCloud, porosity 0.95) between six frictionless walls is compacted
   isotropically to `sigma` by growing the spheres (TriaxialStressController, internalCompaction)
   with the low friction `compFriction` (a dense sample), until the mean stress is within 0.1 % of
   the goal and the unbalanced force below `unbalanced`.
2. The friction is set to `friction` (setContactFriction) and the walls take over: y is compressed
   at the strain rate `rate` while x and z are held at `sigma` (stressMask 5), up to the axial log
   strain `eyyEnd`.
"""
import json
import math
import os

try:
    O  # noqa: B018  (defined when Yade runs the script)
    from yade import pack
except NameError:
    from talus.dem import *  # noqa: F401,F403

P = {"num": 500, "seed": 1, "young": 5e6, "friction": 30.0, "compFriction": 5.0, "sigma": -1e4, "rate": -0.02, "eyyEnd": -0.12,
     "unbalanced": 0.01, "damping": 0.2, **json.loads(os.environ.get("TALUS_SCENARIO", "{}"))}

O.materials.append(FrictMat(young=P["young"], poisson=0.5, frictionAngle=math.radians(P["compFriction"]),
                            density=2600, label='spheres'))
O.materials.append(FrictMat(young=P["young"], poisson=0.5, frictionAngle=0, density=2600, label='walls'))
lo, hi = (0, 0, 0), (1, 1, 1)
# left, right, bottom, top, back, front: the controller's default ids 0..5
O.bodies.append([wall(corner[axis], axis=axis, material='walls') for axis in range(3) for corner in (lo, hi)])
sp = pack.SpherePack()
sp.makeCloud(lo, hi, -1, 0.3333, P["num"], False, 0.95, seed=P["seed"])
sp.toSimulation(material='spheres')

triax = TriaxialStressController(maxMultiplier=1. + 2e4 / P["young"], finalMaxMultiplier=1. + 2e3 / P["young"],
                                 thickness=0, stressMask=7, internalCompaction=True)
triax.goal1 = triax.goal2 = triax.goal3 = P["sigma"]
O.engines = [
    ForceResetter(),
    InsertionSortCollider([Bo1_Sphere_Aabb(), Bo1_Wall_Aabb()]),
    InteractionLoop([Ig2_Sphere_Sphere_ScGeom(), Ig2_Wall_Sphere_ScGeom()], [Ip2_FrictMat_FrictMat_FrictPhys()],
                    [Law2_ScGeom_FrictPhys_CundallStrack()]),
    GlobalStiffnessTimeStepper(timeStepUpdateInterval=100, timestepSafetyCoefficient=0.8),
    triax,
    NewtonIntegrator(damping=P["damping"]),
]

while True:
    O.run(500, True)
    if unbalancedForce() < P["unbalanced"] and abs(P["sigma"] - triax.meanStress) / abs(P["sigma"]) < 0.001:
        break
    if O.iter > 200000:
        raise RuntimeError("the isotropic compaction did not converge")
compaction = {"iter": O.iter, "meanStress": triax.meanStress, "porosity": triax.porosity,
              "coordination": avgNumInteractions(), "unbalanced": unbalancedForce()}

triax.internalCompaction = False
setContactFriction(math.radians(P["friction"]))
triax.stressMask = 5
triax.goal1 = triax.goal3 = P["sigma"]
triax.goal2 = P["rate"]
# strains from here on
triax.width0, triax.height0, triax.depth0 = triax.width, triax.height, triax.depth
history = {k: [] for k in ("i", "eyy", "evol", "sxx", "syy", "szz", "unbalanced")}


def record():
    history["i"].append(O.iter)
    history["eyy"].append(float(math.log(triax.height / triax.height0)))
    history["evol"].append(float(math.log(triax.width * triax.height * triax.depth
                                          / (triax.width0 * triax.height0 * triax.depth0))))
    history["sxx"].append(float(triax.stress(1)[0]))
    history["syy"].append(float(triax.stress(3)[1]))
    history["szz"].append(float(triax.stress(5)[2]))
    history["unbalanced"].append(float(unbalancedForce()))


while True:
    O.run(100, True)
    record()
    if history["eyy"][-1] <= P["eyyEnd"]:
        break
print("RESULT " + json.dumps({"compaction": compaction, "history": history, "spheres": len(O.bodies) - 6,
                              "iter": O.iter, "dt": O.dt}))
