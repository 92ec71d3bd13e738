"""Scenes of absurd extent: the collider's grid stays proportional to the sphere count whatever
the scene's shape (flat, long, a sparse periodic cell), and a body a step moved absurdly far is
named instead of a raw allocation error."""
import os
import subprocess
import sys
import textwrap

import pytest

from talus.dem import (ForceResetter, InsertionSortCollider, InteractionLoop, Ip2_FrictMat_FrictMat_FrictPhys,
                       Law2_ScGeom_FrictPhys_CundallStrack, NewtonIntegrator, Scene, sphere, wall)

LINEAR = ([Ip2_FrictMat_FrictMat_FrictPhys()], [Law2_ScGeom_FrictPhys_CundallStrack()])


def scene_of(centres, radius=1e-3, periodic_size=None):
    S = Scene()
    if periodic_size:
        S.periodic = True
        S.cell.setBox(periodic_size)
    S.bodies.append([sphere(c, radius) for c in centres])
    S.engines = [ForceResetter(), InsertionSortCollider(), InteractionLoop([], *LINEAR), NewtonIntegrator()]
    S.dt = 1e-7
    return S


# Flat (two axes in one cell before), long, and sparse periodic scenes: each took gigabytes (or
# failed with bad_alloc) when the grid was not coarsened.
SPARSE = {
    "plane 300 m": "scene_of([(0, 0, 0), (300, 0, 0), (0, 300, 0)])",
    "plane 1000 m": "scene_of([(0, 0, 0), (1000, 0, 0), (0, 1000, 0)])",
    "line 1e7 m": "scene_of([(0, 0, 0), (1e7, 0, 0)])",
    "periodic 1000 m": "scene_of([(1, 1, 1), (500, 500, 500)], periodic_size=(1000, 1000, 1000))",
}


@pytest.mark.parametrize("scene", SPARSE.values(), ids=list(SPARSE))
def test_sparse_scenes_of_any_shape_stay_small(scene, build_dir):
    # In a process of its own, to read its peak memory.
    code = textwrap.dedent(f"""
        import resource, sys
        sys.path.insert(0, {str(__import__('pathlib').Path(__file__).parent)!r})
        from test_bad_input_extent import scene_of
        before = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss
        S = {scene}
        S.run(10)
        print(S.iter, (resource.getrusage(resource.RUSAGE_SELF).ru_maxrss - before) / 1024)
        """)
    env = {**os.environ, "PYTHONPATH": str(build_dir / "python")}
    done = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=120, env=env)
    assert done.returncode == 0, done.stderr
    steps, grown_mb = done.stdout.split()
    assert int(steps) == 10
    assert float(grown_mb) < 50, f"the run grew the process by {grown_mb} MB"


@pytest.mark.parametrize("periodic_size", [None, (1, 1, 1)], ids=["open", "periodic"])
def test_a_step_that_sends_a_body_to_infinity_names_it(periodic_size):
    S = scene_of([(0, 0, 0.1), (0.1, 0, 0.1)], radius=0.01, periodic_size=periodic_size)
    if not periodic_size:
        S.bodies.append(wall(0, axis=2, sense=1))
    S.overlapStops = False          # Yade's: no time-step check, the run goes on until it cannot
    S.dt = 1e300
    S.engines = S.engines[:-1] + [NewtonIntegrator(gravity=(0, 0, -9.81))]
    with pytest.warns(RuntimeWarning, match="times the P-wave critical step"):
        with pytest.raises(RuntimeError, match=r"body 0 has a non-finite position \(0, 0, -inf\) \(velocity .*\): "
                                               r"a velocity or O.dt so large"):
            S.run(3)


def test_bodies_too_far_apart_for_doubles_are_named():
    S = scene_of([(-1e308, 0, 0), (0, 0, 0), (1e308, 0, 0)])
    with pytest.raises(RuntimeError, match=r"bodies 0 and 2 are too far apart along axis 0 .*extent overflows"):
        S.step()


def test_a_huge_velocity_runs_on_a_coarse_grid():
    S = scene_of([(0, 0, 0), (0.1, 0, 0)], radius=0.01)
    S.bodies[0].state.vel = (1e300, 0, 0)
    S.dt = 1e-6
    S.run(3)                       # 1e294 m away: a coarse grid, no allocation
    assert S.bodies[0].state.pos[0] == pytest.approx(3e294)


def test_periodic_body_billions_of_cells_away_is_named():
    S = scene_of([(0.5, 0.5, 0.5), (0.2, 0.2, 0.2)], radius=0.05, periodic_size=(1, 1, 1))
    S.bodies[1].state.pos = (1e12, 0.2, 0.2)
    with pytest.raises(RuntimeError, match="body 1 is more than 1e9 periodic cells away"):
        S.step()

