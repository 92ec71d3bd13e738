"""Clumps of two and three spheres falling onto a wall in a loose grid, with friction and Cundall
damping, energy tracked. Runs unchanged in Yade (`yade -n -x`) and in Talus (talus.twin);
prints the energies (O.energy), the clumps' kinetic energy computed here from their state as rigid
bodies (1/2 m v^2 + 1/2 w.R I R^T w, principal moments I), the real contact count and the iteration
as JSON. $TALUS_SCENARIO: {"steps": n, "damping": d, "dt": dt}."""
import json
import math
import os

try:
    O  # noqa: B018  (defined when Yade runs the script)
    real_contacts = O.interactions.countReal
except NameError:
    from talus.dem import *  # noqa: F401,F403
    real_contacts = O._cpp.realContactCount

params = json.loads(os.environ.get("TALUS_SCENARIO", "{}"))
O.materials.append(FrictMat(young=1e7, poisson=0.3, density=2600, frictionAngle=0.5))
O.bodies.append(wall(0, axis=2, sense=1))
# A dumbbell and an unequal triangle, offsets from a grid point (the clumps start apart, at rest:
# Yade would ignore an angular velocity set on a clump, its integrator keeps the angular
# momentum, which angVel does not set).
shapes = [[((0, 0, 0), 0.05), ((0.08, 0, 0.02), 0.04)],
          [((0, 0, 0), 0.05), ((0.07, 0, 0), 0.04), ((0.02, 0.06, 0.01), 0.035)]]
clumps = []
for layer in range(2):
    for i in range(3):
        for j in range(3):
            origin = (0.2 * i + 0.03 * layer, 0.2 * j + 0.02 * (i % 2), 0.15 + 0.2 * layer + 0.01 * j)
            members = shapes[(i + j + layer) % 2]
            cid, _ = O.bodies.appendClumped([sphere(tuple(o + d for o, d in zip(origin, c)), r) for c, r in members])
            clumps.append(cid)
O.engines = [
    ForceResetter(),
    InsertionSortCollider([Bo1_Sphere_Aabb(), Bo1_Wall_Aabb()]),
    InteractionLoop([Ig2_Sphere_Sphere_ScGeom(), Ig2_Wall_Sphere_ScGeom()], [Ip2_FrictMat_FrictMat_FrictPhys()],
                    [Law2_ScGeom_FrictPhys_CundallStrack()]),
    NewtonIntegrator(gravity=(0, 0, -9.81), damping=params.get("damping", 0.3)),
]
O.dt = params.get("dt", 2e-4)  # 2e-4: about 0.33 PWaveTimeStep(), written out so both programs use the same bits
O.trackEnergy = True


def rigid_kinetic():
    """Kinetic energy of the clumps as rigid bodies, from their state (world inertia R I R^T)."""
    total = 0.0
    for cid in clumps:
        s = O.bodies[cid].state
        v, w, q = s.vel, s.angVel, s.ori
        # w in the principal frame: the conjugate rotation of w
        R = q.toRotationMatrix()
        body = [sum(R[k][a] * w[k] for k in range(3)) for a in range(3)]
        total += 0.5 * s.mass * sum(x * x for x in v) + 0.5 * sum(s.inertia[a] * body[a] ** 2 for a in range(3))
    return total


start = rigid_kinetic()
O.run(params.get("steps", 8000), True)
print("RESULT " + json.dumps({"energy": {k: O.energy[k] for k in O.energy.keys()}, "total": O.energy.total(),
                              "startKinetic": start, "rigidKinetic": rigid_kinetic(),
                              "contacts": real_contacts(), "iter": O.iter}))
