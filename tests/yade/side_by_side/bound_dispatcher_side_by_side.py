"""A BoundDispatcher alone in O.engines (Yade's test/pack-cloud.py has one), written so that the
same file runs in Yade (`yade -n -x`) and in Talus: before a collider it changes nothing, and a
list of it alone runs. Prints one RESULT line (tests/yade/test_bound_dispatcher.py)."""
import json

try:
    O  # noqa: B018  (defined when Yade runs the script)
except NameError:
    from talus.dem import *  # noqa: F401,F403

O.materials.append(FrictMat(young=1e7, density=2600))
O.bodies.append([sphere((0.1 * (i % 3), 0.05 * i, 0.15 + 0.25 * i), 0.12) for i in range(8)])
O.bodies.append(wall(0, axis=2))
O.engines = [ForceResetter(), BoundDispatcher([Bo1_Sphere_Aabb(), Bo1_Wall_Aabb()]),
             InsertionSortCollider([Bo1_Sphere_Aabb(), Bo1_Wall_Aabb()]),
             InteractionLoop([Ig2_Sphere_Sphere_ScGeom(), Ig2_Wall_Sphere_ScGeom()], [Ip2_FrictMat_FrictMat_FrictPhys()],
                             [Law2_ScGeom_FrictPhys_CundallStrack()]),
             NewtonIntegrator(gravity=(0, 0, -9.81), damping=0.3)]
O.dt = 2e-4
O.run(2000, True)
positions = [list(b.state.pos) for b in O.bodies if isinstance(b.shape, Sphere)]
O.engines = [BoundDispatcher([Bo1_Sphere_Aabb()])]
O.run(3, True)
print("RESULT " + json.dumps({"positions": positions, "alone": [type(e).__name__ for e in O.engines], "iter": O.iter}))
