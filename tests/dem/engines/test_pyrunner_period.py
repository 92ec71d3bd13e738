"""PyRunner's virtPeriod (simulated seconds between calls), as Yade's PeriodicEngine."""
import pytest

from talus.dem import ForceResetter, NewtonIntegrator, PyRunner, Scene, sphere


def test_virt_period_calls_at_yades_times():
    S = Scene()
    S.bodies.append(sphere((0, 0, 0), 0.1))
    times = []
    S.engines = [ForceResetter(), NewtonIntegrator(), PyRunner(command=lambda: times.append(round(S.time, 10)),
                                                               virtPeriod=0.0025)]
    S.dt = 1e-3
    S.run(10)
    assert times == [0.003, 0.006, 0.009]   # Yade 2023.02a, the same scene
    with pytest.raises(ValueError, match="virtPeriod must be >= 0"):
        PyRunner(command="pass", virtPeriod=-1)
