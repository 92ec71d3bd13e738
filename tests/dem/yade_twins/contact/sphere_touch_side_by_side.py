"""When two spheres touch, to the last bit: written so that the same file runs in Yade
(`yade -n -x`) and in Talus (tests/dem/contact/test_sphere_touch.py); the scenario is the
parameter "case":
- "lattice": a regularHexa packing with no gap (pairs touching exactly), one step: the pairs in
  contact, and how many of the touching pairs each order of |d|^2 would count (Yade's sum
  x^2 + (y^2 + z^2), the vectorised (x^2 + y^2) + z^2), to show the scene tells them apart;
- "hold": pairs of fixed spheres, overlapping, then moved apart to where |d|^2 > (r1 + r2)^2
  while r1 + r2 - sqrt(|d|^2) rounds to 0 (enough pairs for the four-lane path): whether each
  contact is still real one and two steps later; and the same places from the start, where no
  contact begins."""
import json
import math
import os
import random

try:
    O  # noqa: B018  (defined when Yade runs the script)
except NameError:
    from talus.dem import *  # noqa: F401,F403

case = json.loads(os.environ.get("TALUS_SCENARIO", "{}")).get("case", "lattice")
R = 2.8


def engines():
    return [ForceResetter(), InsertionSortCollider([Bo1_Sphere_Aabb()]),
            InteractionLoop([Ig2_Sphere_Sphere_ScGeom()], [Ip2_FrictMat_FrictMat_FrictPhys()],
                            [Law2_ScGeom_FrictPhys_CundallStrack()]),
            NewtonIntegrator(gravity=(0, 0, 0))]


def real_pairs():
    return sorted([int(i.id1), int(i.id2)] for i in O.interactions if i.isReal)


O.materials.append(FrictMat(young=5e6, poisson=0.5, frictionAngle=0, density=2600))
result = {}
if case == "lattice":
    O.bodies.append(pack.regularHexa(pack.inAlignedBox((0, 0, 0), (40, 40, 40)), radius=R, gap=0))
    O.engines = engines()
    O.dt = 1e-5
    O.step()
    pos = [tuple(float(c) for c in b.state.pos) for b in O.bodies]
    yade_order = vectorised = 0
    for i in range(len(pos)):
        for j in range(i + 1, len(pos)):
            x, y, z = (pos[j][k] - pos[i][k] for k in range(3))
            yade_order += x * x + (y * y + z * z) <= (R + R) * (R + R)
            vectorised += (x * x + y * y) + z * z <= (R + R) * (R + R)
    result = {"pairs": real_pairs(), "yade_order": yade_order, "vectorised": vectorised}
elif case == "hold":
    # Centre offsets where the squared test fails in both orders but the penetration is 0.
    rng, reach, offsets = random.Random(1), R + R, []
    while len(offsets) < 8:
        k = len(offsets)
        u = [rng.gauss(0, 1) for _ in range(3)]
        norm = math.sqrt(sum(t * t for t in u))
        p1 = (20.0 * k, 0.0, 0.0)
        p2 = tuple(p1[a] + reach * u[a] / norm for a in range(3))
        x, y, z = (p2[a] - p1[a] for a in range(3))
        if min(x * x + (y * y + z * z), (x * x + y * y) + z * z) > reach * reach and reach - math.sqrt(x * x + (y * y + z * z)) == 0:
            offsets.append((p1, p2))
    rows = []
    for start in ("overlapping", "apart"):
        O.reset()
        O.materials.append(FrictMat(young=5e6, poisson=0.5, frictionAngle=0, density=2600))
        for p1, p2 in offsets:
            near = tuple(p1[a] + 0.99 * (p2[a] - p1[a]) for a in range(3))
            O.bodies.append([sphere(p1, R, fixed=True), sphere(near if start == "overlapping" else p2, R, fixed=True)])
        O.engines = engines()
        O.dt = 1e-5
        O.step()
        begun = len(real_pairs())
        for k, (p1, p2) in enumerate(offsets):
            O.bodies[2 * k + 1].state.pos = p2
        O.step()
        once = real_pairs()
        O.step()
        rows.append({"begun": begun, "after one step": once, "after two": real_pairs()})
    result = {"overlapping": rows[0], "apart": rows[1]}
print("RESULT " + json.dumps(result))
