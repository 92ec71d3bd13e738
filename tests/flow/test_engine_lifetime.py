"""A fluid engine the script drops is freed with its pore network and CHOLMOD factor (its C++
runner once held a bound method: a reference cycle through C++ that the garbage collector does
not see, so every engine lived to the end of the process), and one in O.engines lives on and
steps."""
import gc
import weakref

import numpy as np
import pytest

from talus.dem import O, aabbWalls, sphere
from talus.flow import FlowEngine, HydroForceEngine, PeriodicFlowEngine, ThermalEngine

ENGINES = [(FlowEngine, {}), (PeriodicFlowEngine, {}), (ThermalEngine, {}),
           (HydroForceEngine, dict(nCell=10, deltaZ=0.01))]


@pytest.mark.parametrize("make, keywords", ENGINES, ids=[e[0].__name__ for e in ENGINES])
def test_a_dropped_engine_is_freed(make, keywords):
    engine = make(**keywords)
    ref = weakref.ref(engine)
    del engine
    gc.collect()
    assert ref() is None


def test_an_engine_in_the_engine_list_lives_and_steps():
    O.reset()
    rng = np.random.default_rng(3)
    O.bodies.append(aabbWalls([(0, 0, 0), (1, 1, 1)], thickness=0))
    for x in rng.uniform(0.15, 0.85, (60, 3)):
        O.bodies.append(sphere(tuple(x), 0.08, fixed=True))
    flow = FlowEngine(bndCondIsPressure=[0, 0, 1, 1, 0, 0], bndCondValue=[0, 0, 1, 0, 0, 0])
    ref = weakref.ref(flow)
    O.engines = [flow]
    del flow
    gc.collect()
    assert ref() is not None
    O.step()
    assert ref().getBoundaryFlux(2) < 0       # fluid enters at ymin: the engine ran its step
    O.reset()
