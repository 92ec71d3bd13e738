"""A BoundDispatcher by itself in O.engines, as Yade 2023.02a accepts it."""
from pathlib import Path

import numpy as np
import pytest

from talus.dem import (BoundDispatcher, Bo1_Sphere_Aabb, ForceResetter, IGeomDispatcher, IPhysDispatcher,
                       Ig2_Sphere_Sphere_ScGeom, Ip2_FrictMat_FrictMat_FrictPhys, Scene)
from talus import twin

HERE = Path(__file__).parent


@pytest.mark.skipif(not twin.yade_available(), reason="yade is not installed")
def test_bound_dispatcher_alone_as_yade():
    ours, theirs = (twin.run(HERE / "side_by_side" / "bound_dispatcher_side_by_side.py", {}, who) for who in ("talus", "yade"))
    assert theirs["alone"] == ours["alone"] == ["BoundDispatcher"] and ours["iter"] == theirs["iter"] == 2003
    assert np.allclose(ours["positions"], theirs["positions"], rtol=0, atol=1e-10)
    assert min(p[2] for p in theirs["positions"]) < 0.13       # they fell on the floor


def test_other_dispatchers_still_come_in_a_row():
    S = Scene()
    S.engines = [ForceResetter(), BoundDispatcher([Bo1_Sphere_Aabb()], label="bounds")]
    assert S.engines[1].functors and S.engines[1].label == "bounds"
    with pytest.raises(TypeError, match="IGeomDispatcher must come as"):
        S.engines = [IGeomDispatcher([Ig2_Sphere_Sphere_ScGeom()]), BoundDispatcher(),
                     IPhysDispatcher([Ip2_FrictMat_FrictMat_FrictPhys()])]
