"""O.run() until O.pause() from a PyRunner, PyRunner periods by steps and by wall-clock time."""
import time

import pytest

from talus.dem import ForceResetter, NewtonIntegrator, PyRunner, Scene, sphere


def falling():
    S = Scene()
    S.bodies.append(sphere((0, 0, 0), 0.1))
    S.engines = [ForceResetter(), NewtonIntegrator(gravity=(0, 0, -10))]
    S.dt = 1e-4
    return S


def test_run_until_pause_stops_after_the_pausing_step():
    S = falling()
    S.engines = S.engines + [PyRunner(command=lambda: S.iter == 1233 and S.pause(), iterPeriod=1)]
    S.run(wait=True)
    assert S.iter == 1234           # the runner sees iter before the clock advances
    S.run(10)                       # a pause does not carry over to the next run
    assert S.iter == 1244


def test_run_without_a_runner_is_refused():
    S = falling()
    with pytest.raises(ValueError, match="O.pause"):
        S.run(wait=True)
    with pytest.raises(ValueError, match="nSteps"):
        S.run(-5)


def test_iter_period_counts_steps():
    S = falling()
    calls = []
    S.engines = S.engines + [PyRunner(command=lambda: calls.append(S.iter), iterPeriod=10)]
    S.run(35)
    assert calls == [10, 20, 30]


def test_real_period_counts_seconds():
    S = falling()
    calls = []
    S.engines = S.engines + [PyRunner(command=lambda: (calls.append(time.monotonic()), time.sleep(0.002)),
                                      realPeriod=0.05)]
    start = time.monotonic()
    while time.monotonic() - start < 0.3:
        S.run(10)
    elapsed = time.monotonic() - start
    # Never more often than realPeriod; on a loaded machine the run may get fewer time slices,
    # so only the upper bound is tight.
    assert 2 <= len(calls) <= elapsed / 0.05 + 1
    gaps = [b - a for a, b in zip(calls, calls[1:])]
    assert min(gaps) >= 0.049


def test_default_period_is_every_step():
    S = falling()
    calls = []
    S.engines = S.engines + [PyRunner(command=lambda: calls.append(S.iter))]
    S.run(5)
    assert calls == [1, 2, 3, 4]     # as Yade: the first call when iter reaches iterPeriod


def test_open_ended_run_without_wait_runs_at_wait_as_in_yade():
    """Yade's O.run() returns at once and runs in the background; Talus keeps it for O.wait()
    (a script ending before that stops it, as yade -x does)."""
    S = falling()
    S.engines = S.engines + [PyRunner(command=lambda: S.iter == 99 and S.pause(), iterPeriod=1)]
    S.run()
    assert S.iter == 0 and S.running
    S.wait()
    assert S.iter == 100 and not S.running


def test_stop_at_iter_and_time():
    S = falling()
    S.stopAtIter = 50
    S.run(wait=True)
    assert S.iter == 50
    S.run(20)                       # a limit already reached does not hold later runs
    assert S.iter == 70
    S.stopAtTime = S.time + 0.0105  # 1e-4 steps: the first step at or past it
    S.run(wait=True)
    assert S.iter == 176
    S.run(1000.0)                   # a whole number given as a float, as Yade's scripts do
    assert S.iter == 1176
    with pytest.raises(ValueError, match="whole number"):
        S.run(10.5)


def test_stop_limits_set_during_a_run_are_kept():
    # Yade checks O.stopAtIter at every step: a PyRunner setting it ends an open-ended run there
    # (spheresFactory.py stops its run so).
    from talus.dem import O, PyRunner
    O.reset()
    O.engines = [PyRunner(iterPeriod=10, command=lambda: setattr(O, "stopAtIter", O.iter + 5))]
    O.dt = 1.0
    O.run(); O.wait()
    assert O.iter == 15
    O.stopAtIter = 0
    O.engines = [PyRunner(iterPeriod=3, command=lambda: setattr(O, "stopAtTime", O.time + 2.5))]
    O.run(); O.wait()
    assert O.iter == 18
