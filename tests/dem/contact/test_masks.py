"""Body group masks (Yade's groupMask, b.mask) against Yade 2023.02a (masks_side_by_side.py):
the collider's pairs, avoidSelfInteractionMask, a contact lasting past a mask change, the masks of
GravityEngine and NewtonIntegrator; and the masks kept by checkpoints."""
from pathlib import Path

import pytest

from talus.dem import Scene, box, facet, sphere, wall
from talus import twin
from talus.dem.files import io

TWINS = Path(__file__).parents[1] / "yade_twins" / "engines"  # the scripts Yade and Talus both run
SCRIPT = TWINS / "masks_side_by_side.py"
needs_yade = pytest.mark.skipif(not twin.yade_available(), reason="yade is not installed")


@needs_yade
@pytest.mark.parametrize("case", ["fall", "groups", "engines"])
def test_masks_match_yade(case):
    ours, theirs = (twin.run(SCRIPT, {"case": case}, who) for who in ("talus", "yade"))
    assert ours == theirs                      # bit for bit: masks only choose what is computed
    if case == "fall":
        z = [row[:3] for row in theirs]
        assert z[-1][1] < -1 < 0.14 < z[-1][0] == z[-1][2]   # mask 2 fell through the floor, 1 and 3 rest
        assert theirs[-1][3] == 2 and theirs[-1][-1] == 2    # the first changed its mask, its contact lasts
    if case == "groups":
        assert len({str(row[2]) for row in theirs}) == 4      # each avoidSelfInteractionMask its pairs


def test_makers_and_bodies_take_masks():
    assert [s.mask for s in (sphere((0, 0, 0), 1, mask=5), box((0, 0, 0), (1, 1, 1), mask=0),
                             facet([(0, 0, 0), (1, 0, 0), (0, 1, 0)], mask=4), wall(0, axis=2, mask=-1))] == [5, 0, 4, -1]
    S = Scene()
    i = S.bodies.append(sphere((0, 0, 0), 1))
    assert S.bodies[i].mask == S.bodies[i].groupMask == 1
    S.bodies[i].groupMask = 6
    assert S.bodies[i].mask == 6
    with pytest.raises(OverflowError, match="body 0"):
        S.bodies[i].mask = 2**40
    with pytest.raises(TypeError, match="body 0"):
        S.bodies[i].mask = 1.5


def test_checkpoints_keep_masks(tmp_path):
    S = Scene()
    S.bodies.append([sphere((0, 0, 0), 1, mask=3), sphere((3, 0, 0), 1, mask=-8)])
    io.save(S, tmp_path / "m.h5")
    T = Scene()
    io.load(T, tmp_path / "m.h5")
    assert [b.mask for b in T.bodies] == [3, -8]
