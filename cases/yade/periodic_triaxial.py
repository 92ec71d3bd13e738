"""Scenario: the seed's periodic triaxial tutorial (06-periodic-triaxial-test, uniform cloud, or with
`clumps` > 0 the tutorial's variant: that many clumps of its three-sphere template by makeClumpCloud).
Runs unchanged in Yade (`yade -n -x`) and in Talus; parameters from $TALUS_SCENARIO (JSON), result
printed as one `RESULT {json}` line (see talus.twin).

1. A periodic cloud (makeCloud, seeded) compacted isotropically to sigmaIso by PeriTriaxController
   (dynCell, maxUnbalanced 0.1, relStressTol 1e-3); the doneHook ends the stage.
2. Strain-controlled compression along z (rate `rate`) to the log strain `ezzGoal` with sigmaIso
   kept on x and y (stressMask 3).
"""
import json
import os

try:
    O  # noqa: B018  (defined when Yade runs the script)
    from yade import pack
except NameError:
    from talus.dem import *  # noqa: F401,F403

P = {"size": 2.0, "rMean": .1, "rRelFuzz": .3, "seed": 1, "sigmaIso": -1e5, "ezzGoal": -.2, "rate": .1,
     "friction": .5, "clumps": 0, "compactionRate": 10, **json.loads(os.environ.get("TALUS_SCENARIO", "{}"))}
sigmaIso = P["sigmaIso"]

O.periodic = True
O.materials.append(FrictMat(young=1e7, poisson=.3, frictionAngle=P["friction"], density=1000))
sp = pack.SpherePack()
if P["clumps"]:
    c1 = pack.SpherePack([((0, 0, 0), .03333), ((.03, 0, 0), .017), ((0, .03, 0), .017)])
    sp.makeClumpCloud((0, 0, 0), (P["size"],) * 3, [c1], periodic=True, num=P["clumps"], seed=P["seed"])
else:
    sp.makeCloud((0, 0, 0), (P["size"],) * 3, rMean=P["rMean"], rRelFuzz=P["rRelFuzz"], periodic=True,
                 seed=P["seed"])
sp.toSimulation()

O.engines = [
    ForceResetter(),
    InsertionSortCollider([Bo1_Sphere_Aabb()]),
    InteractionLoop([Ig2_Sphere_Sphere_ScGeom()], [Ip2_FrictMat_FrictMat_FrictPhys()],
                    [Law2_ScGeom_FrictPhys_CundallStrack()]),
    PeriTriaxController(label='triax', goal=(sigmaIso, sigmaIso, sigmaIso), stressMask=7, dynCell=True,
                        maxStrainRate=(P["compactionRate"],) * 3, maxUnbalanced=.1, relStressTol=1e-3,
                        doneHook='compactionFinished()'),
    NewtonIntegrator(damping=.2),
    PyRunner(command='addData()', iterPeriod=50),
]
O.dt = .5 * PWaveTimeStep()
history = {k: [] for k in ("i", "stage", "exx", "eyy", "ezz", "sxx", "syy", "szz", "unbalanced")}
state = {"stage": 0}
compaction = {}


def addData():
    for k, v in (("i", O.iter), ("stage", state["stage"]), ("unbalanced", unbalancedForce())):
        history[k].append(float(v))
    for a, axis in enumerate("xyz"):
        history["e" + axis * 2].append(float(triax.strain[a]))
        history["s" + axis * 2].append(float(triax.stress[a]))


def compactionFinished():
    compaction.update(iter=O.iter, stress=[float(x) for x in triax.stress], unbalanced=float(unbalancedForce()),
                      porosity=float(porosity()), coordination=float(avgNumInteractions()))
    O.cell.trsf = Matrix3.Identity
    triax.goal = (sigmaIso, sigmaIso, P["ezzGoal"])
    triax.stressMask = 3
    triax.maxStrainRate = (1., 1., P["rate"])
    triax.doneHook = 'triaxFinished()'
    triax.maxUnbalanced = 10
    state["stage"] = 1


def triaxFinished():
    addData()
    O.pause()


O.run(-1, True)
print("RESULT " + json.dumps({"compaction": compaction, "history": history, "spheres": len(O.bodies),
                              "final_strain": [float(x) for x in triax.strain], "iter": O.iter}))
