"""dict() of materials, states and shapes as Yade 2023.02a's Serializable.dict()."""
from pathlib import Path

import pytest

from talus import twin

HERE = Path(__file__).parent


@pytest.mark.skipif(not twin.yade_available(), reason="yade is not installed")
def test_dict_as_yade():
    ours, theirs = (twin.run(HERE / "side_by_side" / "serializable_dict_side_by_side.py", {}, who) for who in ("talus", "yade"))
    assert theirs["FrictMat"]["young"] == 1e9 and theirs["appended"]["id"] == 0
    assert ours["clump material"] == theirs["clump material"] == [True, 0]
    for key in ("FrictMat", "ViscElMat", "CohFrictMat", "ElastMat", "appended", "shape 0", "shape 1", "shape 2",
                "shape 3"):
        assert list(ours[key].items()) == list(theirs[key].items()), key     # the same order too
    # Talus's state has no isDamped or densityScaling yet; blockedDOFs is its letters, Yade's dict a bit mask.
    state = {k: v for k, v in theirs["state"].items() if k not in ("isDamped", "densityScaling", "blockedDOFs")}
    assert set(theirs["state"]) - set(ours["state"]) <= {"isDamped", "densityScaling"}
    assert ours["state"]["blockedDOFs"] == "" and theirs["state"]["blockedDOFs"] == 0
    assert {k: ours["state"][k] for k in state} == state
