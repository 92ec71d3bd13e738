"""coupling: addForceChange (talus._coupling.add_force_change), the DEM side's one pass that
adds an exchange's force change to the bodies' persistent and step forces: the same sums as
NumPy's, for coupled ids that are not one run, and refusals that leave the arrays untouched
(an id that is no body, arrays of another size, per-body arrays that would be converted
copies)."""
import numpy as np
import pytest

from foam_case import BUILD

pytestmark = pytest.mark.skipif(not (BUILD / "python" / "talus" / "coupling").exists(),
                                reason="coupling component off (see the configure summary)")


def module():
    from talus.coupling.foam import _module
    return _module()


def test_same_sums_as_numpy_for_scattered_ids():
    rng = np.random.default_rng(3)
    ids = np.array([7, 2, 5, 0], dtype=np.int64)
    forces, applied = rng.normal(size=(4, 3)), rng.normal(size=(4, 3))
    persistent, step = rng.normal(size=(9, 3)), rng.normal(size=(9, 3))
    expected_persistent, expected_step = persistent.copy(), step.copy()
    expected_persistent[ids] += forces - applied
    expected_step[ids] += forces - applied
    module().add_force_change(forces, applied, ids, persistent, step)
    assert np.array_equal(persistent, expected_persistent) and np.array_equal(step, expected_step)


def test_refusals_leave_the_arrays_untouched():
    m = module()
    forces, applied = np.ones((2, 3)), np.zeros((2, 3))
    persistent, step = np.zeros((3, 3)), np.zeros((3, 3))
    with pytest.raises(ValueError, match="not a body"):
        m.add_force_change(forces, applied, np.array([0, 3], dtype=np.int64), persistent, step)
    with pytest.raises(ValueError, match="differ in size"):
        m.add_force_change(forces, applied, np.array([0], dtype=np.int64), persistent, step)
    with pytest.raises(TypeError):  # float32 per-body arrays: a converted copy would be changed
        m.add_force_change(forces, applied, np.array([0, 1], dtype=np.int64), persistent.astype(np.float32), step)
    assert not persistent.any() and not step.any()
