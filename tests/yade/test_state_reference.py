"""state.refPos and state.refOri as Yade 2023.02a's (set where a body is made, a clump at the
origin, never moved by a run, settable, kept by checkpoints); vel, angVel, inertia and refPos
handed as references into the body, pos as a copy."""
from pathlib import Path

import numpy as np
import pytest

from talus.dem import Scene, sphere
from talus.dem.files import io
from talus import twin

HERE = Path(__file__).parent


@pytest.mark.skipif(not twin.yade_available(), reason="yade is not installed")
def test_reference_as_yade():
    ours, theirs = (twin.run(HERE / "side_by_side" / "state_reference_side_by_side.py", {}, who) for who in ("talus", "yade"))
    assert theirs["after run"][0] == [1, 2, 3] and theirs["clump"][0] == [0, 0, 0]
    assert theirs["references"][0][0] == 5 and theirs["references"][4][2] != 70   # vel a reference, pos a copy
    assert ours.keys() == theirs.keys()
    for key in theirs:
        assert np.allclose(np.concatenate(ours[key]), np.concatenate(theirs[key]), rtol=1e-15, atol=1e-15), key


@pytest.mark.skipif(not io.available(), reason="checkpoints need h5py")
def test_reference_kept_by_a_checkpoint_file(tmp_path):
    S = Scene()
    S.bodies.append([sphere((0, 0, 0), 1), sphere((3, 0, 0), 1)])
    S.bodies[1].state.refPos = (5, 6, 7)
    io.save(S, tmp_path / "ck.h5")
    T = Scene()
    io.load(T, tmp_path / "ck.h5")
    assert list(T.bodies[1].state.refPos) == [5, 6, 7] and list(T.bodies[0].state.refPos) == [0, 0, 0]
    with pytest.raises(ValueError, match="body 0: refPos"):
        T.bodies[0].state.refPos = (1, 2)
