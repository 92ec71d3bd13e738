"""ThermalEngine's thermal expansion (thermoMech, solidThermoMech, fluidThermoMech): the spheres'
radii follow their temperature change, alpha r dT, and the pore fluid's expansion raises an
undrained pore pressure by K_f fluidBeta dT; checkpoints keep the expansion's state."""
import math
from pathlib import Path

import numpy as np
import pytest

from talus.dem import (O, Bo1_Sphere_Aabb, Bo1_Wall_Aabb, ForceResetter, FrictMat, Ig2_Sphere_Sphere_ScGeom,
                       Ig2_Wall_Sphere_ScGeom, InsertionSortCollider, InteractionLoop, Ip2_FrictMat_FrictMat_FrictPhys,
                       Law2_ScGeom_FrictPhys_CundallStrack, NewtonIntegrator, aabbWalls, sphere)
from talus.flow import FlowEngine, ThermalEngine

PACKING = Path("/usr/share/doc/yade/examples/ThermalEngine/5cmEdge_1mm.spheres")
NO_FLUID = dict(advection=False, fluidConduction=False, fluidThermoMech=False)


def engines(*coupling):
    return [ForceResetter(), InsertionSortCollider([Bo1_Sphere_Aabb(), Bo1_Wall_Aabb()]),
            InteractionLoop([Ig2_Sphere_Sphere_ScGeom(), Ig2_Wall_Sphere_ScGeom()], [Ip2_FrictMat_FrictMat_FrictPhys()],
                            [Law2_ScGeom_FrictPhys_CundallStrack()]), *coupling, NewtonIntegrator(damping=0)]


def chain(thermal, n=5, radius=0.01):
    """n touching fixed spheres along x."""
    O.reset()
    mat = O.materials.append(FrictMat(young=1e7, density=2600))
    for i in range(n):
        O.bodies.append(sphere((i * 2 * radius * (1 - 5e-5), 0, 0), radius, fixed=True, material=mat))
    O.engines = engines(thermal)
    O.dt = 1e-3
    return thermal


def test_radii_follow_each_sphere_temperature_change():
    """A hot sphere in a cold chain: each thermal run multiplies every radius by 1 + alpha dT of
    that run, the hot one shrinking, its neighbours growing; the contacts see the new overlaps
    (alpha small enough that the overlaps of 1e-6 m stay)."""
    alpha = 1e-6
    thermal = chain(ThermalEngine(thermoMech=True, solidThermoMech=False, particleAlpha=alpha, particleT0=300,
                                  particleK=50, tsSafetyFactor=0, **NO_FLUID))
    O.dt = 0.5    # the chain's stable conduction step is 4 s
    O.bodies[2].state.temp = 400
    O.step()      # the reference temperatures are those of this first run's start
    for _ in range(20):
        before = np.array([b.state.temp for b in O.bodies])
        radii0 = np.array([b.shape.radius for b in O.bodies])
        O.step()
        temps = np.array([b.state.temp for b in O.bodies])
        radii = np.array([b.shape.radius for b in O.bodies])
        np.testing.assert_allclose(radii, radii0 * (1 + alpha * (temps - before)), rtol=1e-14)
    assert temps[2] < 390 and temps[1] > 305 and radii[2] < 0.01 < radii[1]
    # the contact pass of the next step sees the radii of this step's end (expansion comes after it)
    O.step()
    distance = (O.bodies[2].state.pos - O.bodies[1].state.pos).norm()
    assert O.interactions[1, 2].geom.penetrationDepth == pytest.approx(radii[1] + radii[2] - distance, rel=1e-9)
    assert radii[1] + radii[2] - distance != pytest.approx(0.02 - distance, rel=1e-3)
    assert thermal.particleAlpha == alpha


