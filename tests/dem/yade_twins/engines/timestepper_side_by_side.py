"""GlobalStiffnessTimeStepper on an overlapping packing resting on a wall, written so that the same
file runs in Yade (`yade -n -x`) and in Talus: prints the time step of the first steps, the
P-wave and the Rayleigh estimates as JSON (one DT line)."""
import json

try:
    O  # noqa: B018  (defined when Yade runs the script)
    from yade import pack
except NameError:
    from talus.dem import *  # noqa: F401,F403

O.materials.append(FrictMat(young=5e6, poisson=0.25, frictionAngle=0.4, density=2500))
sp = pack.SpherePack()
sp.makeCloud((0, 0, 0), (1, 1, 0.6), rMean=.06, rRelFuzz=.2, seed=4)
O.bodies.append(wall(0.0, axis=2))
# 10 % larger radii than the cloud's: the spheres start with loaded contacts
O.bodies.append([sphere(c, 1.1 * r) for c, r in sp])
O.engines = [
    ForceResetter(),
    InsertionSortCollider([Bo1_Sphere_Aabb(), Bo1_Wall_Aabb()]),
    InteractionLoop([Ig2_Sphere_Sphere_ScGeom(), Ig2_Wall_Sphere_ScGeom()], [Ip2_FrictMat_FrictMat_FrictPhys()],
                    [Law2_ScGeom_FrictPhys_CundallStrack()]),
    GlobalStiffnessTimeStepper(timestepSafetyCoefficient=0.7, timeStepUpdateInterval=3),
    NewtonIntegrator(gravity=(0, 0, -9.81), damping=0.4),
]
dts = []
for k in range(12):
    O.step()
    dts.append(O.dt)
print("RESULT " + json.dumps({"dt": dts, "pwave": PWaveTimeStep(), "rayleigh": RayleighWaveTimeStep(), "n": len(O.bodies)}))
