"""makeCloud with maxCorner below minCorner along an axis, as Yade 2023.02a."""
from pathlib import Path

import numpy as np
import pytest

from talus import twin
from talus.dem.packing.pack import SpherePack

HERE = Path(__file__).parent


@pytest.mark.skipif(not twin.yade_available(), reason="yade is not installed")
def test_inverted_box_as_yade():
    ours, theirs = (twin.run(HERE / "side_by_side" / "inverted_cloud_side_by_side.py", {}, who) for who in ("talus", "yade"))
    assert ours["count"] == theirs["count"] > 100
    np.testing.assert_allclose(ours["spheres"], theirs["spheres"], rtol=0, atol=1e-12)
    y = np.array(theirs["spheres"])[:, 1]
    assert y.min() < -13 and y.max() > -9      # a radius beyond the corners, as Yade


def test_what_an_inverted_box_cannot_be():
    with pytest.raises(ValueError, match="periodic cloud needs maxCorner"):
        SpherePack().makeCloud((0, 0, 0), (1, -1, 1), rMean=0.1, periodic=True)
    with pytest.raises(ValueError, match="num without rMean"):
        SpherePack().makeCloud((0, 0, 0), (1, -1, 1), num=10)
