"""Yade's particle factories (BoxFactory, CircularFactory) and DomainLimiter: against Yade
2023.02a (factories_side_by_side.py; Yade's factories draw from a clock-seeded generator, so
what is random is compared as statistics), and their regions, limits, seeds and errors."""
import math
import warnings
from pathlib import Path

import numpy as np
import pytest

from talus.dem import (BoxFactory, CircularFactory, DomainLimiter, ForceResetter, FrictMat,
                       InsertionSortCollider, InteractionLoop, NewtonIntegrator, O, SpheresFactory, sphere)
from talus import twin

TWINS = Path(__file__).parents[1] / "yade_twins" / "engines"  # the scripts Yade and Talus both run


@pytest.fixture(scope="module")
def runs():
    if not twin.yade_available():
        pytest.skip("yade is not installed")
    script = TWINS / "factories_side_by_side.py"
    return twin.run(script, {}, "talus"), twin.run(script, {}, "yade")


def test_exact_diameters_from_a_distribution_are_yades(runs):
    ours, theirs = (r["exact"] for r in runs)
    assert ours["counts"] == theirs["counts"] and ours["radii"] == theirs["radii"]
    assert set(ours["radii"]) == {0.01, 0.015, 0.025}


def test_random_sizes_and_velocities_have_yades_statistics(runs):
    # Yade's draws come from the clock: each run (ours with its seed, Yade's) is held to the
    # expected number and mean radius of the spheres within 4 standard deviations.
    ours, theirs = runs
    for name, bins, (vmin, vmax), direction in [
            ("binned", [(0.01, 0.015), (0.015, 0.025)], (1, 2), (math.sqrt(0.5), math.sqrt(0.5), 0)),
            ("disc", [(0.01, 0.03)], (2, 3), (1, 0, 0))]:
        # radii uniform in one of the bins, each bin as often
        moment = lambda k: np.mean([(b ** (k + 1) - a ** (k + 1)) / ((k + 1) * (b - a)) for a, b in bins])
        mass = lambda k: (4 / 3 * math.pi * 2000) ** k * moment(3 * k)        # k-th moment of a sphere's mass
        expected = 9.0 / mass(1)
        spread = math.sqrt(expected * (mass(2) - mass(1) ** 2)) / mass(1)
        radiusSpread = math.sqrt((moment(2) - moment(1) ** 2) / expected)
        for run in (ours[name], theirs[name]):
            assert run["counts"][2] == 9.0                                  # goal mass: 3000 kg/s x 30 steps
            assert 0 <= run["counts"][1] - 9.0 < 4 / 3 * math.pi * bins[-1][1] ** 3 * 2000   # up to the goal
            assert abs(run["counts"][0] - expected) < 4 * spread
            assert abs(np.mean(run["radii"]) - moment(1)) < 4 * radiusSpread
            assert bins[0][0] <= min(run["radii"]) and max(run["radii"]) <= bins[-1][1]
            assert vmin <= min(run["speeds"]) and max(run["speeds"]) <= vmax
            assert np.allclose(run["directions"], direction)
    # by number: half of the spheres in each bin, as Yade
    for run in runs:
        radii = np.array(run["binned"]["radii"])
        assert abs(np.sum(radii < 0.015) - np.sum(radii >= 0.015)) <= 1


def test_domain_limiter_is_yades(runs):
    ours, theirs = runs
    assert ours["limiter"] == theirs["limiter"]
    assert ours["limiter"][-1][0] == 5                                       # 4 spheres and a clump


def factory_scene(factory, steps=20):
    O.reset()
    O.materials.append(FrictMat(young=1e7, density=1000))
    O.engines = [ForceResetter(), InsertionSortCollider(verletDist=0), NewtonIntegrator(damping=0), factory]
    O.dt = 1e-3
    O.run(steps, True)
    ids = factory.ids
    return np.array([O.bodies[i].state.pos for i in ids]), np.array([O.bodies[i].shape.radius for i in ids])


def test_places_in_the_regions_without_overlaps():
    # velocities 0: the spheres stay where they were put
    pos, r = factory_scene(BoxFactory(center=(1, 2, 3), extents=(0.3, 0.2, 0), normal=(1, 0, 0), massFlowRate=50,
                                      rMin=0.01, rMax=0.02, vMin=0, vMax=0, maxParticles=-1))
    assert len(pos) > 50
    assert np.allclose(pos[:, 0], 1) and np.all(np.abs(pos[:, 1] - 2) <= 0.2) and np.all(np.abs(pos[:, 2] - 3) <= 0.3)
    gaps = np.linalg.norm(pos[:, None] - pos[None], axis=2) - (r[:, None] + r[None]) + 3 * np.eye(len(r))
    assert gaps.min() >= 0
    pos, r = factory_scene(CircularFactory(center=(0, 0, 1), radius=0.5, length=0.2, normal=(0, 0, 1), massFlowRate=50,
                                           rMin=0.01, rMax=0.02, vMin=0, vMax=0, maxParticles=-1))
    assert np.all(np.hypot(pos[:, 0], pos[:, 1]) <= 0.5 - r) and np.all(np.abs(pos[:, 2] - 1) <= 0.1)


