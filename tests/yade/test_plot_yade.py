"""yade.plot's addData, addAutoData and saveDataTxt give what Yade 2023.02a's give."""
from pathlib import Path

import pytest

from talus import twin

HERE = Path(__file__).parent


@pytest.mark.skipif(not twin.yade_available(), reason="yade is not installed")
def test_plot_data_as_yade():
    ours, theirs = (twin.run(HERE / "side_by_side" / "plot_side_by_side.py", {}, who) for who in ("talus", "yade"))
    assert theirs["added"]["a"] == ["1", "nan", "3"]          # ints stay ints
    assert "c_z" in theirs["added"] and "d_yx" in theirs["added"]
    assert theirs["auto"]["n"] == ["0", "1"]
    assert ours == theirs


def test_plot_rejects_what_is_not_a_number():
    from talus import plot
    plot.resetData()
    with pytest.raises(TypeError, match="'s' is not a number"):
        plot.addData(s="text")
    with pytest.raises(TypeError, match="'v' is not a number"):
        plot.addData(v=[1, 2, 3])
    assert plot.data == {}
