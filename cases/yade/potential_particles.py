"""Potential Particles on identical input in Yade (`yade -n -x`) and in Talus (twin runs, see
talus.twin): parameters from the JSON in TALUS_SCENARIO, one line `RESULT {json}` out.

mode "pressing": two fixed cubes face to face at centre distance `D`, one step: contact normal,
    overlap, area and normal force (`twoDimension`, `unitWidth2D`: Ig2_PP_PP_ScGeom's 2D mode).
mode "resting": a cube dropped on a fixed boundary plate under gravity: contact force, overlap.
mode "packing": `n` cubes at jittered grid points with random orientations (random.Random(seed),
    the same numbers in both programs) settle under gravity in a box of five boundary plates
    (Yade's cubePPscaled.py, smaller); then every body is fixed and `timedSteps` steps are timed
    (no motion: each step is the contact geometry of every pair): porosity, coordination and
    the step's cost per contact pair.
Volumes and inertias are Talus's (passed in `props`), so both programs use the same masses.
"""
import json
import math
import os
import random
import time

try:
    O  # noqa: B018  (defined when Yade runs the script)
    YADE = True
except NameError:
    from talus import _dem
    from talus.dem import *  # noqa: F401,F403
    YADE = False

P = json.loads(os.environ.get("TALUS_SCENARIO", "{}"))
KN, KS = P.get("Knormal", 1e8), P.get("Kshear", 1e7)
RHO, G = 1000.0, 9.81
CUBE = dict(a=[1, -1, 0, 0, 0, 0], b=[0, 0, 1, -1, 0, 0], c=[0, 0, 0, 0, 1, -1])

if YADE:
    O.materials.append(FrictMat(young=-1, poisson=-1, frictionAngle=P.get("friction", 0.5), density=RHO, label="mat"))
else:
    MAT = O.materials.append(FrictMat(density=RHO, frictionAngle=P.get("friction", 0.5)))


def shape_args(kind):
    s = P["shapes"][kind]
    return dict(CUBE, d=s["d"], r=s["r"], k=s["k"], R=s["R"])


def add(kind, pos, axis=(0, 0, 1), angle=0.0, fixed=False, boundary=False):
    """A particle of shape `kind` (its planes, r, k, R and Talus's volume and inertia in
    P["shapes"]) at `pos`, turned by `angle` about `axis`."""
    args = shape_args(kind)
    s = P["shapes"][kind]
    if YADE:
        half = Vector3(*s["half"]) * 1.02   # the bounding box in the local frame
        b = Body()
        b.aspherical = True
        b.shape = PotentialParticle(isBoundary=boundary, AabbMinMax=True, minAabbRotated=half, maxAabbRotated=half,
                                    minAabb=half, maxAabb=half, id=len(O.bodies), **args)
        utils._commonBodySetup(b, s["volume"], Vector3(*s["inertia"]), material="mat", pos=pos, fixed=fixed)
        b.state.ori = Quaternion(Vector3(*axis), angle)
        b.shape.volume = s["volume"]
        return O.bodies.append(b)
    # Quaternion(axis, angle) as in Yade's branch: the same orientation for the non-unit random axes
    q = Quaternion(axis, angle)
    return O.bodies.append(potentialParticle(PotentialParticle(isBoundary=boundary, **args), pos=pos, orientation=q,
                                             material=MAT, fixed=fixed))


def engines(gravity, damping, viscous):
    geom = Ig2_PP_PP_ScGeom(twoDimension=P.get("twoDimension", False), unitWidth2D=P.get("unitWidth2D", 1.0),
                            calContactArea=True, areaStep=5)
    phys = Ip2_FrictMat_FrictMat_KnKsPhys(Knormal=KN, Kshear=KS, kn_i=KN, ks_i=KS, useFaceProperties=False,
                                          viscousDamping=viscous)
    law = Law2_SCG_KnKsPhys_KnKsLaw(neverErase=False)
    if YADE:
        newton = NewtonIntegrator(damping=damping, exactAsphericalRot=True, gravity=gravity)
    else:
        newton = NewtonIntegrator(damping=damping, gravity=gravity)
    O.engines = [ForceResetter(), InsertionSortCollider([PotentialParticle2AABB()], verletDist=0.01),
                 InteractionLoop([geom], [phys], [law]), newton]


