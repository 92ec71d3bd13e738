"""GlobalStiffnessTimeStepper(viscEl=...) on visco-elastic contacts (ViscElMat young/poisson/en,
the FluidCouplingVANS1D examples' form), a fixed overlapping packing on a flat box, written so
that the same file runs in Yade (`yade -n -x`) and in Talus. Parameters (TALUS_SCENARIO JSON):
en, viscEl. Prints the time step of the first steps as JSON (one RESULT line)."""
import json
import os

try:
    O  # noqa: B018  (defined when Yade runs the script)
    from yade import pack
except NameError:
    from talus.dem import *  # noqa: F401,F403

params = json.loads(os.environ.get("TALUS_SCENARIO") or "{}")
O.materials.append(ViscElMat(en=params.get("en", 0.5), et=0., young=5e6, poisson=0.5, density=2500,
                             frictionAngle=0.4))
sp = pack.SpherePack()
sp.makeCloud((0, 0, 0), (1, 1, 0.6), rMean=.06, rRelFuzz=.2, seed=4)
O.bodies.append(box((0.5, 0.5, 0), (2, 2, 0), fixed=True))
# 10 % larger radii than the cloud's: the spheres start with loaded contacts
O.bodies.append([sphere(c, 1.1 * r) for c, r in sp])
O.engines = [
    ForceResetter(),
    InsertionSortCollider([Bo1_Sphere_Aabb(), Bo1_Box_Aabb()]),
    InteractionLoop([Ig2_Sphere_Sphere_ScGeom(), Ig2_Box_Sphere_ScGeom()], [Ip2_ViscElMat_ViscElMat_ViscElPhys()],
                    [Law2_ScGeom_ViscElPhys_Basic()]),
    GlobalStiffnessTimeStepper(timestepSafetyCoefficient=0.7, viscEl=params.get("viscEl", True), label="GSTS"),
    NewtonIntegrator(gravity=(0, 0, -9.81), damping=0.2),
]
dts = []
for k in range(12):
    O.step()
    dts.append(O.dt)
print("RESULT " + json.dumps({"dt": dts, "n": len(O.bodies), "contacts": O.interactions.countReal()}))
