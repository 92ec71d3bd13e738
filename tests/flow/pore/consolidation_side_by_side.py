"""A short 1D consolidation (the oedometer phase of Yade's FluidCouplingPFV/oedometer.py) from a
fixed packing, written so that the same file runs in Yade (`yade -n -x`) and in Talus: 300
spheres compacted to 10 kPa (data/consolidation_packing.txt, made by Yade 2023.02a as the
example makes its 1000), drained at the top, loaded to 11 kPa by the top wall with O.dt fixed at
1e-4 and no damping. Prints one RESULT line: the top wall's position, the pore pressure near the
bottom and the largest fluid force on a sphere, every 50 steps (tests/flow/pore/test_consolidation.py)."""
import json
import math
import os

try:
    O  # noqa: B018  (defined when Yade runs the script)
except NameError:
    from yade import *  # noqa: F401,F403  (Talus's drop-in namespace: talus.dem and FlowEngine)

STEPS = json.loads(os.environ.get("TALUS_SCENARIO", "{}")).get("steps", 1000)   # run in this folder
rows = [l.split() for l in open(os.path.join("..", "data", "consolidation_packing.txt")) if not l.startswith("#")]
O.materials.append(FrictMat(young=1e6, poisson=0.5, frictionAngle=math.radians(30), density=2600, label="spheres"))
O.materials.append(FrictMat(young=1e6, poisson=0.5, frictionAngle=0, density=0, label="walls"))
O.bodies.append(aabbWalls([Vector3(0, 0, 0), Vector3(1, 1, 1)], thickness=0, material="walls"))
for x, y, z, r in rows:
    O.bodies.append(sphere((float(x), float(y), float(z)), float(r), material="spheres"))
triax = TriaxialStressController(thickness=0, stressMask=2, max_vel=0.005, internalCompaction=False)
triax.goal1 = triax.goal3 = 0
triax.goal2 = -11000
triax.wall_bottom_activated = False
flow = FlowEngine(defTolerance=0.3, meshUpdateInterval=200, useSolver=3, permeabilityFactor=1, viscosity=10)
flow.bndCondIsPressure = [0, 0, 0, 1, 0, 0]
flow.bndCondValue = [0, 0, 0, 0, 0, 0]
flow.boundaryUseMaxMin = [0, 0, 0, 0, 0, 0]
newton = NewtonIntegrator(damping=0)
O.engines = [ForceResetter(), InsertionSortCollider([Bo1_Sphere_Aabb(), Bo1_Box_Aabb()]),
             InteractionLoop([Ig2_Sphere_Sphere_ScGeom(), Ig2_Box_Sphere_ScGeom()], [Ip2_FrictMat_FrictMat_FrictPhys()],
                             [Law2_ScGeom_FrictPhys_CundallStrack()]),
             flow, GlobalStiffnessTimeStepper(active=1, timeStepUpdateInterval=100, timestepSafetyCoefficient=0.8),
             triax, newton]
O.dt = 1e-4
O.dynDt = False
trace = []
for k in range(STEPS // 50):
    O.run(50, True)
    fmax = max(Vector3(flow.fluidForce(b.id)).norm() for b in O.bodies if isinstance(b.shape, Sphere))
    trace.append([O.iter, O.dt, O.bodies[3].state.pos[1], flow.getPorePressure((0.5, 0.1, 0.5)), fmax])
print("RESULT " + json.dumps({"trace": trace}))
