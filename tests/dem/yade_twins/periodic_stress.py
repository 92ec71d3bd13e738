"""A dense periodic packing (150 spheres, stored in periodic_packing.json, sheared cell): one
step of contact forces and the homogenised stress, written so the same file runs in Yade
(`yade -n -x`) and in Talus. Prints getStress() and the number of contacts as `RESULT {...}` (talus.dem.twin)."""
import json

import numpy as np

try:
    O  # noqa: B018  (defined when Yade runs the script)
except NameError:
    from talus.dem import *  # noqa: F401,F403

data = json.load(open("periodic_packing.json"))  # run from this folder (Yade has no __file__ of the script)
O.periodic = True
O.cell.hSize = Matrix3(*[x for row in data["hSize"] for x in row])
O.materials.append(FrictMat(young=1e7, poisson=0.3, frictionAngle=0.5, density=2600))
O.bodies.append([sphere(tuple(c), r) for c, r in zip(data["pos"], data["radius"])])
O.engines = [
    ForceResetter(),
    InsertionSortCollider([Bo1_Sphere_Aabb()]),
    InteractionLoop([Ig2_Sphere_Sphere_ScGeom()], [Ip2_FrictMat_FrictMat_FrictPhys()],
                    [Law2_ScGeom_FrictPhys_CundallStrack()]),
    NewtonIntegrator(damping=0.0),
]
O.dt = 1e-12
O.step()
print("RESULT " + json.dumps({"stress": np.array(getStress()).tolist(), "contacts": avgNumInteractions()}))
