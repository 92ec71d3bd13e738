"""Hertz-Mindlin restitution per pair of materials (MatchMakers for en, es), as Yade 2023.02a."""
from pathlib import Path

import numpy as np
import pytest

from talus.dem import (FrictMat, ForceResetter, InsertionSortCollider, InteractionLoop,
                       Ip2_FrictMat_FrictMat_MindlinPhys, Law2_ScGeom_MindlinPhys_Mindlin, MatchMaker,
                       NewtonIntegrator, Scene, sphere)
from talus import twin

TWINS = Path(__file__).parents[1] / "yade_twins" / "laws"  # the scripts Yade and Talus both run


@pytest.mark.skipif(not twin.yade_available(), reason="yade is not installed")
def test_restitution_per_material_pair_matches_yade():
    ours, theirs = (np.array(twin.run(TWINS / "mindlin_matchmaker_side_by_side.py", {}, who)) for who in ("talus", "yade"))
    assert ours.shape == theirs.shape
    assert np.abs(theirs[-1] - theirs[0]).max() > 1      # the collisions changed the velocities
    assert np.abs(ours - theirs).max() < 1e-12 * np.abs(theirs).max()


def two_spheres(physics):
    S = Scene()
    a = S.materials.append(FrictMat(young=1e9, poisson=0.3, density=3000, label="a"))
    b = S.materials.append(FrictMat(young=1e9, poisson=0.3, density=3000, label="b"))
    S.bodies.append([sphere((0, 0, 0), 0.01, material=a), sphere((0, 0, 0.0199), 0.01, material=b)])
    S.engines = [ForceResetter(), InsertionSortCollider(),
                 InteractionLoop([], [physics(a, b)], [Law2_ScGeom_MindlinPhys_Mindlin()]), NewtonIntegrator(damping=0)]
    S.dt = 1e-7
    return S


def test_a_pair_without_a_value_is_an_error_naming_it():
    # Yade's functor passes no material values: algo 'avg' cannot average, so an unlisted pair fails.
    S = two_spheres(lambda a, b: Ip2_FrictMat_FrictMat_MindlinPhys(en=MatchMaker(matches=((a, a, 0.5),))))
    with pytest.raises(RuntimeError, match=r"no value for materials 'a' and 'b' \(bodies 0 and 1\)"):
        S.step()


def test_fallback_value_and_conflicts():
    S = two_spheres(lambda a, b: Ip2_FrictMat_FrictMat_MindlinPhys(en=MatchMaker(algo="val", val=0.5, matches=((a, a, 1),))))
    S.step()
    assert S.contacts()[0]["cn"] > 0                            # the pair (a, b) took val
    with pytest.raises(ValueError, match=r"only one of en, betan"):
        two_spheres(lambda a, b: Ip2_FrictMat_FrictMat_MindlinPhys(en=MatchMaker(algo="val", val=0.5), betan=0.1))
    with pytest.raises(ValueError, match=r"en must be in \(0, 1\], got 1.5"):
        two_spheres(lambda a, b: Ip2_FrictMat_FrictMat_MindlinPhys(en=MatchMaker(matches=((a, b, 1.5),))))


def test_matchmakers_are_kept_by_checkpoints(tmp_path):
    from talus.dem import O
    O.reset()
    a = O.materials.append(FrictMat(young=1e9, poisson=0.3, density=3000))
    O.bodies.append([sphere((0, 0, 0), 0.01, material=a), sphere((0, 0, 0.0199), 0.01, material=a)])
    physics = Ip2_FrictMat_FrictMat_MindlinPhys(en=MatchMaker(matches=((a, a, 0.3),)))
    O.engines = [ForceResetter(), InsertionSortCollider(), InteractionLoop([], [physics], [Law2_ScGeom_MindlinPhys_Mindlin()]),
                 NewtonIntegrator(damping=0)]
    O.dt = 1e-7
    O.save(str(tmp_path / "s.h5"))
    O.load(str(tmp_path / "s.h5"))
    en = O.engines[2].physFunctors[0].en
    assert isinstance(en, MatchMaker) and en(a, a) == 0.3
