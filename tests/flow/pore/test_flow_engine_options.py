"""Yade's FlowEngine options of its ThermalEngine examples: meshUpdateInterval < 0 (never
remesh by count), decoupleForces (fluid forces kept off the bodies), pZero (the initial pressure
of a compressible fluid), debug (accepted), permeabilityMap (True refused)."""
from pathlib import Path

import numpy as np
import pytest

from talus.flow import FlowEngine

DATA = Path(__file__).resolve().parents[1] / "data"


def _sample(steps, velocity=0.5, **engine):
    """The 400 spheres of the pore tests moving towards the centre at ``velocity`` x distance
    (no contacts), ``steps`` steps; returns the engine, the scene and the sphere ids."""
    from talus.dem import ForceResetter, NewtonIntegrator, Scene, sphere
    a = np.loadtxt(DATA / "pore_packing.txt")
    S = Scene()
    ids = S.bodies.append([sphere(p, r, fixed=True) for p, r in zip(a[:, :3], a[:, 3])])
    vel = np.asarray(S.velocities())
    vel[ids] = -velocity * (a[:, :3] - 0.5)
    S.velocities()[:] = vel
    flow = FlowEngine(scene=S, wallIds=[-1] * 6, **engine)
    S.engines = [ForceResetter(), flow, NewtonIntegrator(damping=0)]
    S.dt = 2e-3
    for _ in range(steps):
        S.step()
    return flow, S, ids


DRAINED = dict(bndCondIsPressure=[0, 0, 1, 1, 0, 0], bndCondValue=[0] * 6)


def test_negative_meshUpdateInterval_never_remeshes_by_count():
    every3, _, _ = _sample(7, meshUpdateInterval=3, **DRAINED)
    never, _, _ = _sample(7, meshUpdateInterval=-1, **DRAINED)
    assert every3.remeshCount()[0] == 3
    assert never.remeshCount()[0] == 1 and never.meshUpdateInterval == -1
    never.updateTriangulation = True      # a requested remesh still comes
    never._scene.step()
    assert never.remeshCount()[0] == 2


def test_decoupleForces_keeps_the_fluid_forces_off_the_bodies():
    coupled, S, ids = _sample(2, **DRAINED)
    decoupled, T, _ = _sample(2, decoupleForces=True, **DRAINED)
    f, g = np.asarray(S.forces())[ids], np.asarray(T.forces())[ids]
    assert np.abs(f).max() > 0 and np.abs(g).max() == 0
    # the same fluid: its forces are computed all the same
    assert np.allclose(decoupled.fluidForce(ids[7]), coupled.fluidForce(ids[7]), rtol=1e-12, atol=0)
    assert np.allclose(f[7], coupled.fluidForce(ids[7]), rtol=1e-12, atol=1e-15)


def test_pZero_is_the_initial_pressure_of_a_compressible_fluid():
    closed = dict(bndCondIsPressure=[0] * 6, fluidBulkModulus=1e5)
    rest, _, _ = _sample(3, velocity=0.0, pZero=10, **closed)     # closed, at rest: stays at pZero
    p = [rest.getCellPressure(c) for c in range(rest.nCells())]
    assert np.allclose(p, 10.0, rtol=1e-9, atol=0)
    drained, _, _ = _sample(1, velocity=0.0, pZero=10, fluidBulkModulus=1e5, **DRAINED)
    p = np.array([drained.getCellPressure(c) for c in range(drained.nCells())])
    assert 0 < p.max() < 10 and p.min() >= 0                       # relaxing towards the drained faces
    zero, _, _ = _sample(1, velocity=0.0, fluidBulkModulus=1e5, **DRAINED)
    assert max(abs(zero.getCellPressure(c)) for c in range(zero.nCells())) == 0


def test_debug_is_accepted_and_permeabilityMap_is_refused():
    flow = FlowEngine(debug=True, permeabilityMap=False)
    assert flow.debug and not flow.permeabilityMap and not flow.decoupleForces and flow.pZero == 0
    with pytest.raises(ValueError, match="permeabilityMap = True"):
        flow.permeabilityMap = True
    with pytest.raises(AttributeError, match="no attribute 'permeabilityMaps'"):
        flow.permeabilityMaps = True


def test_saveVtk_without_the_boundary_pores_into_a_folder(tmp_path):
    from talus.dem import Scene
    a = np.loadtxt(DATA / "pore_packing.txt")
    flow = FlowEngine(scene=Scene(), **DRAINED)
    flow.bndCondValue = [0, 0, 1, 0, 0, 0]
    flow.triangulate(a[:, :3], a[:, 3], np.arange(6, 6 + len(a)))    # vertex ids 0..5: the walls
    flow.solve()
    inner = [c for c in range(flow.nCells()) if min(flow.getVertices(c)) >= 6]
    assert 0 < len(inner) < flow.nCells()
    pores, _ = flow.saveVtk(str(tmp_path / "VTK") + "/", withBoundaries=False)
    assert pores == str(tmp_path / "VTK" / "pores_0.pores.vtk")     # Yade's folder form, at iteration 0
    lines = open(pores).read().splitlines()
    assert f"CELLS {len(inner)} {5 * len(inner)}" in lines
    start = lines.index("SCALARS pressure double 1") + 2
    assert np.allclose([float(x) for x in lines[start:start + len(inner)]], flow.pressures[inner], rtol=1e-12)
    every, _ = flow.saveVtk(str(tmp_path / "all"))
    assert f"CELLS {flow.nCells()} {5 * flow.nCells()}" in open(every).read().splitlines()


def test_a_misspelt_attribute_is_refused_with_the_close_name():
    # Yade's flowScenario.py sets minKdivmean, which Yade stores without effect
    with pytest.raises(AttributeError, match="no attribute 'minKdivmean' \\(did you mean 'minKdivKmean'\\?\\)"):
        FlowEngine().minKdivmean = 1e-4
