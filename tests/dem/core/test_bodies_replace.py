"""O.bodies.clear and O.bodies.replace (Yade's): every body and contact goes, ids start again at
0, and the scene then runs as a new scene made of the new bodies would, whatever ran before
(laws with contact state included); VTK output and checkpoints of the new bodies."""
import numpy as np
import pytest

from talus.dem import (FrictMat, ForceResetter, InsertionSortCollider, InteractionLoop,
                       Ip2_FrictMat_FrictMat_MindlinPhys, Law2_ScGeom_MindlinPhys_Mindlin, NewtonIntegrator,
                       Scene, facet, sphere)
from talus.dem.files import export, io


def floor_and_spheres(m: int, seed: int) -> list:
    """Two facets as a floor and an m x m x 2 lattice of jittered spheres just above it."""
    rng = np.random.default_rng(seed)
    grid = np.stack(np.meshgrid(np.arange(m), np.arange(m), np.arange(2), indexing="ij"), -1).reshape(-1, 3)
    centres = (grid + 0.5 + rng.uniform(-0.05, 0.05, grid.shape)) / m
    return ([facet([(-0.1, -0.1, 0), (1.1, -0.1, 0), (1.1, 1.1, 0)]),
             facet([(-0.1, -0.1, 0), (1.1, 1.1, 0), (-0.1, 1.1, 0)])]
            + [sphere(c, r) for c, r in zip(centres, rng.uniform(0.45, 0.5, len(grid)) / m)])


def hertz_scene() -> Scene:
    S = Scene()
    S.materials.append(FrictMat(young=1e7, poisson=0.3, frictionAngle=0.5, density=2600))
    S.engines = [ForceResetter(), InsertionSortCollider(),
                 InteractionLoop([], [Ip2_FrictMat_FrictMat_MindlinPhys(en=0.5)], [Law2_ScGeom_MindlinPhys_Mindlin()]),
                 NewtonIntegrator(gravity=(0, 0, -9.81), damping=0.2)]
    S.dt = 2e-4
    return S


def test_replace_runs_as_a_new_scene_would():
    """A Hertz-Mindlin bed of 72 spheres that has run (contacts with state) is replaced by 32
    other spheres: after 1000 steps they are where the same 32 spheres of a new scene are, to
    the bit."""
    used = hertz_scene()
    used.bodies.append(floor_and_spheres(6, seed=1))
    used.run(1000, wait=True)
    assert used._cpp.realContactCount() > 50
    ids = used.bodies.replace(floor_and_spheres(4, seed=2))
    assert ids == list(range(34)) and len(used.bodies) == 34
    assert used.interactions.countReal() == 0
    used.run(1000, wait=True)

    new = hertz_scene()
    new.bodies.append(floor_and_spheres(4, seed=2))
    new.run(1000, wait=True)
    assert new._cpp.realContactCount() > 20
    assert np.array_equal(used.positions(), new.positions())
    assert np.array_equal(used.velocities(), new.velocities())
    assert used._cpp.realContactCount() == new._cpp.realContactCount()


def test_clear_restarts_ids_and_forgets_looks_and_references():
    S = hertz_scene()
    b = sphere((0, 0, 1), 0.1, color=(1, 0, 0))
    S.bodies.append([sphere((0, 0, 0), 0.1), b])
    S.bodies[1].state.refPos = (5, 5, 5)
    S.bodies.clear()
    assert len(S.bodies) == 0 and S.interactions.countReal() == 0 and list(S.bodies) == []
    with pytest.raises(IndexError, match="no body with id 1"):
        S.bodies[1]
    assert S.bodies.append(sphere((0, 0, 2), 0.1)) == 0
    assert tuple(S.bodies[0].shape.color) != (1, 0, 0)                  # the default look again
    assert tuple(S.bodies[0].state.refPos) == (0, 0, 2)                 # its own reference
    S.run(5, wait=True)
    assert S.iter == 5 and S.bodies[0].state.pos[2] < 2


def test_replace_refuses_what_is_not_a_body_and_keeps_the_scene():
    S = hertz_scene()
    S.bodies.append(sphere((0, 0, 0), 0.1))
    with pytest.raises(TypeError, match="O.bodies.replace: takes bodies"):
        S.bodies.replace([sphere((0, 0, 1), 0.1), (0, 0, 1)])
    assert len(S.bodies) == 1


@pytest.mark.skipif(not io.available(), reason="built without HDF5")
def test_replaced_scene_writes_vtk_and_restarts(tmp_path):
    S = hertz_scene()
    S.bodies.append(floor_and_spheres(5, seed=3))
    S.run(50, wait=True)
    S.bodies.replace(floor_and_spheres(3, seed=4))
    S.run(50, wait=True)
    io.save(S, tmp_path / "r.h5")
    R = Scene()
    io.load(R, tmp_path / "r.h5")
    assert len(R.bodies) == 20
    assert np.array_equal(R.positions(), S.positions())
    written = export.VTKExporter(str(tmp_path / "r"), scene=S).exportSpheres()
    assert 'NumberOfPoints="18"' in open(written).read()
