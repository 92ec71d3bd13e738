"""Packing generators refuse, before allocating anything, a count of spheres beyond their stated
limit (SpherePack's maxSpheres, 1e8): a radius too small for the box, a mistyped count."""
import pytest

from talus import _dem
from talus.dem.packing import pack
from talus.dem.packing.densepack import randomDensePack
from talus.dem.packing.pack import SpherePack, inAlignedBox

BOX = inAlignedBox((0, 0, 0), (1, 1, 1))


def test_the_limit_is_stated():
    assert pack.MAX_SPHERES == _dem.SpherePack.maxSpheres == 100_000_000


@pytest.mark.parametrize("generator", [pack.regularHexa, pack.regularOrtho])
def test_regular_lattices_beyond_the_limit_are_refused(generator):
    # radius 1e-4 in a 1 m box: about 1e11 (ortho: 1.25e11) spheres
    with pytest.raises(ValueError, match=rf"{generator.__name__} would make \S+ spheres, more than the limit of 1e\+08"):
        generator(BOX, radius=1e-4, gap=0)
    assert len(generator(BOX, radius=0.1, gap=0)) > 50


def test_make_cloud_beyond_the_limit_is_refused():
    sp = SpherePack()
    with pytest.raises(ValueError, match=r"makeCloud: num = 1000000000 spheres is more than the limit of 100000000"):
        sp.makeCloud((0, 0, 0), (1, 1, 1), rMean=1e-3, num=10 ** 9)
    with pytest.raises(ValueError, match=r"makeCloud: the box holds up to \S+ spheres of rMean = 0.000010, more than "
                                         r"the limit"):
        sp.makeCloud((0, 0, 0), (1, 1, 1), rMean=1e-5)
    assert len(sp) == 0
    assert sp.makeCloud((0, 0, 0), (1, 1, 1), rMean=0.1, seed=1) > 10


def test_random_dense_pack_and_cell_repeat_beyond_the_limit_are_refused():
    with pytest.raises(ValueError, match="randomDensePack would make .* more than the limit"):
        randomDensePack(BOX, radius=1e-4, returnSpherePack=True)
    sp = SpherePack()
    sp.makeCloud((0, 0, 0), (1, 1, 1), rMean=0.1, periodic=True, seed=1)
    with pytest.raises(ValueError, match="SpherePack.cellRepeat would make .* more than the limit"):
        sp.cellRepeat((1000, 1000, 1000))