def contacts():
    """Real contacts: ids, normal, overlap, normal force, area."""
    out = []
    if YADE:
        for i in O.interactions:
            if i.isReal:
                out.append(dict(id1=i.id1, id2=i.id2, normal=list(i.geom.normal), penetrationDepth=i.geom.penetrationDepth,
                                contactPoint=list(i.geom.contactPoint), normalForce=list(i.phys.normalForce),
                                contactArea=i.phys.contactArea))
    else:
        areas = _dem.contact_areas(O._cpp)
        for c, a in zip([c for c in O._cpp.contacts()], areas):
            out.append(dict(id1=int(c["id1"]), id2=int(c["id2"]), normal=list(map(float, c["normal"])),
                            penetrationDepth=float(c["penetrationDepth"]), contactPoint=list(map(float, c["contactPoint"])),
                            normalForce=list(map(float, c["normalForce"])), contactArea=float(a)))
    return out


def positions():
    return [list(map(float, b.state.pos)) for b in O.bodies] if YADE else [list(map(float, p)) for p in O._cpp.pos()]


mode = P["mode"]
if mode == "pressing":
    engines((0, 0, 0), 0.0, 0.0)
    add("cube", (0, 0, 0), fixed=True)
    add("cube", (0, 0, P["D"]), fixed=True)
    O.dt = 1e-5
    O.run(2, True)   # Yade's Ig2 stores the area in the contact's physics, which exists from the 2nd step
    print("RESULT " + json.dumps({"contacts": contacts()}))
elif mode == "resting":
    engines((0, 0, -G), P.get("damping", 0.3), P.get("viscous", 0.5))
    add("plate", (0, 0, -P["shapes"]["plate"]["half"][2]), fixed=True, boundary=True)
    cube = add("cube", (0, 0, P["shapes"]["cube"]["half"][2] + 1e-4))
    O.dt = P.get("dt", 2e-4)
    history = []
    for _ in range(P["steps"] // 100):
        O.run(100, True)
        c = contacts()
        history.append(c[0]["normalForce"][2] if c else 0.0)
    print("RESULT " + json.dumps({"contacts": contacts(), "history": history, "pos": positions()[cube]}))
elif mode == "packing":
    engines((0, -G, 0), P.get("damping", 0.2), P.get("viscous", 0.05))
    L, H, t = P["box"], P["height"], 0.5   # inner width, wall height, plate thickness
    walls = [((0, -t / 2, 0), "floor"), ((L / 2 + t / 2, H / 2, 0), "side_x"), ((-L / 2 - t / 2, H / 2, 0), "side_x"),
             ((0, H / 2, L / 2 + t / 2), "side_z"), ((0, H / 2, -L / 2 - t / 2), "side_z")]
    for pos, kind in walls:
        add(kind, pos, fixed=True, boundary=True)
    rng = random.Random(P.get("seed", 1))
    m, spacing = P["perRow"], P["spacing"]
    first = len(O.bodies)
    for k in range(P["n"]):
        ix, iz, iy = k % m, (k // m) % m, k // (m * m)
        pos = (spacing * (ix - (m - 1) / 2) + rng.uniform(-0.05, 0.05), 1.0 + spacing * iy + rng.uniform(-0.05, 0.05),
               spacing * (iz - (m - 1) / 2) + rng.uniform(-0.05, 0.05))
        add("cube", pos, axis=(rng.random(), rng.random(), rng.random()), angle=rng.uniform(0, math.pi))
    O.dt = P["dt"]
    O.run(P["steps"], True)
    ids = list(range(first, len(O.bodies)))
    pos = positions()
    cs = contacts()
    particle = set(ids)
    pp = sum(1 for c in cs if c["id1"] in particle and c["id2"] in particle)
    pw = sum(1 for c in cs if (c["id1"] in particle) != (c["id2"] in particle))
    # Cost of the contact geometry: every body fixed and at rest, so each step redoes the
    # geometry of every pair and nothing else moves.
    for b in (O.bodies if YADE else []):
        b.state.blockedDOFs = "xyzXYZ"
        b.state.vel = Vector3(0, 0, 0)
        b.state.angVel = Vector3(0, 0, 0)
    if not YADE:
        for i in range(len(pos)):
            O._cpp.setDynamic(i, False)
            O.bodies[i].state.vel = (0, 0, 0)
            O.bodies[i].state.angVel = (0, 0, 0)
    O.run(5, True)
    rebuilds = 0 if YADE else O.engines[1]._cpp.rebuilds
    start = time.perf_counter()
    O.run(P["timedSteps"], True)
    seconds = (time.perf_counter() - start) / P["timedSteps"]
    rebuilds = 0 if YADE else O.engines[1]._cpp.rebuilds - rebuilds   # none expected: nothing moves
    print("RESULT " + json.dumps({"positions": [pos[i] for i in ids], "particleContacts": pp, "wallContacts": pw,
                                  "real": len(cs), "stepSeconds": seconds,
                                  "realAfter": len(contacts()), "rebuildsWhileTimed": rebuilds}))
