"""Spheres falling onto the walls of a box under gravity: a script written for one process, run
as it is by `talus run` and by `mpirun -np N talus run` (the distributed DEM's parity case,
cases/dem/dem_mpi_parity.py).

Arguments: spheres, steps, output file (JSON: the positions of every body by id every 100 steps,
the halo traffic per process, the final unbalanced force), and optionally the contact law: linear
(FrictMat, Cundall-Strack; the default), hertz (Hertz-Mindlin with restitution 0.5),
viscoelastic (ViscElMat with rolling resistance) or cohesive (CohFrictMat bonding new contacts,
with rolling and twisting moments): each law with contact state exercises its state's migration.
"""
import json
import sys

from yade import pack
from talus.dem import distributed

spheres, steps, output = int(sys.argv[1]), int(sys.argv[2]), sys.argv[3]
law = sys.argv[4] if len(sys.argv) > 4 else "linear"
sixD = law == "cohesive"      # the cohesive law's geometry keeps the bodies' relative rotation
material, physics, contactLaw = {
    "linear": (FrictMat(young=1e7, poisson=0.3, frictionAngle=0.5, density=2600),
               Ip2_FrictMat_FrictMat_FrictPhys(), Law2_ScGeom_FrictPhys_CundallStrack()),
    "hertz": (FrictMat(young=1e7, poisson=0.3, frictionAngle=0.5, density=2600),
              Ip2_FrictMat_FrictMat_MindlinPhys(en=0.5), Law2_ScGeom_MindlinPhys_Mindlin()),
    "viscoelastic": (ViscElMat(young=1e7, tc=5e-3, en=0.5, et=0.5, frictionAngle=0.5, density=2600, mR=0.01),
                     Ip2_ViscElMat_ViscElMat_ViscElPhys(), Law2_ScGeom_ViscElPhys_Basic()),
    "cohesive": (CohFrictMat(young=1e7, poisson=0.3, frictionAngle=0.5, density=2600, isCohesive=True,
                             normalCohesion=1e3, shearCohesion=1e3, momentRotationLaw=True),
                 Ip2_CohFrictMat_CohFrictMat_CohFrictPhys(setCohesionOnNewContacts=True),
                 Law2_ScGeom6D_CohFrictPhys_CohesionMoment(useIncrementalForm=True)),
}[law]
O.materials.append(material)
side = (spheres / 400.0) ** (1 / 3.0)
cloud = pack.SpherePack()
cloud.makeCloud((0, 0, 0), (side, side, 2 * side), rMean=0.04, rRelFuzz=0.3, num=spheres, seed=1)
cloud.toSimulation()
for axis in range(3):
    O.bodies.append(utils.wall(0, axis=axis, sense=1))
    if axis < 2:
        O.bodies.append(utils.wall(side, axis=axis, sense=-1))
samples = []


def sample():
    samples.append(distributed.positions().tolist())   # every body, on every process
    print(O.iter, unbalancedForce())


O.engines = [
    ForceResetter(),
    InsertionSortCollider([Bo1_Sphere_Aabb(), Bo1_Wall_Aabb()]),
    InteractionLoop([Ig2_Sphere_Sphere_ScGeom6D(), Ig2_Wall_Sphere_ScGeom6D()] if sixD
                    else [Ig2_Sphere_Sphere_ScGeom(), Ig2_Wall_Sphere_ScGeom()], [physics], [contactLaw]),
    NewtonIntegrator(gravity=(0, 0, -9.81), damping=0.4),
    PyRunner(command='sample()', iterPeriod=100),
]
O.dt = 0.7 * PWaveTimeStep()
O.run(steps, True)
sample()                                               # the state after the last step
# Collective reads (every process calls them), then the file from process 0.
result = {"positions": samples, "traffic": distributed.traffic(), "unbalanced": unbalancedForce(),
          "floor_force": O.forces.f(spheres + 4)[2]}   # the floor (the fifth wall), summed over processes
if distributed.rank() == 0:
    with open(output, "w") as f:
        json.dump(result, f)
