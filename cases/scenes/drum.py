"""A rotating drum, for speed comparisons; the same file runs in Yade and in Talus.

    yade -n -j1 -x drum.py PACKING STEPS [SAVE]   |   talus run drum.py PACKING STEPS [SAVE]

PACKING is a text file written by cases/dem_bench_kinds.py: a first line `dt young density
omega`, then the drum's triangles (`F x1 y1 z1 x2 y2 z2 x3 y3 z3`: a closed cylinder of facets,
axis z through the origin) and the spheres (`S x y z r`, a lattice filling its lower part).
A RotationEngine turns the facets at omega rad/s about z; FrictMat (poisson 0.3, friction
0.5 rad), linear Cundall-Strack with Coulomb friction, Cundall damping 0.2, gravity -9.81 along
y. One step builds the contacts, then STEPS steps are timed. Prints `TIMED <steps> <seconds>
<contacts> <cpu seconds>` (the CPU time of this process over the timed steps). With SAVE, the
spheres where they end are written there as `S x y z r` lines (the case settles the bed with the
drum at rest, omega 0, and times the settled bed turning).
"""
import sys
import time

try:
    O  # noqa: B018  (defined when Yade runs the script)
    import yade.utils as _utils
    _facet = _utils.facet
except NameError:
    from talus.dem import *  # noqa: F401,F403
    _facet = facet

packing_file, steps = sys.argv[1], int(sys.argv[2])
with open(packing_file) as source:
    dt, young, density, omega = (float(v) for v in source.readline().split())
    rows = [line.split() for line in source if line.strip()]
triangles = [[float(v) for v in row[1:]] for row in rows if row[0] == "F"]
spheres = [[float(v) for v in row[1:]] for row in rows if row[0] == "S"]

material = O.materials.append(FrictMat(young=young, poisson=0.3, frictionAngle=0.5, density=density))
drum = O.bodies.append([_facet((t[0:3], t[3:6], t[6:9]), material=material) for t in triangles])
balls = O.bodies.append([sphere((x, y, z), r, material=material) for x, y, z, r in spheres])
O.engines = [
    ForceResetter(),
    InsertionSortCollider([Bo1_Sphere_Aabb(), Bo1_Facet_Aabb()]),
    InteractionLoop([Ig2_Sphere_Sphere_ScGeom(), Ig2_Facet_Sphere_ScGeom()], [Ip2_FrictMat_FrictMat_FrictPhys()],
                    [Law2_ScGeom_FrictPhys_CundallStrack()]),
    RotationEngine(ids=drum, rotationAxis=(0, 0, 1), angularVelocity=omega, rotateAroundZero=True, zeroPoint=(0, 0, 0)),
    NewtonIntegrator(damping=0.2, gravity=(0, -9.81, 0)),
]
O.dt = dt
O.run(1, True)
start, cpu = time.perf_counter(), time.process_time()
O.run(steps, True)
seconds, cpu = time.perf_counter() - start, time.process_time() - cpu
contacts = sum(1 for i in O.interactions if i.isReal) if hasattr(O, "interactions") else O._cpp.realContactCount()
fused = f" fused {O.fusedSteps}" if hasattr(O, "fusedSteps") else ""
print(f"TIMED {steps} {seconds:.6f} {contacts} {cpu:.6f}{fused}")
if len(sys.argv) > 3:
    with open(sys.argv[3], "w") as out:
        out.writelines(f"S {' '.join(repr(float(v)) for v in (*O.bodies[i].state.pos, O.bodies[i].shape.radius))}\n"
                       for i in balls)
