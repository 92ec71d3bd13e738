# Side-by-side script: runs unchanged in Yade (yade -n -x hydro_forces.py, cwd = this folder) and in
# Talus (python3 hydro_forces.py). Spheres of three sizes at pseudo-random positions and
# velocities in a given fluid velocity and solid fraction profile; prints as JSON the fluid force
# of every sphere for several option sets (HydroForceEngine.action), and the averaged profiles of
# a packing whose sphere centres sit at layer mid-heights (averageProfile; see test_hydro.py for
# why mid-heights).
import json
import math

try:
    O
    TALUS = False
except NameError:
    from talus.dem import *  # noqa: F401,F403
    from talus.flow import HydroForceEngine
    TALUS = True

N_CELL, DZ, Z_REF = 60, 1e-3, -0.01


def lcg(seed):
    """A small deterministic generator, identical in both programs."""
    state = seed
    while True:
        state = (1103515245 * state + 12345) % 2 ** 31
        yield state / 2 ** 31


def profiles(n=N_CELL, dz=DZ):
    z = [(j + 0.5) * dz for j in range(n - 1)]
    vx = [0.0] + [0.8 * math.tanh(zj / 0.015) for zj in z] + [0.8 * math.tanh((n - 1) * dz / 0.015)]
    phi = [0.55 * 0.5 * (1 - math.tanh((j * dz - 0.02) / 0.004)) for j in range(n)]
    return vx, phi


def build():
    rnd = lcg(12345)
    radii = (1.5e-3, 2e-3, 3.1e-3)
    ids = []
    for k in range(40):
        r = radii[k % 3]
        # Anywhere in the grid, the top layer (above the fluid resolution's surface node, whose
        # velocity it sees) included.
        z = Z_REF + r + (N_CELL * DZ - 2 * r) * next(rnd)
        b = O.bodies.append(sphere((0.01 * next(rnd), 0.01 * next(rnd), z), r))
        O.bodies[b].state.vel = (0.5 * next(rnd) - 0.1, 0.2 * next(rnd) - 0.1, 0.2 * next(rnd) - 0.1)
        ids.append(b)
    return ids


def forces(ids, options):
    options = dict(options)
    n, dz = options.pop("nCell", N_CELL), options.pop("deltaZ", DZ)
    if TALUS and n * dz < N_CELL * DZ:
        options["ignoreOutside"] = True      # Yade's behaviour (talus run's default)
    vx, phi = profiles(n, dz)
    e = HydroForceEngine(densFluid=1000.0, viscoDyn=1.1e-3, zRef=Z_REF, deltaZ=dz, nCell=n,
                         gravity=(9.81 * math.sin(0.05), 0.0, -9.81 * math.cos(0.05)), ids=ids, **options)
    e.initialization()
    e.vxFluid = vx
    e.phiPart = phi
    # A NewtonIntegrator makes Yade reset its force container every step; with a 1e-12 s step
    # the particles do not move measurably, and both programs move them the same way.
    O.engines = [ForceResetter(), e, NewtonIntegrator(gravity=(0, 0, 0), damping=0.0)]
    O.dt = 1e-12
    O.step()
    if TALUS:
        f = O.forces()
        return [[float(x) for x in f[i]] for i in ids]
    return [[float(x) for x in O.forces.f(i)] for i in ids]


def average(moved):
    """Spheres centred at layer mid-heights, in a 2 cm x 2 cm column; the spheres of ``moved``
    are first put far below the grid (averageProfile takes every sphere, as in Yade)."""
    for i in moved:
        O.bodies[i].state.pos = (0.0, 0.0, Z_REF - 1.0)
    ids = []
    rnd = lcg(777)
    for k in range(30):
        r = (1.5e-3, 2.5e-3)[k % 2]
        layer = 8 + int(20 * next(rnd))
        b = O.bodies.append(sphere((0.02 * next(rnd), 0.02 * next(rnd), Z_REF + (layer + 0.5) * DZ), r))
        O.bodies[b].state.vel = (0.3 * next(rnd), 0.1 * next(rnd) - 0.05, 0.1 * next(rnd) - 0.05)
        ids.append(b)
    vx, phi = profiles()
    e = HydroForceEngine(densFluid=1000.0, viscoDyn=1e-3, zRef=Z_REF, deltaZ=DZ, nCell=N_CELL,
                         vCell=0.02 * 0.02 * DZ, ids=ids, expoRZ=3.1)
    e.initialization()
    e.enableMultiClassAverage = True   # as Yade's bi-disperse example: after initialization()
    e.vxFluid = vx
    e.phiPart = phi
    e.averageProfile()
    # The per-class velocities are left out: Yade adds each slice's velocity to the layer of the
    # sphere's centre (docs/flow.md).
    classes = {"radiusParts": [float(r) for r in e.radiusParts],
               "multiPhi": [[float(x) for x in c] for c in e.multiPhiPart],
               "multiDrag": [[float(x) for x in c] for c in e.multiDragPart]}
    if TALUS:
        v = e.vPart
        return {"phi": list(map(float, e.phiPart)), "vx": list(map(float, v[:, 0])),
                "vy": list(map(float, v[:, 1])), "vz": list(map(float, v[:, 2])),
                "drag": list(map(float, e.averageDrag)), **classes}
    return {"phi": list(e.phiPart), "vx": [v[0] for v in e.vPart], "vy": [v[1] for v in e.vPart],
            "vz": [v[2] for v in e.vPart], "drag": list(e.averageDrag), **classes}


OPTION_SETS = {
    "default": {},
    "rest": {"steadyFlow": False, "expoRZ": 2.4},
    "lift": {"lift": True, "Cl": 0.3},
    # Coarse grids covering the lower part of the column: the spheres above get no force.
    "one layer": {"nCell": 1, "deltaZ": N_CELL * DZ / 2},
    "two layers": {"nCell": 2, "deltaZ": N_CELL * DZ / 3, "steadyFlow": False},
}
ids = build()
out = {name: forces(ids, options) for name, options in OPTION_SETS.items()}
out["average"] = average(ids)
print("RESULT " + json.dumps(out))
