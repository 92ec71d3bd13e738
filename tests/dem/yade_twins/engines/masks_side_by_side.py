"""Group masks, written so that the same file runs in Yade (`yade -n -x`) and in Talus
(tests/dem/contact/test_masks.py); the scenario is the parameter "case":
- "fall": spheres of masks 1, 2, 3 fall through a mask-0 box (the VANS examples' water surface)
  onto a mask-1 floor box; the first one's mask is then changed to 2 while it rests on the floor
  (the contact lasts, as in Yade); prints positions every 100 steps;
- "groups": Yade's avoidSelfInteractionMask check (checkAvoidSelfInteractionMask.py): six
  overlapping spheres of masks 2, 1, 3, for each avoidSelfInteractionMask 0..3 the pairs of masks
  that touch after one step, in an open and in a periodic scene;
- "engines": GravityEngine(mask=2) and NewtonIntegrator(mask=1) on spheres of masks 1, 2, 3."""
import json
import os

try:
    O  # noqa: B018  (defined when Yade runs the script)
except NameError:
    from talus.dem import *  # noqa: F401,F403

case = json.loads(os.environ.get("TALUS_SCENARIO", "{}")).get("case", "fall")


def engines(**collider):
    return [ForceResetter(), InsertionSortCollider([Bo1_Sphere_Aabb(), Bo1_Box_Aabb()], **collider),
            InteractionLoop([Ig2_Sphere_Sphere_ScGeom(), Ig2_Box_Sphere_ScGeom()], [Ip2_FrictMat_FrictMat_FrictPhys()],
                            [Law2_ScGeom_FrictPhys_CundallStrack()])]


rows = []
if case == "fall":
    O.materials.append(FrictMat(density=2000, young=1e7, poisson=0.3, frictionAngle=0.5))
    O.bodies.append(box((0, 0, 0.5), (1, 1, 0.01), fixed=True, mask=0))
    O.bodies.append(box((0, 0, 0), (1, 1, 0.05), fixed=True))
    ids = O.bodies.append([sphere((x, 0, 0.8), 0.1, mask=m) for x, m in ((-0.5, 1), (0, 2), (0.5, 3))])
    O.engines = engines() + [NewtonIntegrator(gravity=(0, 0, -9.81), damping=0.9)]
    O.dt = 2e-4
    for k in range(8):
        if k == 6:
            O.bodies[ids[0]].mask = 2
        O.run(1500, True)
        rows.append([O.bodies[i].state.pos[2] for i in ids] + [O.bodies[i].mask for i in ids]
                    + [len([c for c in O.interactions if c.isReal])])
elif case == "groups":
    for periodic in (False, True):
        for avoid in (0, 1, 2, 3):
            O.reset()
            if periodic:
                O.periodic = True
                O.cell.setBox(10, 10, 10)
            O.engines = engines(avoidSelfInteractionMask=avoid) + [NewtonIntegrator()]
            masks = (2, 2, 1, 1, 3, 3)
            places = ((0, 0, 0), (0, 0.1, 0), (0.1, 0, 0), (0, 0, 0.1), (-0.1, 0, 0), (0, -0.1, 0))
            if periodic:   # the same pairs, some across the cell's faces
                places = tuple((x + 9.95 * (k % 2), y, z) for k, (x, y, z) in enumerate(places))
            O.bodies.append([sphere(p, 1, mask=m) for p, m in zip(places, masks)])
            O.dt = 1e-9
            if hasattr(O, "maxOverlapRatio"):   # Talus's check of created overlaps: these are on purpose
                O.maxOverlapRatio = 10
            O.run(1, True)
            pairs = sorted({tuple(sorted((O.bodies[c.id1].mask, O.bodies[c.id2].mask))) for c in O.interactions
                            if c.isReal})
            rows.append([avoid, periodic, [list(p) for p in pairs]])
elif case == "engines":
    O.materials.append(FrictMat(density=2000, young=1e7, poisson=0.3, frictionAngle=0.5))
    ids = O.bodies.append([sphere((3 * k, 0, 0), 0.1, mask=m) for k, m in enumerate((1, 2, 3))])
    for i in ids:
        O.bodies[i].state.vel = (1, 0, 0)
    O.engines = engines() + [GravityEngine(gravity=(0, 0, -9.81), mask=2, warnOnce=False),
                             NewtonIntegrator(gravity=(0, -1, 0), damping=0.0, mask=1)]
    O.dt = 1e-3
    O.run(100, True)
    rows = [[float(x) for i in ids for x in tuple(O.bodies[i].state.pos) + tuple(O.bodies[i].state.vel)]]
print("RESULT " + json.dumps(rows))
