"""FlowEngine's boundary lists: a NaN pressure or a string of flags is refused when set, naming
the parameter and what it takes (a string would read as six True, a NaN give NaN pressures)."""
import math

import pytest

from talus.flow import FlowEngine


@pytest.mark.parametrize("name", ["bndCondValue", "wallPosition"])
@pytest.mark.parametrize("bad", [[0, 0, math.nan, 0, 0, 0], [math.inf] * 6])
def test_boundary_values_must_be_finite(name, bad):
    with pytest.raises(ValueError, match=rf"FlowEngine.{name} must be 6 finite numbers"):
        FlowEngine(**{name: bad})
    f = FlowEngine()
    with pytest.raises(ValueError, match=rf"FlowEngine.{name} must be 6 finite numbers"):
        setattr(f, name, bad)


@pytest.mark.parametrize("name", ["bndCondIsPressure", "boundaryUseMaxMin"])
@pytest.mark.parametrize("bad", ["abcdef", [0, 0, 2, 0, 0, 0], [0, 0, 0.5, 0, 0, 0], ["a"] * 6])
def test_boundary_flags_must_be_six_booleans(name, bad):
    with pytest.raises((TypeError, ValueError), match=rf"FlowEngine.{name} (must be a list of 6 booleans|needs a list of 6)"):
        FlowEngine(**{name: bad})


def test_good_boundary_lists_are_kept():
    f = FlowEngine(bndCondIsPressure=[0, 0, 1, True, 0, False], bndCondValue=[0, 0, 1e3, 0, 0, 0])
    assert f.bndCondIsPressure == [False, False, True, True, False, False]
    assert f.bndCondValue == [0, 0, 1e3, 0, 0, 0]
    with pytest.raises(ValueError, match="needs a list of 6 values"):
        f.bndCondValue = [1, 2, 3]
