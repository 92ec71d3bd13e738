# What the set-ups of Yade's examples/ThermalEngine share, for the scripts that run them by the same
# text in Yade and Talus (cases/yade/thermal_scenario.py, tests/flow/thermal/thermal_noflow.py and
# thermal_rod.py). Yade's `-x` puts no script folder on sys.path: a script first adds this folder.
from math import radians

from yade import *
from yade.utils import aabbWalls, sphere

EXAMPLE_PACKING = "/usr/share/doc/yade/examples/ThermalEngine/5cmEdge_1mm.spheres"


def packing_spheres(path, material):
    """The spheres of a sphere file (x y z r per line; the examples' ymport.textExt(path, 'x_y_z_r'),
    read by hand)."""
    with open(path) as f:
        rows = [[float(v) for v in line.split()] for line in f if line.strip() and not line.startswith('#')]
    return [sphere((x, y, z), r, material=material) for x, y, z, r in rows]


def static_box(mn, mx, young, spheres):
    """The examples' scene: FrictMat 'spheres' (poisson 0.5, friction 3 degrees, density 2600) and
    'walls' (no friction, no mass), both of Young's modulus `young`; the six walls of the box mn-mx
    and the spheres `spheres('spheres')` makes, none dynamic; the engines with a FlowEngine 'flow'
    and a ThermalEngine 'thermal' before NewtonIntegrator(damping=0.2). Returns (flow, thermal)."""
    O.materials.append(FrictMat(young=young, poisson=0.5, frictionAngle=radians(3), density=2600, label='spheres'))
    O.materials.append(FrictMat(young=young, poisson=0.5, frictionAngle=0, density=0, label='walls'))
    O.bodies.append(aabbWalls([mn, mx], thickness=0, material='walls'))
    O.bodies.append(spheres('spheres'))
    for b in O.bodies:
        b.dynamic = False
    flow = FlowEngine(label="flow")
    thermal = ThermalEngine(label="thermal")
    O.engines = [ForceResetter(), InsertionSortCollider([Bo1_Sphere_Aabb(), Bo1_Box_Aabb()]),
                 InteractionLoop([Ig2_Sphere_Sphere_ScGeom(), Ig2_Box_Sphere_ScGeom()], [Ip2_FrictMat_FrictMat_FrictPhys()],
                                 [Law2_ScGeom_FrictPhys_CundallStrack()]),
                 flow, thermal, NewtonIntegrator(damping=0.2)]
    return flow, thermal


def water_and_particles(flow, thermal):
    """The fluid examples' water (viscosity, density, heat capacity and conductivity), flow coupled
    to the heat (advection, no thermo-mechanics, fictitious conduction ignored) and particles
    (333.15 K, 2600 kg/m3, 2 W/(m K), 710 J/(kg K), Kern's exchange); a thermal step of O.dt."""
    flow.permeabilityFactor = 1
    flow.viscosity = 0.001
    flow.thermalEngine = True
    flow.fluidRho = 997
    flow.fluidCp = 4181.7
    thermal.ignoreFictiousConduction = True
    thermal.thermoMech = False
    thermal.solidThermoMech = False
    thermal.fluidThermoMech = False
    thermal.advection = True
    thermal.fluidK = 0.6069
    thermal.particleT0 = 333.15
    thermal.particleDensity = 2600.
    thermal.particleK = 2.
    thermal.particleCp = 710.
    thermal.tsSafetyFactor = 0
    thermal.useKernMethod = True
