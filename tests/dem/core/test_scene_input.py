"""Bad input gets a clear error naming the item; nothing is half-added."""
import math

import pytest

from talus.dem import (FrictMat, ForceResetter, InsertionSortCollider, InteractionLoop,
                       Ip2_FrictMat_FrictMat_FrictPhys, Law2_ScGeom_FrictPhys_CundallStrack,
                       Law2_ScGeom_ViscElPhys_Basic, NewtonIntegrator, PyRunner, Scene, ViscElMat,
                       sphere, wall)


@pytest.mark.parametrize("radius", [0.0, -0.1, math.nan, math.inf])
def test_bad_radius_names_the_body(radius):
    S = Scene()
    S.bodies.append(sphere((0, 0, 0), 0.1))
    with pytest.raises(ValueError, match=r"sphere #1: radius must be positive"):
        S.bodies.append(sphere((1, 0, 0), radius))
    assert len(S.bodies) == 1


def test_nan_position_and_unknown_material():
    S = Scene()
    with pytest.raises(ValueError, match=r"sphere #0: centre is not finite"):
        S.bodies.append(sphere((0, math.nan, 0), 0.1))
    S.materials.append(FrictMat())
    with pytest.raises(ValueError, match="unknown material index 5"):
        S.bodies.append(sphere((0, 0, 0), 0.1, material=5))
    with pytest.raises(ValueError, match="no material labelled 'steel'"):
        S.bodies.append(sphere((0, 0, 0), 0.1, material="steel"))
    assert len(S.bodies) == 0


@pytest.mark.parametrize("params, message", [
    (dict(young=-1.0), "young must be finite and >= 0"),
    (dict(density=-1.0), "density must be finite and >= 0"),
    (dict(frictionAngle=2.0), "frictionAngle must be in"),
])
def test_bad_material_parameters(params, message):
    with pytest.raises(ValueError, match=f"material 'sand': {message}"):
        Scene().materials.append(FrictMat(label="sand", **params))


@pytest.mark.parametrize("params, message", [
    (dict(tc=1e-3, en=0.5), "tc must be positive and comes with en and et"),
    (dict(kn=1e5, cn=1.0), "kn must be positive and comes with cn, ks, cs"),
    (dict(tc=1e-3, en=0.5, et=0.5, kn=1e5, cn=0.0, ks=0.0, cs=0.0), "ViscElMat takes either tc"),
    (dict(tc=1e-3, en=1.5, et=0.5), "en must be in"),
    (dict(en=0.5, cn=1.0), "cn and cs come together"),
    (dict(en=0.5, mRtype=3), "mRtype must be 1 or 2"),
    (dict(tc=1e-3, en=0.5, et=0.5, lubrication=True), "lubrication needs the young, poisson, en form"),
])
def test_viscoelastic_material_forms(params, message):
    # Groups Yade would silently skip (falling through to its next form) are refused.
    with pytest.raises(ValueError, match=f"material 'v': {message}"):
        Scene().materials.append(ViscElMat(label="v", **params))


def test_unknown_parameter_and_body_id():
    with pytest.raises(TypeError, match="no parameter 'yong'"):
        FrictMat(yong=1e7)
    S = Scene()
    S.bodies.append(sphere((0, 0, 0), 0.1))
    with pytest.raises(IndexError, match="no body with id 7"):
        S.bodies[7]
    S.bodies.erase(0)
    assert S.bodies[0] is None and S.bodies[-1] is None    # erased, as in Yade


def test_a_law_without_its_physics_functor_is_refused():
    with pytest.raises(ValueError, match="needs Ip2_ViscElMat_ViscElMat_ViscElPhys"):
        InteractionLoop([], [Ip2_FrictMat_FrictMat_FrictPhys()], [Law2_ScGeom_ViscElPhys_Basic()])
    with pytest.raises(ValueError, match="at least one Law2"):
        InteractionLoop([], [Ip2_FrictMat_FrictMat_FrictPhys()], [])


