"""Friction on facets as Yade's: spheres sliding and rolling in a facet box follow Yade's
trajectories (Yade takes the shear lever arms of facet contacts to the contact point)."""
from pathlib import Path

import numpy as np
import pytest

from talus import twin

TWINS = Path(__file__).parents[1] / "yade_twins" / "laws"  # the scripts Yade and Talus both run


@pytest.mark.skipif(not twin.yade_available(), reason="yade is not installed")
def test_sliding_and_rolling_in_a_facet_box_match_yade():
    ours, theirs = (np.array(twin.run(TWINS / "facet_friction_side_by_side.py", {}, who)) for who in ("talus", "yade"))
    assert ours.shape == theirs.shape
    moved = np.abs(theirs[-1] - theirs[0]).max()
    assert moved > 0.05                                # they did slide and roll
    assert np.abs(ours - theirs).max() < 1e-8          # 30000 steps with impacts and friction