def test_seeds_repeat_and_differ():
    make = lambda seed: BoxFactory(center=(0, 0, 0), extents=(1, 1, 1), normal=(0, 0, 1), massFlowRate=20, rMin=0.01,
                                   rMax=0.02, vMin=0, vMax=0, seed=seed)
    first, again, other = (factory_scene(make(s))[0] for s in (7, 7, 8))
    assert np.array_equal(first, again) and not np.array_equal(first[:len(other)], other[:len(first)])


def test_limits_stop_the_flow():
    f = BoxFactory(center=(0, 0, 0), extents=(1, 1, 1), normal=(0, 0, 1), massFlowRate=50, rMin=0.01, rMax=0.02,
                   vMin=0, vMax=0, maxParticles=7)
    factory_scene(f)
    assert f.numParticles == 7 and len(O.bodies) == 7 and f.goalMass == pytest.approx(50 * 20e-3)
    # a region too small for the next sphere: Yade's warning, and the factory stops
    f = BoxFactory(center=(0, 0, 0), extents=(0.01, 0.01, 0.01), normal=(0, 0, 1), massFlowRate=50, rMin=0.01,
                   rMax=0.01, vMin=0, vMax=0, maxAttempt=50)
    with pytest.warns(RuntimeWarning, match="unable to place new sphere after 50 attempts"):
        factory_scene(f)
    assert f.numParticles == 1 and f.massFlowRate == 0 and f.goalMass == f.totalMass


def test_checkpoint_keeps_the_generator():
    f = BoxFactory(center=(0, 0, 0), extents=(1, 1, 1), normal=(0, 0, 1), massFlowRate=20, rMin=0.01, rMax=0.02,
                   vMin=0, vMax=0, maxParticles=-1, label="f")
    factory_scene(f, 5)
    O.saveTmp("factory")
    O.run(10, True)
    later = [tuple(O.bodies[i].state.pos) for i in O.engines[-1].ids]
    O.loadTmp("factory")
    O.run(10, True)
    assert [tuple(O.bodies[i].state.pos) for i in O.engines[-1].ids] == later


def test_unset_or_unsupported_parameters_are_errors():
    with pytest.raises(ValueError, match=r"BoxFactory.rMin must be set"):
        factory_scene(BoxFactory(center=(0, 0, 0), extents=(1, 1, 1), normal=(0, 0, 1), massFlowRate=1, vMin=0, vMax=0))
    with pytest.raises(ValueError, match=r"CircularFactory.radius must be set"):
        factory_scene(CircularFactory(center=(0, 0, 0), normal=(0, 0, 1), massFlowRate=1, rMin=1, rMax=1, vMin=0, vMax=0))
    with pytest.raises(RuntimeError, match="SpheresFactory has no region"):
        factory_scene(SpheresFactory(massFlowRate=1))
    with pytest.raises(ValueError, match="PSDsizes should have a number of elements on 1 more"):
        factory_scene(BoxFactory(center=(0, 0, 0), extents=(1, 1, 1), normal=(0, 0, 1), massFlowRate=1, vMin=0, vMax=0,
                                 PSDsizes=[1, 2], PSDcum=[0.5, 1], exactDiam=False))


def test_domain_limiter_without_period_never_runs():
    O.reset()
    O.bodies.append(sphere((5, 0, 0), 0.1))
    limiter = DomainLimiter(lo=(-1, -1, -1), hi=(1, 1, 1))
    O.engines = [limiter]
    O.dt = 1
    O.run(3, True)
    assert len(O.bodies) == 1 and limiter.nDeleted == 0                     # as Yade: no period, no run
    limiter.iterPeriod, limiter.nDo = 1, 1
    O.run(3, True)
    assert O.bodies[0] is None and limiter.nDeleted == 1 and limiter.nDone == 1


def test_masks():
    f = BoxFactory(center=(0, 0, 0), extents=(1, 1, 1), normal=(0, 0, 1), massFlowRate=20, rMin=0.01, rMax=0.02,
                   vMin=0, vMax=0, mask=6, maxParticles=4)
    factory_scene(f)
    assert [O.bodies[i].mask for i in f.ids] == [6] * 4
    O.bodies[f.ids[0]].mask = 1
    limiter = DomainLimiter(lo=(5, 5, 5), hi=(6, 6, 6), iterPeriod=1, mask=2)
    O.engines = O.engines[:-1] + [limiter]
    O.step()
    assert limiter.nDeleted == 3 and O.bodies[f.ids[0]] is not None       # the body of mask 1 stays
