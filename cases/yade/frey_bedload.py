"""Scenario: the quasi-2D bedload channel of Frey (2014) / Maurin et al. (2015) continued from a
given state, in Yade and in Talus (talus.dem.twin). Parameters ($TALUS_SCENARIO, written by
cases/vans_frey_vs_yade.py): the periodic cell, the visco-elastic material, every sphere (position,
velocity, spin, radius, fixed), the two side walls, the HydroForceEngine settings, the fluid
velocity and Reynolds-stress profiles, the coupling period, fluid step, DEM step, the run length
and the start of the averaging window.

Both programs run the same loop: DEM steps for one coupling period, then averageProfile() and
fluidResolution(period, dtFluid); every eddy turnover time (water depth above the bed over the
mean fluid velocity there, the bed being the first layer from the top with phi > 0.5 that still
rises downwards) every grain's fluctuation is redrawn (turbulentFluctuation(), as Yade's
validMaurin2015.py). After `average` seconds the solid fraction and phi vx profiles of each
coupling are summed. Prints `RESULT {phi, phivx (time-averaged profiles), qs (the dimensionless
transport rate of each coupling), time}`."""
import json
import math
import os

try:
    O  # noqa: B018  (defined when Yade runs the script)
    yade = True
except NameError:
    from talus.dem import *  # noqa: F401,F403
    from talus.flow import HydroForceEngine
    yade = False

P = json.loads(os.environ["TALUS_SCENARIO"])
O.periodic = True
O.cell.setBox(*P["cell"])
m = P["material"]
O.materials.append(ViscElMat(kn=m["kn"], cn=m["cn"], ks=m["ks"], cs=m["cs"], density=m["density"],
                             frictionAngle=m["frictionAngle"]))
for y in P["walls"]:
    if yade:
        # As Yade's validMaurin2015.py: a flat box far wider than the cell (a Wall in a periodic
        # cell sends Yade's collider into a crawl); the same plane contact as Talus's wall.
        O.bodies.append(box(center=(P["cell"][0] / 2, y, P["cell"][2] / 2), extents=(2000, 0, 10 * P["cell"][2]),
                            fixed=True))
    else:
        O.bodies.append(wall(y, axis=1))
first = len(O.bodies)
for (x, y, z), r, fixed in zip(P["pos"], P["radius"], P["fixed"]):
    O.bodies.append(sphere((x, y, z), r, fixed=fixed))
for k, (v, w) in enumerate(zip(P["vel"], P["angVel"])):
    O.bodies[first + k].state.vel = Vector3(*v)
    O.bodies[first + k].state.angVel = Vector3(*w)
mobile = [first + k for k, fixed in enumerate(P["fixed"]) if not fixed]
h = P["hydro"]
common = dict(densFluid=h["densFluid"], viscoDyn=h["viscoDyn"], zRef=h["zRef"], gravity=tuple(h["gravity"]),
              deltaZ=h["deltaZ"], expoRZ=h["expoRZ"], lift=False, nCell=h["nCell"], vCell=h["vCell"],
              radiusPart=h["radiusPart"], phiMax=h["phiMax"], iturbu=1, ilm=2, iusl=1, irheolf=0,
              fluidWallFriction=True, channelWidth=h["channelWidth"], bedElevation=h["bedElevation"], ids=mobile)
if yade:
    # Yade's action skips a grain outside the grid; Talus says so explicitly (ignoreOutside).
    hydro = HydroForceEngine(**common)
    collider = InsertionSortCollider([Bo1_Sphere_Aabb(), Bo1_Box_Aabb()], allowBiggerThanPeriod=True)
    geometry = [Ig2_Sphere_Sphere_ScGeom(), Ig2_Box_Sphere_ScGeom()]
else:
    hydro = HydroForceEngine(ignoreOutside=True, **common)
    collider = InsertionSortCollider([Bo1_Sphere_Aabb(), Bo1_Wall_Aabb()])
    geometry = [Ig2_Sphere_Sphere_ScGeom(), Ig2_Wall_Sphere_ScGeom()]
O.engines = [ForceResetter(), collider,
             InteractionLoop(geometry, [Ip2_ViscElMat_ViscElMat_ViscElPhys()], [Law2_ScGeom_ViscElPhys_Basic()]),
             hydro, NewtonIntegrator(damping=0.0, gravity=tuple(h["gravity"]))]
O.dt = P["dt"]
if yade:
    hydro.initialization()
hydro.vxFluid = P["vxFluid"]
hydro.ReynoldStresses = P["ReynoldStresses"]
hydro.turbulentFluctuation()         # sizes the fluctuation arrays (and draws a first set)

n = h["nCell"]
dz = h["deltaZ"]
scale = math.sqrt((m["density"] / h["densFluid"] - 1) * abs(h["gravity"][2]) * P["diameter"] ** 3)
chunk = int(round(P["period"] / O.dt))
couplings = int(round(P["duration"] / P["period"]))
phi_sum, phivx_sum, averaged, qs, times = [0.0] * n, [0.0] * n, 0, [], []
next_refresh = 0.0
elapsed = 0.0
for k in range(couplings):
    O.run(chunk, True)
    elapsed += chunk * O.dt
    hydro.averageProfile()
    phi, vx = list(hydro.phiPart), list(hydro.vxPart)
    hydro.fluidResolution(P["period"], P["dtFluid"])
    qs.append(sum(p * v for p, v in zip(phi, vx)) * dz / scale)
    times.append(elapsed)
    if elapsed > P["average"]:
        averaged += 1
        for j in range(n):
            phi_sum[j] += phi[j]
            phivx_sum[j] += phi[j] * vx[j]
    if elapsed >= next_refresh:
        bed = next((j for j in range(n - 1, 0, -1) if phi[j] < phi[j - 1] and phi[j] > 0.5), None)
        fluid = list(hydro.vxFluid)
        if bed is None:
            next_refresh = elapsed + P["period"]
            continue
        velocity = sum(fluid[bed:]) / len(fluid[bed:])
        hydro.bedElevation = bed * dz
        hydro.turbulentFluctuation()
        next_refresh = elapsed + (n - 1 - bed) * dz / velocity
print("RESULT " + json.dumps({"phi": [p / averaged for p in phi_sum], "phivx": [p / averaged for p in phivx_sum],
                              "qs": qs, "time": times, "couplings": couplings}))
