"""A dense, contact-dominated bed for speed comparisons; the same file runs in Yade and in Talus.

    yade -n -j1 -x dense_bed.py PACKING STEPS [LAW]   |   talus run dense_bed.py PACKING STEPS [LAW]

PACKING is a text file written by cases/bench/11_bench_dense.py: a first line `dt young density box_x
box_y` and then `x y z r` per sphere. The spheres rest on the floor of a box of five walls under
gravity -9.81 along z (Verlet skin half the smallest radius, Yade's default). LAW (default
linear) is the contact model, poisson 0.3 and friction 0.5 rad throughout:
  linear        FrictMat, linear Cundall-Strack with Coulomb friction, Cundall damping 0.2;
  hertz         FrictMat, Hertz-Mindlin (no viscous damping of its own), Cundall damping 0.2;
  viscoelastic  ViscElMat, the linear spring-dashpot of the same contact time as the linear law's
                springs (kn = E r) and restitution 0.3 both ways, no Cundall damping;
  cohesive      CohFrictMat, the cohesive-frictional law with moments (bonds made at the first
                contact, normal and shear cohesion 1e5 Pa), Cundall damping 0.2; the walls are
                boxes (Yade has no wall geometry of ScGeom6D).
One step builds the contacts, then STEPS steps are timed. Prints `TIMED <steps> <seconds>
<contacts> <cpu seconds>` (the CPU time of this process over the timed steps).
"""
import math
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(sys.argv[0])))   # bench_scene.py, under Yade's -x too
from bench_scene import read_packing, timed  # noqa: E402

try:
    O  # noqa: B018  (defined when Yade runs the script)
    import yade.utils as _utils
    _wall, _box = _utils.wall, _utils.box
except NameError:
    from talus.dem import *  # noqa: F401,F403
    _wall, _box = wall, box

packing_file, steps = sys.argv[1], int(sys.argv[2])
law = sys.argv[3] if len(sys.argv) > 3 else "linear"
(dt, young, density, box_x, box_y), spheres, _ = read_packing(packing_file)

damping = 0.2
if law == "linear":
    material = FrictMat(young=young, poisson=0.3, frictionAngle=0.5, density=density)
    physics, contact_law = Ip2_FrictMat_FrictMat_FrictPhys(), Law2_ScGeom_FrictPhys_CundallStrack()
elif law == "hertz":
    material = FrictMat(young=young, poisson=0.3, frictionAngle=0.5, density=density)
    physics, contact_law = Ip2_FrictMat_FrictMat_MindlinPhys(), Law2_ScGeom_MindlinPhys_Mindlin()
elif law == "viscoelastic":
    r = spheres[0][3]
    contact_time = math.pi / math.sqrt(young * r / (density * 4 / 3 * math.pi * r**3 / 2))
    material = ViscElMat(tc=contact_time, en=0.3, et=0.3, poisson=0.3, frictionAngle=0.5, density=density)
    physics, contact_law = Ip2_ViscElMat_ViscElMat_ViscElPhys(), Law2_ScGeom_ViscElPhys_Basic()
    damping = 0.0
elif law == "cohesive":
    material = CohFrictMat(young=young, poisson=0.3, frictionAngle=0.5, density=density, isCohesive=True,
                           normalCohesion=1e5, shearCohesion=1e5, momentRotationLaw=True)
    physics = Ip2_CohFrictMat_CohFrictMat_CohFrictPhys(setCohesionNow=True, setCohesionOnNewContacts=False)
    contact_law = Law2_ScGeom6D_CohFrictPhys_CohesionMoment()
else:
    raise SystemExit(f"LAW must be linear, hertz, viscoelastic or cohesive, not {law!r}")
material = O.materials.append(material)
O.bodies.append([sphere((x, y, z), r, material=material) for x, y, z, r in spheres])
if law == "cohesive":
    top, t = max(z + r for x, y, z, r in spheres), 2 * spheres[0][3]
    O.bodies.append([_box((box_x / 2, box_y / 2, -t), (box_x / 2 + 2 * t, box_y / 2 + 2 * t, t), fixed=True, material=material),
                     _box((-t, box_y / 2, top / 2), (t, box_y / 2 + 2 * t, top), fixed=True, material=material),
                     _box((box_x + t, box_y / 2, top / 2), (t, box_y / 2 + 2 * t, top), fixed=True, material=material),
                     _box((box_x / 2, -t, top / 2), (box_x / 2, t, top), fixed=True, material=material),
                     _box((box_x / 2, box_y + t, top / 2), (box_x / 2, t, top), fixed=True, material=material)])
    bounds, geometries = [Bo1_Sphere_Aabb(), Bo1_Box_Aabb()], [Ig2_Sphere_Sphere_ScGeom6D(), Ig2_Box_Sphere_ScGeom6D()]
else:
    O.bodies.append([_wall(0, axis=2, sense=1, material=material), _wall(0, axis=0, sense=1, material=material),
                     _wall(box_x, axis=0, sense=-1, material=material), _wall(0, axis=1, sense=1, material=material),
                     _wall(box_y, axis=1, sense=-1, material=material)])
    bounds, geometries = [Bo1_Sphere_Aabb(), Bo1_Wall_Aabb()], [Ig2_Sphere_Sphere_ScGeom(), Ig2_Wall_Sphere_ScGeom()]
O.engines = [
    ForceResetter(),
    InsertionSortCollider(bounds),
    InteractionLoop(geometries, [physics], [contact_law]),
    NewtonIntegrator(damping=damping, gravity=(0, 0, -9.81)),
]
O.dt = dt
timed(O, steps)
