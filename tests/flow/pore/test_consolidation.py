"""A coupled 1D consolidation (the oedometer phase of Yade's FluidCouplingPFV/oedometer.py) from
a fixed packing, against Yade 2023.02a (consolidation_side_by_side.py): the top wall loads a
drained-at-the-top sample from 10 to 11 kPa at O.dt = 1e-4 without damping. The excess pore
pressure at the undrained bottom rises to the load increment (Terzaghi's initial condition) and
the fluid forces stay bounded; with the step the time stepper would have given (16 times larger,
what `O.dynDt = False` failed to keep) the same run blew up within 25 steps."""
from pathlib import Path

import numpy as np
import pytest

from talus import twin

HERE = Path(__file__).parent
LOAD = 1000.0   # Pa, the load increment


@pytest.fixture(scope="module")
def talus_trace():
    return np.array(twin.run(HERE / "consolidation_side_by_side.py", {"steps": 1000}, "talus")["trace"])


def test_consolidation_is_stable_and_builds_the_pore_pressure_of_the_load(talus_trace):
    iters, dt, top, p, fmax = talus_trace.T
    assert np.all(dt == 1e-4)                       # the hand-set step is kept (O.dynDt = False)
    assert np.all(np.diff(top) < 0)                 # the sample settles, monotonically
    assert 5e-4 < top[0] - top[-1] < 5e-3
    assert np.all(fmax < 100)                       # N; an unstable coupling grows without bound
    assert abs(p[-1] - LOAD) < 0.15 * LOAD          # undrained bottom: excess pressure = load increment


@pytest.mark.skipif(not twin.yade_available(), reason="yade is not installed")
def test_consolidation_as_yade(talus_trace):
    yade = np.array(twin.run(HERE / "consolidation_side_by_side.py", {"steps": 1000}, "yade")["trace"])
    assert talus_trace.shape == yade.shape
    settlement = 1 - yade[:, 2]
    # measured: settlements within 5e-7 of 1.2e-3, pressures within 0.6 %, forces within 1 %
    assert np.allclose(1 - talus_trace[:, 2], settlement, rtol=0, atol=0.002 * settlement.max())
    assert np.allclose(talus_trace[:, 3], yade[:, 3], rtol=0, atol=0.02 * LOAD)
    assert np.allclose(talus_trace[:, 4], yade[:, 4], rtol=0.05)
