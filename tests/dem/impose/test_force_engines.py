"""Yade's force engines, engine + engine and the helix engines move bodies as Yade 2023.02a does."""
from pathlib import Path

import numpy as np
import pytest

from talus import twin

TWINS = Path(__file__).parents[1] / "yade_twins" / "engines"  # the scripts Yade and Talus both run


@pytest.mark.skipif(not twin.yade_available(), reason="yade is not installed")
def test_force_and_kinematic_engines_match_yade():
    ours, theirs = (np.array(twin.run(TWINS / "engines_side_by_side.py", {}, who)) for who in ("talus", "yade"))
    assert ours.shape == theirs.shape
    moved = np.abs(theirs[-1] - theirs[0]).reshape(5, 3).max(axis=1)
    assert (moved > 5e-4).all()                            # every engine moved its body
    assert np.abs(ours - theirs).max() < 1e-12 * max(1.0, np.abs(theirs).max())
