"""yade.bodiesHandling and getSpheresVolume/getSpheresMass as Yade 2023.02a's."""
from pathlib import Path

import numpy as np
import pytest

from talus import twin

HERE = Path(__file__).parent


def close(a, b):
    if isinstance(a, dict):
        return a.keys() == b.keys() and all(close(a[k], b[k]) for k in a)
    return np.allclose(a, b, rtol=1e-13, atol=1e-13)


@pytest.mark.skipif(not twin.yade_available(), reason="yade is not installed")
def test_bodies_handling_as_yade():
    ours, theirs = (twin.run(HERE / "side_by_side" / "bodies_handling_side_by_side.py", {}, who) for who in ("talus", "yade"))
    assert theirs["ids"]["number"] == 6 and theirs["facets"]["number"] == 12 and theirs["moved"] is True
    assert theirs["by mask"]["number"] == 6 and theirs["list and mask"]["number"] == 4   # copies included
    for key in theirs:
        assert close(ours[key], theirs[key]), key


def test_what_talus_refuses():
    from yade import bodiesHandling
    from talus.dem import O, sphere
    O.reset()
    ids = O.bodies.append([sphere((0, 0, 0), 1), sphere((3, 0, 0), 1, mask=2)])
    with pytest.raises(RuntimeWarning, match="length > 1"):      # Yade's exception
        bodiesHandling.spheresPackDimensions([])
    with pytest.raises(RuntimeWarning, match="Not enough bodies"):
        bodiesHandling.spheresPackDimensions(mask=2)
    with pytest.raises(AttributeError, match="radius of body 0 cannot be changed"):
        bodiesHandling.spheresModify(ids, scale=2)
    O.reset()
