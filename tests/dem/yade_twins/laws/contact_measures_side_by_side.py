"""A jittered, slightly overlapping lattice of spheres on a wall, stepped three times (the
contacts still closed), written so that the same file runs in Yade (`yade -n -x`) and in Talus:
prints the per-body stresses (bodyStressTensors), the number of contacts and the spheres touching
the wall as JSON (one RESULT line)."""
import json
import math

try:
    O  # noqa: B018  (defined when Yade runs the script)
    real_contacts = O.interactions.countReal
except NameError:
    from talus.dem import *  # noqa: F401,F403
    real_contacts = O._cpp.realContactCount

R, N = 0.1, 4
O.materials.append(FrictMat(young=1e7, poisson=.3, frictionAngle=.4, density=2600))
O.bodies.append([wall(0, axis=2, sense=1)])
for i in range(N):
    for j in range(N):
        for k in range(N):
            n = i + N * (j + N * k)
            # deterministic jitter: the same numbers in both programs
            jitter = [0.01 * R * math.sin(1.3 * n + a) for a in (0.0, 2.0, 4.0)]
            center = [2 * R * 0.97 * (i + 0.5) + jitter[0], 2 * R * 0.97 * (j + 0.5) + jitter[1],
                      2 * R * 0.97 * (k + 0.5) + jitter[2]]
            O.bodies.append(sphere(center, R * (1 + 0.02 * math.cos(n))))
O.engines = [
    ForceResetter(),
    InsertionSortCollider([Bo1_Sphere_Aabb(), Bo1_Wall_Aabb()]),
    InteractionLoop([Ig2_Sphere_Sphere_ScGeom(), Ig2_Wall_Sphere_ScGeom()], [Ip2_FrictMat_FrictMat_FrictPhys()],
                    [Law2_ScGeom_FrictPhys_CundallStrack()]),
    NewtonIntegrator(damping=0.2, gravity=(0, 0, -9.81)),
]
O.dt = 0.3 * PWaveTimeStep()
O.run(3, True)
print("RESULT " + json.dumps({
    "stress": [[float(s[a, b]) for a in range(3) for b in range(3)] for s in bodyStressTensors()],
    "contacts": int(real_contacts()),
    "onWall": [b.id for b in O.bodies if hasattr(b.shape, "radius") and b.state.pos[2] < b.shape.radius],
}))
