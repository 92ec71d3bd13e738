"""Yade's test/exact-rot.py without its views: two spheres in contact turned by
RotationEngines, gravity. With {"oldStyle": true} (Talus) the engine list is the example's
IGeomDispatcher, IPhysDispatcher, ElasticContactLaw (after a RotationEngine, as shear.py has
it); else the InteractionLoop it stands for, which is what Yade 2023.02a can run (its standalone
IGeomDispatcher aborts). Prints RESULT with the final state (tests/dem/laws/test_legacy_engines.py)."""
import json
import os
from math import sqrt

try:
    O  # noqa: B018  (defined when Yade runs the script)
except NameError:
    from talus.dem import *  # noqa: F401,F403

geometry, physics = [Ig2_Sphere_Sphere_ScGeom(), Ig2_Facet_Sphere_ScGeom()], [Ip2_FrictMat_FrictMat_FrictPhys()]
turn1 = RotationEngine(ids=[1], rotationAxis=(1, 0, 0), angularVelocity=.01)
if json.loads(os.environ.get("TALUS_SCENARIO", "{}")).get("oldStyle"):
    contacts = [IGeomDispatcher(geometry), IPhysDispatcher(physics), turn1, ElasticContactLaw(label="law")]
else:
    contacts = [InteractionLoop(geometry, physics, [Law2_ScGeom_FrictPhys_CundallStrack()]), turn1]
O.engines = ([ForceResetter(), InsertionSortCollider([Bo1_Sphere_Aabb(), Bo1_Box_Aabb()])] + contacts
             + [RotationEngine(ids=[0], rotationAxis=(1, 1, 1), angularVelocity=-.02),
                NewtonIntegrator(damping=.2, gravity=(0, 0, -9.81))])
O.bodies.append(sphere([0, 0, 0], 1, fixed=True))
O.bodies.append(sphere([0, sqrt(2), sqrt(2)], 1))
O.dt = .01 * PWaveTimeStep()
O.run(20000, True)
i = O.interactions[0, 1]
print("RESULT " + json.dumps({"bodies": [list(b.state.pos) + list(b.state.angVel) for b in O.bodies],
                              "fn": list(i.phys.normalForce), "fs": list(i.phys.shearForce)}))
