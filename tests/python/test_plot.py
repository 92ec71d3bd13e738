"""plot.addData time series: NaN padding as Yade, text/CSV/HDF5 round trips, PNG plots."""
import math

import numpy as np
import pytest

from talus import plot


@pytest.fixture(autouse=True)
def clean():
    plot.reset()
    yield
    plot.reset()


def test_columns_stay_aligned_with_nan_padding():
    plot.addData(i=0, a=1.0)
    plot.addData({"i": 1, "b": 5.0})          # 'a' missing here, 'b' new
    plot.addData(i=2, a=3.0, b=6.0)
    assert plot.data["i"] == [0, 1, 2]
    assert plot.data["a"][0] == 1.0 and math.isnan(plot.data["a"][1]) and plot.data["a"][2] == 3.0
    assert math.isnan(plot.data["b"][0]) and plot.data["b"][1:] == [5.0, 6.0]


def test_non_numbers_are_refused_by_name():
    with pytest.raises(TypeError, match="'label'"):
        plot.addData(i=0, label="x")


@pytest.mark.parametrize("name", ["d.txt", "d.csv", "d.txt.bz2", "d.csv.gz"])
def test_text_round_trip(tmp_path, name):
    for k in range(5):
        plot.addData(i=k, t=0.1 * k, s=-1e5 / 3 * k)
    saved = {k: list(v) for k, v in plot.data.items()}
    plot.saveDataTxt(tmp_path / name)
    plot.resetData()
    assert plot.loadDataTxt(tmp_path / name) == saved       # repr() keeps every bit
    assert [p.name for p in tmp_path.iterdir()] == [name]     # no temporary left


def test_hdf5_round_trip(tmp_path):
    h5py = pytest.importorskip("h5py")
    plot.addData(i=1, x=2.5)
    plot.saveDataHdf5(tmp_path / "d.h5")
    with h5py.File(tmp_path / "d.h5") as f:
        assert np.array_equal(f["x"][:], [2.5]) and np.array_equal(f["i"][:], [1.0])


def test_plot_with_two_axes_styles_and_callables(tmp_path):
    for k in range(20):
        plot.addData(i=k, unbalanced=1 / (k + 1), kinetic=k * k, sz=-k)
    plot.plots = {"i": (("unbalanced", "go"), None, lambda: ["kinetic"]), "i ": ("sz",)}
    figure = plot.plot(noShow=True)
    assert len(figure.axes) == 3              # two subplots, the first with a right-hand axis
    plot.savePlot(tmp_path / "p.png")
    assert (tmp_path / "p.png").read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"


def test_unknown_names_are_reported():
    plot.addData(i=0)
    plot.plots = {"i": ("nope",)}
    with pytest.raises(KeyError, match="'nope'.*recorded: i"):
        plot.plot(noShow=True)
    with pytest.raises(KeyError, match="'zz'"):
        plot.saveDataTxt("/tmp/never.txt", vars=["zz"])


def test_malformed_file_names_the_line(tmp_path):
    (tmp_path / "bad.txt").write_text("# a b\n1 2\n3\n")
    with pytest.raises(ValueError, match="bad.txt, line 3"):
        plot.loadDataTxt(tmp_path / "bad.txt")
