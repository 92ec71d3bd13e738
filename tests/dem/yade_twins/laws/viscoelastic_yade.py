"""Visco-elastic contacts (ViscElMat) in small scenes, run unchanged by `yade -x` and `talus run`:
prints one line "JSON {...}" with each scene's contact parameters and its bodies' motion, for
tests/dem/laws/test_viscoelastic_yade.py to compare. Scenes: the young/en form on sphere pairs of
several restitutions; an oblique sphere-sphere and a sphere-wall impact (young/en, tc, kn
forms); spheres on a facet, a box and a fixed sphere; rolling resistance (mRtype 1 and 2);
Ip2 MatchMakers; lubrication."""
import json
import math

out = {}
ENGINES = lambda: [ForceResetter(), InsertionSortCollider([Bo1_Sphere_Aabb(), Bo1_Wall_Aabb(), Bo1_Facet_Aabb(), Bo1_Box_Aabb()]),
                   InteractionLoop([Ig2_Sphere_Sphere_ScGeom(), Ig2_Wall_Sphere_ScGeom(), Ig2_Facet_Sphere_ScGeom(),
                                    Ig2_Box_Sphere_ScGeom()], [Ip2_ViscElMat_ViscElMat_ViscElPhys()],
                                   [Law2_ScGeom_ViscElPhys_Basic()]),
                   NewtonIntegrator(damping=0, gravity=(0, 0, -9.81))]


def phys():
    return sorted([I.id1, I.id2, I.phys.kn, I.phys.cn, I.phys.ks, I.phys.cs, I.phys.tangensOfFrictionAngle]
                  for I in O.interactions)


def motion(ids, chunks, steps):
    rows = []
    for _ in range(chunks):
        O.run(steps, True)
        for i in ids:
            s = O.bodies[i].state
            rows.append(list(s.pos) + list(s.vel) + list(s.angVel))
    return rows


# 1. Two equal spheres (E 1e7, r 1 cm, density 2500) touching: the dashpot for each en.
O.reset()
for k, en in enumerate([0.1, 0.3, 0.5, 0.7, 0.9, 0.99]):
    m = O.materials.append(ViscElMat(young=1e7, poisson=0.3, en=en, et=0.0, density=2500))
    O.bodies.append([sphere((k, 0, 0), 0.01, material=m), sphere((k, 0, 0.0199), 0.01, material=m)])
O.engines = ENGINES()
O.dt = 1e-6
O.step()
out["dashpots"] = phys()

# 2. Oblique impacts, sphere-sphere and sphere-wall, in the three forms.
for form, params in [("young", dict(young=1e7, poisson=0.3, en=0.5, et=0.0)), ("tc", dict(tc=1e-3, en=0.5, et=0.5)),
                     ("kn", dict(kn=1e5, cn=5.0, ks=3e4, cs=2.0))]:
    O.reset()
    mat = O.materials.append(ViscElMat(density=2500, frictionAngle=0.4, **params))
    a = O.bodies.append(sphere((0, 0, 0), 0.01, material=mat))
    b = O.bodies.append(sphere((0.0205, 0.003, 0), 0.01, material=mat))
    O.bodies.append(wall((0, -0.0105, 0), axis=1, material=mat))
    O.bodies[a].state.vel, O.bodies[b].state.vel = (0.1, -0.3, 0), (-0.1, 0, 0.02)
    O.bodies[a].state.angVel = (0, 0, 3)
    O.engines = ENGINES()
    O.engines[-1].gravity = (0, 0, 0)
    O.dt = 1e-5
    out["impact-" + form] = motion([a, b], 8, 100)

