"""Yade's triax-basic.py test (TriaxialCompressionEngine on six walls, frictionless walls,
TriaxialStateRecorder) on fixed input, in Yade or in Talus (tests/dem/control/test_triaxial_compression.py
runs it in both). Parameters (JSON in $TALUS_SCENARIO):

* phase "compaction": 300 spheres from makeCloud(seed=7), isotropic compaction to 50 kPa for
  `steps` steps;
* phase "loading": the compacted packing of triax_packing.json (Yade's state at the end of the
  compaction above) between walls at its stored places, currentState=3: deviatoric loading at
  strain rate 0.01 under 50 kPa for `steps` steps;
* phase "threeD": the same packing under a ThreeDTriaxialEngine: x and z at 50 kPa, y strained;
* phase "generate": writes triax_packing.json (run it in Yade).

Prints RESULT {"rows": the recorder's lines as numbers, "state": currentState, ...}."""
import json
import os
from math import radians

try:
    O  # noqa: B018  (defined when Yade runs the script)
    from yade import pack
except NameError:
    from talus.dem import *  # noqa: F401,F403

params = json.loads(os.environ.get("TALUS_SCENARIO", "{}"))
phase = params.get("phase", "compaction")
steps = int(params.get("steps", 60))

O.materials.append(FrictMat(young=15e6, poisson=.4, frictionAngle=radians(30), density=2600, label='spheres'))
O.materials.append(FrictMat(young=15e6, poisson=.4, frictionAngle=0, density=0, label='frictionless'))
if phase in ("loading", "threeD"):
    with open("triax_packing.json") as f:
        stored = json.load(f)
    O.bodies.append([sphere(c, r, material='spheres') for c, r in stored["spheres"]])
    extrema = stored["walls"]
else:
    sp = pack.SpherePack()
    sp.makeCloud(minCorner=(0, 0, 0), maxCorner=(10, 10, 10), rRelFuzz=.2, num=300, seed=7)
    O.bodies.append([sphere(c, r, material='spheres') for c, r in sp])
    extrema = None
wallIds = O.bodies.append(aabbWalls(extrema, thickness=1e-10, material='frictionless'))
if phase == "threeD":
    # x and z at 50 kPa, y strained at a rate relaxing towards 1/s
    triax = ThreeDTriaxialEngine(stressControl_1=True, stressControl_2=False, stressControl_3=True, goal1=-50e3,
                                 goal3=-50e3, strainRate2=1, internalCompaction=False, max_vel=10)
else:
    triax = TriaxialCompressionEngine(internalCompaction=False, sigmaIsoCompaction=-50e3,
                                      sigmaLateralConfinement=-50e3, max_vel=10, strainRate=0.01, noFiles=True,
                                      currentState=3 if phase == "loading" else 0)
for name, id in zip(("left", "right", "bottom", "top", "back", "front"), wallIds):
    setattr(triax, f"wall_{name}_id", id)
O.engines = [
    ForceResetter(),
    InsertionSortCollider([Bo1_Sphere_Aabb(), Bo1_Box_Aabb()]),
    InteractionLoop([Ig2_Sphere_Sphere_ScGeom(), Ig2_Box_Sphere_ScGeom()], [Ip2_FrictMat_FrictMat_FrictPhys()],
                    [Law2_ScGeom_FrictPhys_CundallStrack()]),
    GlobalStiffnessTimeStepper(active=1, timeStepUpdateInterval=100, timestepSafetyCoefficient=0.8),
    triax,
    TriaxialStateRecorder(iterPeriod=10, file="triax_side_by_side.txt", truncate=True),
    NewtonIntegrator(damping=.4)
]

if phase == "generate":
    while triax.currentState != 3:
        O.run(20, True)
    half = [triax.width / 2, triax.height / 2, triax.depth / 2]
    centre = [(O.bodies[wallIds[2 * k + 1]].state.pos[k] + O.bodies[wallIds[2 * k]].state.pos[k]) / 2
              for k in range(3)]
    spheres = [[list(b.state.pos), b.shape.radius] for b in O.bodies if isinstance(b.shape, Sphere)]
    with open("triax_packing.json", "w") as f:
        json.dump({"about": "Yade 2023.02a, triax_side_by_side.py phase generate: the packing when the "
                            "TriaxialCompressionEngine entered the loading", "iter": O.iter,
                   "spheres": spheres, "walls": [[centre[k] - half[k] for k in range(3)],
                                                 [centre[k] + half[k] for k in range(3)]]}, f)
else:
    O.run(steps, True)
with open("triax_side_by_side.txt") as f:
    rows = [[float(x) for x in line.split()] for line in f.readlines()[1:]]
os.remove("triax_side_by_side.txt")
print("RESULT " + json.dumps({"rows": rows, "state": getattr(triax, "currentState", None), "iter": O.iter,
                              "porosity": triax.porosity, "meanStress": triax.meanStress}))