def test_time_step_and_wall_parameters():
    S = Scene()
    for dt in (math.nan, math.inf, -math.inf):
        with pytest.raises(ValueError, match="O.dt must be zero or positive"):
            S.dt = dt
    with pytest.raises(RuntimeError, match="No TimeStepper"):   # Yade: hands dt to the stepper
        S.dt = -1.0
    S.dt = 0.0   # as in Yade: a step that moves nothing
    with pytest.raises(ValueError, match="axis must be 0, 1 or 2"):
        S.bodies.append(wall(0, axis=3))
    with pytest.raises(ValueError, match="unknown letters 'q'"):
        S.bodies.append(sphere((0, 0, 0), 0.1))
        S.bodies[0].state.blockedDOFs = "xq"


def test_an_error_in_a_pyrunner_stops_the_run_with_the_python_error():
    S = Scene()
    S.bodies.append(sphere((0, 0, 0), 0.1))

    def boom():
        raise RuntimeError(f"stop at iteration {S.iter}")
    S.engines = [ForceResetter(), InsertionSortCollider(),
                 InteractionLoop([], [Ip2_FrictMat_FrictMat_FrictPhys()], [Law2_ScGeom_FrictPhys_CundallStrack()]),
                 NewtonIntegrator(), PyRunner(boom, iterPeriod=5)]
    S.dt = 1e-3
    with pytest.raises(RuntimeError, match="stop at iteration 5"):
        S.run(100)
    assert S.iter == 5


def test_material_edits_after_append_reach_the_scene_and_are_checked():
    S = Scene()
    mat = FrictMat(young=1e7, label="soft")
    S.materials.append(mat)
    mat.young = 2e7                                   # applies to contacts created from now on
    assert S._cpp.material(0).young == 2e7
    with pytest.raises(ValueError, match="material 'soft': young must be finite and >= 0"):
        mat.young = -5.0
    assert mat.young == 2e7                           # the invalid value was not kept
    with pytest.raises(ValueError, match="already in a scene"):
        Scene().materials.append(mat)


def test_none_engines_and_laws_and_missing_walls_are_refused_by_the_core_too():
    """The raw bindings (which the couplings use) refuse what would crash the step."""
    from talus import _dem
    from talus.dem import TriaxialStressController
    S = Scene()
    S.bodies.append(sphere((0, 0, 0), 0.1))
    with pytest.raises(TypeError, match="Scene.engines: item 1 is None"):
        S._cpp.engines = [ForceResetter()._cpp, None]
    loop = _dem.InteractionLoop()
    with pytest.raises(TypeError, match="InteractionLoop.laws: item 0 is None"):
        loop.laws = [None]
    S.run(2)  # the scene was left as it was
    assert S.iter == 2
    # Six wall ids by default (0 ... 5) on a scene of one sphere: refused, not read past the end.
    triax = TriaxialStressController()
    with pytest.raises(ValueError, match="TriaxialStressController: .* = 0 must be a wall normal to axis 0"):
        triax._cpp.computeStressStrain(S._cpp)


def test_adding_bodies_warns_when_it_moves_arrays_still_held():
    """A view from positions() points at the old storage once an append moves the arrays:
    the append says so (no warning when no earlier view is alive, or the arrays had room)."""
    import warnings
    S = Scene()
    S.bodies.append(sphere((0, 0, 0), 0.1))
    held = S.positions()
    with pytest.warns(RuntimeWarning, match="adding bodies moves the per-body arrays"):
        for k in range(1, 64):
            S.bodies.append(sphere((k, 0, 0), 0.1))
    assert held.shape == (1, 3)
    del held
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        S.positions()[0]                  # a temporary view, gone at once
        for k in range(64, 200):
            S.bodies.append(sphere((k, 0, 0), 0.1))
        spare = S._cpp.bodySpareCapacity()
        kept = S.velocities()
        for k in range(spare):            # room enough: nothing moves
            S.bodies.append(sphere((200 + k, 0, 0), 0.1))
        assert kept.shape == (200, 3)
