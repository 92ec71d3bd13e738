"""Scenario (talus.dem.twin): an exported RVE packing (rve_packing.json, written by the test)
built as a periodic scene in Yade and in Talus, deformed by the displacement gradient G over
nSteps steps (L_k dt = (G / n) (I + (k - 1) / n G)^-1, the Gauss-point calls' sub-steps). Yade
steps O.cell.velGrad itself; Talus hands the scene to talus.fem.MultiscaleRVEs, whose C++ RVE
does the same. Prints `RESULT {stress, tangent}`: Yade's getStressAndTangent and Talus's
Gauss-point getStressAndTangent with form="yade"."""
import json
import os

import numpy as np

try:
    O  # noqa: B018  (defined when Yade runs the script)
    talus = False
except NameError:
    from talus.dem import *  # noqa: F401,F403
    talus = True

P = json.loads(os.environ.get("TALUS_SCENARIO", "{}"))
data = json.load(open("rve_packing.json"))
G, n = np.array(P["G"]), int(P["nSteps"])
O.periodic = True
O.cell.hSize = Matrix3(*np.array(data["hSize"]).ravel())
O.materials.append(FrictMat(young=data["young"], poisson=data["poisson"], frictionAngle=data["frictionAngle"],
                            density=data["density"]))
O.bodies.append([sphere(tuple(c), r) for c, r in zip(data["pos"], data["radius"])])
O.engines = [
    ForceResetter(),
    InsertionSortCollider([Bo1_Sphere_Aabb()]),
    InteractionLoop([Ig2_Sphere_Sphere_ScGeom()], [Ip2_FrictMat_FrictMat_FrictPhys()],
                    [Law2_ScGeom_FrictPhys_CundallStrack()]),
    NewtonIntegrator(damping=0.2),
]
O.dt = data["dt"]
if talus:
    from talus.fem import MultiscaleRVEs
    rves = MultiscaleRVEs([O], nSteps=n, form="yade")
    rves.run(G[None])
    stress, tangent = (x[0] for x in rves.getStressAndTangent())
else:
    for k in range(n):
        O.cell.velGrad = Matrix3(*((G / n) @ np.linalg.inv(np.eye(3) + k / n * G) / O.dt).ravel())
        O.run(1, True)
    stress, tangent = getStressAndTangent(O.cell.volume, True)
    tangent = np.array(tangent)
    tangent = np.triu(tangent) + np.triu(tangent, 1).T     # Yade fills the upper triangle only
print("RESULT " + json.dumps({"stress": np.array(stress).tolist(), "tangent": np.array(tangent).tolist()}))
