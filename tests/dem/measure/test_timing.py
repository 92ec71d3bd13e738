"""Per-engine timing (O.timingEnabled, Engine.execTime/execCount/timingDeltas, talus.dem.analysis.timing):
counts match the steps taken while it is on, stages add up to their engine, and timing changes
nothing in the physics."""
import numpy as np

from talus.dem.analysis import timing

from energy_deposition import scene as deposition


def positions(S):
    return np.array([b.state.pos for b in S.bodies])


def test_engines_are_timed_only_while_enabled():
    S = deposition("linear", m=4, track=False)
    S.run(10)
    assert all(e.execCount == 0 and e.execTime == 0 for e in S.engines)
    S.timingEnabled = True
    S.run(25)
    for e in S.engines:
        # The step resets each body's forces in the gather (dem/step/GatherAhead.h): the
        # resetter is counted and its time booked with the gather's.
        reset_in_gather = type(e).__name__ == "ForceResetter"
        assert e.execCount == 25 and (e.execTime > 0 or reset_in_gather), type(e).__name__
    collider, loop = S.engines[1], S.engines[2]
    stages = {name: (nsec, count) for name, nsec, count in loop.timingDeltas.data}
    assert list(stages) == ["geometry, physics, law", "forces per body"]
    assert all(count == 25 for _, count in stages.values())
    assert sum(nsec for nsec, _ in stages.values()) <= loop.execTime
    checks = {name: count for name, _, count in collider.timingDeltas.data}
    assert checks["skin check"] == 25 and 0 <= checks.get("re-detection", 0) <= 25
    S.timingEnabled = False
    S.run(5)
    assert all(e.execCount == 25 for e in S.engines)


def test_stats_table_and_reset():
    S = deposition("linear", m=3, track=False)
    S.timingEnabled = True
    S.run(5)
    text = timing.stats(S, file=open("/dev/null", "w"))
    for name in ("ForceResetter", "InsertionSortCollider", "InteractionLoop", "NewtonIntegrator", "forces per body"):
        assert name in text
    rows = timing.rows(S)
    assert [r["count"] for r in rows] == [5, 5, 5, 5]
    timing.reset(S)
    assert all(r["count"] == 0 and r["nsec"] == 0 and r["stages"] == [] for r in timing.rows(S))


def test_timing_does_not_change_the_physics():
    timed, plain = deposition("linear", m=4, track=False), deposition("linear", m=4, track=False)
    timed.timingEnabled = True
    timed.run(300)
    plain.run(300)
    assert np.array_equal(positions(timed), positions(plain))
