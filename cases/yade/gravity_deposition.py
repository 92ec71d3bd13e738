"""Scenario: the seed's gravity deposition tutorial (02-gravity-deposition): a seeded cloud
(makeCloud, rMean `rMean`, rRelFuzz 0.5) falls into a facet box with an open top (FrictMat defaults,
damping 0.4, dt 0.5 P-wave) for the simulated time `time` (the same steps in both programs), or,
without it, until the unbalanced force is below `unbalanced` (checked every 200 steps, after
`minIter`). Runs unchanged in Yade (`yade -n -x`) and in Talus; parameters from
$TALUS_SCENARIO (JSON), result printed as one `RESULT {json}` line (see talus.twin).

Measured, the same way in both programs: the porosity of the slab z in [zLow, zHigh] (sphere volume
inside it, exact caps, over the slab volume) and the sphere-sphere coordination 2 C / N.
"""
import json
import math
import os

try:
    O  # noqa: B018  (defined when Yade runs the script)
    from yade import pack

    def contact_pairs():
        return [(i.id1, i.id2) for i in O.interactions if i.isReal]
except NameError:
    from talus.dem import *  # noqa: F401,F403

    def contact_pairs():
        return [(c["id1"], c["id2"]) for c in O.contacts()]

P = {"rMean": .05, "seed": 1, "time": None, "unbalanced": .05, "minIter": 2000, "zLow": .05, "zHigh": .2,
     **json.loads(os.environ.get("TALUS_SCENARIO", "{}"))}

O.bodies.append(geom.facetBox((.5, .5, .5), (.5, .5, .5), wallMask=31))
sp = pack.SpherePack()
sp.makeCloud((0, 0, 0), (1, 1, 1), rMean=P["rMean"], rRelFuzz=.5, seed=P["seed"])
spheres = set(sp.toSimulation())
O.engines = [
    ForceResetter(),
    InsertionSortCollider([Bo1_Sphere_Aabb(), Bo1_Facet_Aabb()]),
    InteractionLoop([Ig2_Sphere_Sphere_ScGeom(), Ig2_Facet_Sphere_ScGeom()], [Ip2_FrictMat_FrictMat_FrictPhys()],
                    [Law2_ScGeom_FrictPhys_CundallStrack()]),
    NewtonIntegrator(gravity=(0, 0, -9.81), damping=0.4),
]
O.dt = .5 * PWaveTimeStep()

if P["time"] is not None:
    O.run(int(P["time"] / O.dt), True)
while P["time"] is None:
    O.run(200, True)
    if O.iter >= P["minIter"] and unbalancedForce() < P["unbalanced"]:
        break
    if O.iter > 500000:
        raise RuntimeError("the deposit did not settle")


def cap(r, h):
    """Volume of a spherical cap of height h (0 <= h <= 2 r)."""
    h = min(max(h, 0.0), 2 * r)
    return math.pi * h * h * (3 * r - h) / 3


solid, top = 0.0, 0.0
for i in spheres:
    b = O.bodies[i]
    z, r = b.state.pos[2], (b.shape.radius if hasattr(b.shape, "radius") else b.radius)
    # volume of the ball between the planes zLow and zHigh
    solid += cap(r, P["zHigh"] - (z - r)) - cap(r, P["zLow"] - (z - r))
    top = max(top, z + r)
pairs = contact_pairs()
between = sum(1 for a, b in pairs if a in spheres and b in spheres)
print("RESULT " + json.dumps({"porosity": 1 - solid / (P["zHigh"] - P["zLow"]), "coordination": 2 * between / len(spheres),
                              "spheres": len(spheres), "iter": O.iter, "time": O.time, "top": top,
                              "unbalanced": unbalancedForce()}))