def test_alpha_zero_does_not_grow_and_per_body_alpha_with_delT():
    thermal = chain(ThermalEngine(thermoMech=True, solidThermoMech=False, particleAlpha=0, particleT0=300,
                                  tsSafetyFactor=0, **NO_FLUID))
    O.dt = 0.5
    O.bodies[2].state.temp = 400
    radii0 = [b.shape.radius for b in O.bodies]
    O.run(20, True)
    assert [b.shape.radius for b in O.bodies] == radii0
    O.bodies[0].state.alpha = 1e-3     # per body, as Yade's state.alpha
    thermal.delT = 10                  # added once to every free sphere, after this step's conduction
    before = O.bodies[0].state.temp
    O.step()
    change = O.bodies[0].state.temp - before
    assert 10 < change < 10.5
    assert O.bodies[0].shape.radius == pytest.approx(radii0[0] * (1 + 1e-3 * change), rel=1e-14)
    assert O.bodies[1].shape.radius == radii0[1]


def test_growth_without_a_flow_engine_warns_that_no_pore_changes():
    chain(ThermalEngine(thermoMech=True, solidThermoMech=True, particleAlpha=1e-5, tsSafetyFactor=0, **NO_FLUID))
    with pytest.warns(RuntimeWarning, match="solidThermoMech: O.engines has no FlowEngine"):
        O.step()


def packing(alpha, drained=False):
    O.reset()
    O.materials.append(FrictMat(young=1e9, poisson=0.5, density=2600, label="spheres"))
    O.bodies.append(aabbWalls([(0, 0, 0), (0.05, 0.05, 0.05)], thickness=0))
    rows = [[float(v) for v in line.split()] for line in PACKING.read_text().splitlines()
            if line.strip() and not line.startswith("#")]
    O.bodies.append([sphere((x, y, z), r, material="spheres", fixed=True) for x, y, z, r in rows])
    flow = FlowEngine(viscosity=1e-3, fluidBulkModulus=2.2e9, tZero=20, bndCondIsPressure=[int(drained), 0, 0, 0, 0, 0])
    thermal = ThermalEngine(advection=True, uniformReynolds=10, thermoMech=True, fluidThermoMech=True,
                            solidThermoMech=True, fluidBeta=2e-4, particleAlpha=alpha, particleT0=20, tsSafetyFactor=0)
    O.engines = engines(flow, thermal)
    O.dt = 1e-5
    return flow, thermal


def heat_everything(flow, dT):
    heat = flow._poreHeat
    for i, t in enumerate(heat.temperatures()):
        heat.setTemperature(i, t + dT)
    for b in O.bodies:
        if type(b.shape).__name__ == "Sphere":
            b.state.temp += dT


def mean_pressure(flow):
    v = np.maximum(flow.cellVoidVolumes, 0)
    return float(np.sum(flow.pressures * v) / np.sum(v))


@pytest.mark.skipif(not PACKING.exists(), reason="Yade's examples (the packing of its ThermalEngine scripts) are not installed")
def test_undrained_pressure_of_the_fluid_expansion():
    """1 K on every pore and sphere of a closed saturated packing: every pore's pressure rises by
    K_f fluidBeta dT (4.4e5 Pa) at the next solve, and stays; with particleAlpha the spheres' growth
    adds K_f dV_s / V_f to the mean."""
    flow, thermal = packing(alpha=0)
    O.run(2, True)
    heat_everything(flow, 1.0)
    O.run(2, True)
    expected = 2.2e9 * 2e-4
    p = np.asarray(flow.pressures)
    stores = np.asarray(flow.cellVoidVolumes) > 0
    # 6e-7: the storage term takes the void volumes of the mesh, the expansion those recomputed since
    np.testing.assert_allclose(p[stores], expected, rtol=1e-5)
    O.run(3, True)
    assert mean_pressure(flow) == pytest.approx(expected, rel=1e-5)

    flow, thermal = packing(alpha=3e-5)
    O.run(2, True)
    radii0 = np.array([b.shape.radius for b in O.bodies if type(b.shape).__name__ == "Sphere"])
    heat_everything(flow, 1.0)
    O.run(2, True)
    radii = np.array([b.shape.radius for b in O.bodies if type(b.shape).__name__ == "Sphere"])
    np.testing.assert_allclose(radii, radii0 * (1 + 3e-5), rtol=1e-12)
    solid = np.sum(4 / 3 * math.pi * (radii ** 3 - radii0 ** 3))
    voids = np.sum(np.maximum(flow.cellVoidVolumes, 0))
    assert mean_pressure(flow) == pytest.approx(2.2e9 * (2e-4 * voids + solid) / voids, rel=1e-5)


