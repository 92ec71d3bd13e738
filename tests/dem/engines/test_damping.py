"""Damping per body (state.isDamped) and NewtonIntegrator(dampGravity=False) as Yade 2023.02a."""
from pathlib import Path

import numpy as np
import pytest

from talus import twin

TWINS = Path(__file__).parents[1] / "yade_twins" / "engines"  # the scripts Yade and Talus both run


@pytest.mark.skipif(not twin.yade_available(), reason="yade is not installed")
@pytest.mark.parametrize("dampGravity", [True, False])
def test_damping_per_body_as_yade(dampGravity):
    params = {"dampGravity": dampGravity}
    ours, theirs = (twin.run(TWINS / "damping_side_by_side.py", params, who) for who in ("talus", "yade"))
    assert theirs["isDamped"] == ours["isDamped"] == [True, False]
    track, expected = np.array(ours["track"]), np.array(theirs["track"])
    assert np.abs(expected[:, 0] - expected[:, 1]).max() > 1e-3         # the undamped one moves otherwise
    vy = expected[:, :, 4]
    falling = np.argmax(vy < 0, axis=0)
    assert all((vy[falling[k]:, k] > 0).any() for k in range(2))     # both fell and bounced off the floor
    np.testing.assert_allclose(track, expected, rtol=1e-9, atol=1e-12)