# 3. Spheres landing on a facet, on a box and on a fixed sphere (young/en form).
O.reset()
mat = O.materials.append(ViscElMat(young=1e7, poisson=0.3, en=0.4, et=0.0, density=2500, frictionAngle=0.4))
s0 = O.bodies.append(sphere((0, 0, 0.0098), 0.01, material=mat))
O.bodies.append(facet([(-1, -1, 0), (1, -1, 0), (0, 1, 0)], material=mat))
s1 = O.bodies.append(sphere((1, 0, 0.0098), 0.01, material=mat))
O.bodies.append(box((1, 0, -0.5), (0.5, 0.5, 0.5), material=mat, fixed=True))
O.bodies.append(sphere((2, 0, 0.0), 0.01, material=mat, fixed=True))
s3 = O.bodies.append(sphere((2.002, 0, 0.0199), 0.01, material=mat))
for i, v, w in ((s0, (0.1, 0, -0.05), (0, 5, 0)), (s1, (0.05, 0.1, -0.05), (3, 0, 0)), (s3, (0, 0.1, -0.1), (0, 0, 4))):
    O.bodies[i].state.vel, O.bodies[i].state.angVel = v, w
O.engines = ENGINES()
O.dt = 2e-6
O.step()
out["boundaries-phys"] = phys()
out["boundaries"] = motion([s0, s1, s3], 4, 500)

# 4. Rolling resistance: spheres rolling down a tilted facet and on a sphere (mRtype 1, 2).
for mRtype in (1, 2):
    O.reset()
    mat = O.materials.append(ViscElMat(frictionAngle=0.5, mR=0.05, mRtype=mRtype, density=2000, tc=1e-3, en=0.7, et=0.7))
    r = 0.002
    s = O.bodies.append(sphere((0, 0, 0.0019), r, material=mat))
    tilt = math.pi / 28
    O.bodies.append(facet([(-0.1, -0.1 * math.cos(tilt), 0.1 * math.sin(tilt)), (0.1, -0.1 * math.cos(tilt), 0.1 * math.sin(tilt)),
                           (0, 0.1 * math.cos(tilt), -0.1 * math.sin(tilt))], material=mat))
    t = O.bodies.append(sphere((1, 0, 0), r, material=mat, fixed=True))
    u = O.bodies.append(sphere((1.0005, 0, 0.0039), r, material=mat))
    O.bodies[u].state.angVel = (0, 30, 0)
    O.engines = ENGINES()
    O.dt = 1e-7   # the explicit rolling moment is stable for mR |Fn| dt / I < 2 or so
    out["rolling-%d" % mRtype] = motion([s, u], 5, 4000)

# 5. MatchMakers of the functor: restitutions and friction per pair of materials.
O.reset()
mats = [O.materials.append(ViscElMat(frictionAngle=0.5, tc=0.001, en=0.5, et=0.5, density=2000)) for _ in range(3)]
for k, (m1, m2) in enumerate([(0, 1), (0, 2), (1, 2)]):
    O.bodies.append([sphere((k, 0, 0), 0.002, material=mats[m1], fixed=True),
                     sphere((k, 0, 0.0039), 0.002, material=mats[m2])])
pairs = lambda a, b, c: MatchMaker(matches=((mats[0], mats[1], a), (mats[0], mats[2], b), (mats[1], mats[2], c)))
engines = ENGINES()
engines[2] = InteractionLoop([Ig2_Sphere_Sphere_ScGeom()],
                             [Ip2_ViscElMat_ViscElMat_ViscElPhys(en=pairs(.9, .5, .1), et=pairs(.9, .5, .1),
                                                                 frictAngle=pairs(.1, .2, .3))],
                             [Law2_ScGeom_ViscElPhys_Basic()])
O.engines = engines
O.dt = 2e-6
O.step()
out["matchmaker"] = phys()

# 6. Lubrication: a head-on collision at Stokes number 100 (young/en form).
O.reset()
density = 1 / (math.pi / 6)
O.materials.append(ViscElMat(en=0.9, et=1.0, frictionAngle=0.4, young=1e4, poisson=0.5, density=density,
                             lubrication=True, viscoDyn=density / 100, roughnessScale=0.01, label="lub"))
O.bodies.append([sphere((0, 0, 0), 0.5, material="lub"), sphere((0, 0, 1.001), 0.5, material="lub")])
O.bodies[0].state.vel, O.bodies[1].state.vel = (0, 0, 0.5), (0, 0, -0.5)
O.engines = ENGINES()
O.engines[-1].gravity = (0, 0, 0)
O.dt = 1e-4
O.run(20, True)
out["lubrication-phys"] = phys()
out["lubrication"] = motion([0, 1], 3, 1000)

print("JSON " + json.dumps(out))