@pytest.mark.skipif(not PACKING.exists(), reason="Yade's examples (the packing of its ThermalEngine scripts) are not installed")
def test_drained_pressure_decays_and_checkpoint_keeps_expansion_state(tmp_path):
    flow, thermal = packing(alpha=1e-5, drained=True)
    O.run(2, True)
    heat_everything(flow, 1.0)
    O.run(2, True)
    peak = mean_pressure(flow)
    assert 0 < peak < 2.2e9 * 2e-4 * 1.5
    O.run(20, True)
    assert mean_pressure(flow) < peak
    O.bodies[8].state.alpha = 2e-5
    path = tmp_path / "thm.h5"
    O.save(str(path))
    alphas = [b.state.alpha for b in O.bodies if type(b.shape).__name__ == "Sphere"]
    O.load(str(path))
    assert [b.state.alpha for b in O.bodies if type(b.shape).__name__ == "Sphere"] == alphas


@pytest.mark.skipif(not PACKING.exists(), reason="Yade's examples (the packing of its ThermalEngine scripts) are not installed")
def test_checkpoint_keeps_the_pore_temperatures(tmp_path):
    """Hot water flowing in, saved half-way: the run reloaded goes on as the uninterrupted one
    (the pores take their saved temperatures once the FlowEngine has rebuilt its network)."""
    flow, thermal = packing(alpha=0, drained=True)
    flow.bndCondIsPressure = [1, 1, 0, 0, 0, 0]
    flow.bndCondValue = [10, 0, 0, 0, 0, 0]
    flow.bndCondIsTemperature = [1, 0, 0, 0, 0, 0]
    flow.thermalBndCondValue = [70, 0, 0, 0, 0, 0]
    flow.fluidBulkModulus = 0
    thermal.thermoMech = False
    O.dt = 1e-4
    O.run(30, True)
    path = tmp_path / "pores.h5"
    O.save(str(path))
    O.run(30, True)
    pores = np.array(O.engines[3].cellTemperatures)
    spheres = [b.state.temp for b in O.bodies if type(b.shape).__name__ == "Sphere"]
    assert pores.max() > 25
    O.load(str(path))
    O.run(30, True)
    np.testing.assert_allclose(O.engines[3].cellTemperatures, pores, rtol=0, atol=1e-9)
    np.testing.assert_allclose([b.state.temp for b in O.bodies if type(b.shape).__name__ == "Sphere"], spheres,
                               rtol=0, atol=1e-9)


@pytest.mark.skipif(not PACKING.exists(), reason="Yade's examples (the packing of its ThermalEngine scripts) are not installed")
def test_pore_temperatures_in_the_flow_vtk(tmp_path):
    flow, thermal = packing(alpha=0, drained=True)
    O.run(2, True)
    heat_everything(flow, 5.0)
    O.run(1, True)
    pores, _ = flow.saveVtk(str(tmp_path / "net"))
    text = Path(pores).read_text().split("SCALARS temperature double 1\nLOOKUP_TABLE default\n")[1].split()
    written = np.array([float(v) for v in text[:flow.nCells()]])
    np.testing.assert_allclose(written, flow.cellTemperatures, rtol=1e-5)
    assert written.min() > 24.9
