"""Yade's ResetRandomPosition, written so that the same file runs in Yade (`yade -n -x`) and in
Talus: spheres fall through the plane z = 0 and are put back on two facets without bound at
z = 0.5, with random velocities. Yade's generators have fixed
seeds: the places are compared, not only their statistics. Prints one RESULT line: each
re-insertion (step, id, position, velocity, angular velocity)."""
import json

try:
    O  # noqa: B018  (defined when Yade runs the script)
except NameError:
    from talus.dem import *  # noqa: F401,F403

mat = O.materials.append(ViscElMat(density=2700, frictionAngle=0.5, tc=1e-3, en=0.3, et=0.3))
top = O.bodies.append([facet([(-0.3, -0.3, 0.5), (0.3, -0.3, 0.5), (0.3, 0.3, 0.5)], material=mat, noBound=True),
                       facet([(-0.3, -0.3, 0.5), (0.3, 0.3, 0.5), (-0.3, 0.3, 0.5)], material=mat,
                             noBound=True)])
spheres = O.bodies.append([sphere((0.1 * (i % 5) - 0.2, 0.1 * (i // 5) - 0.2, 0.05 + 0.01 * i), 0.03, material=mat)
                           for i in range(25)])
O.engines = [
    ForceResetter(),
    InsertionSortCollider([Bo1_Sphere_Aabb(), Bo1_Facet_Aabb()]),
    InteractionLoop([Ig2_Sphere_Sphere_ScGeom(), Ig2_Facet_Sphere_ScGeom()], [Ip2_ViscElMat_ViscElMat_ViscElPhys()],
                    [Law2_ScGeom_ViscElPhys_Basic()]),
    NewtonIntegrator(damping=0, gravity=(0, 0, -9.81)),
    ResetRandomPosition(virtPeriod=0.01, factoryFacets=top, subscribedBodies=spheres, point=(0, 0, 0), normal=(0, 0, 1),
                        velocity=(0, 0, -2), velocityRange=(0.5, 0.3, 0.1), angularVelocity=(1, 0, 0),
                        angularVelocityRange=(0, 2, 0), maxAttempts=20),
]
O.dt = 2e-4
moves, height = [], {i: O.bodies[i].state.pos[2] for i in spheres}
for step in range(1500):
    O.step()
    for i in spheres:
        s = O.bodies[i].state
        if s.pos[2] - height[i] > 0.1:
            moves.append([O.iter, i] + list(s.pos) + list(s.vel) + list(s.angVel))
        height[i] = s.pos[2]
print("RESULT " + json.dumps(moves))
