"""Yade's ParallelEngine: slaves (engines or lists of engines) kept as given, run in order; a
scene stepping through one gives the bits of the same engines listed flat."""
import numpy as np
import pytest

from talus.dem import (BoundDispatcher, ForceResetter, GravityEngine, InsertionSortCollider, InteractionLoop,
                       Ip2_FrictMat_FrictMat_FrictPhys, Law2_ScGeom_FrictPhys_CundallStrack, NewtonIntegrator,
                       ParallelEngine, PyRunner, Scene, sphere)


def test_slaves_as_yade_keeps_them():
    pe = ParallelEngine([InsertionSortCollider(), [BoundDispatcher(), ForceResetter()]])
    assert type(pe.slaves[0]) is InsertionSortCollider and len(pe.slaves[1]) == 2
    pe.slaves = []
    assert pe.slaves == []
    with pytest.raises(TypeError, match="ParallelEngine.slaves takes engines or lists of engines, got 3"):
        ParallelEngine([ForceResetter(), [3]])


def stepped(parallel: bool) -> Scene:
    S = Scene()
    S.bodies.append([sphere((0.3 * i, 0, 0.2399 * j), 0.12, fixed=j == 0) for i in range(4) for j in range(3)])
    calls = []
    collider, runner = InsertionSortCollider(), PyRunner(command=lambda: calls.append(S.iter), iterPeriod=5)
    gravity = GravityEngine(gravity=(0, 0, -9.81))
    middle = [ParallelEngine([collider, [runner, gravity]])] if parallel else [collider, runner, gravity]
    S.engines = ([ForceResetter()] + middle
                 + [InteractionLoop([], [Ip2_FrictMat_FrictMat_FrictPhys()], [Law2_ScGeom_FrictPhys_CundallStrack()]),
                    NewtonIntegrator(damping=0.1)])
    S.dt = 1e-4
    S.run(200, True)
    assert calls == list(range(5, 200, 5))
    return S


def test_a_step_through_a_parallel_engine_equals_the_flat_list():
    flat, grouped = stepped(False), stepped(True)
    assert grouped._cpp.realContactCount() > 0
    assert np.array_equal(flat.positions(), grouped.positions())
