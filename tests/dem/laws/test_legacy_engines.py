"""Yade's older spellings of the interaction loop (talus.dem.step.legacy): ElasticContactLaw after
IGeomDispatcher and IPhysDispatcher, and the deprecated dispatcher names."""
from pathlib import Path

import numpy as np
import pytest

from talus.dem import *  # noqa: F401,F403
from talus import twin

TWINS = Path(__file__).parents[1] / "yade_twins" / "laws"  # the scripts Yade and Talus both run


@pytest.mark.skipif(not twin.yade_available(), reason="yade is not installed (./setup.sh installs it)")
def test_elastic_contact_law_matches_yades_interaction_loop():
    # Yade's exact-rot.py: Talus runs the old engine list, Yade the InteractionLoop it stands
    # for (Yade 2023.02a aborts on the old list, in exact-rot.py, exact-rot-facet.py, shear.py).
    path = TWINS / "elastic_contact_law_side_by_side.py"
    ours, theirs = twin.run(path, {"oldStyle": True}, "talus"), twin.run(path, {}, "yade")
    assert np.linalg.norm(theirs["fs"]) > 100          # the turning spheres did load the contact in shear
    for key in ("bodies", "fn", "fs"):
        a, b = np.array(ours[key]), np.array(theirs[key])
        assert np.max(np.abs(a - b)) <= 1e-12 * np.max(np.abs(b)), key


def test_old_engine_list_becomes_one_interaction_loop():
    law = ElasticContactLaw(label="law")
    rotation = RotationEngine(ids=[1], rotationAxis=(1, 0, 0), angularVelocity=.01)
    scene = Scene()
    scene.engines = [ForceResetter(), InsertionSortCollider([Bo1_Sphere_Aabb()]),
                     IGeomDispatcher([Ig2_Sphere_Sphere_ScGeom()]), IPhysDispatcher([Ip2_FrictMat_FrictMat_FrictPhys()]),
                     rotation, law, NewtonIntegrator()]
    names = [type(e).__name__ for e in scene.engines]
    assert names == ["ForceResetter", "InsertionSortCollider", "InteractionLoop", "RotationEngine", "NewtonIntegrator"]
    loop = scene.engines[2]
    assert loop.label == "law" and [type(f).__name__ for f in loop.lawFunctors] == ["Law2_ScGeom_FrictPhys_CundallStrack"]
    with pytest.raises(ValueError, match="neverErase"):
        ElasticContactLaw(neverErase=True)
    with pytest.raises(TypeError, match="must come as IGeomDispatcher"):
        scene.engines = [IGeomDispatcher([Ig2_Sphere_Sphere_ScGeom()]), law]


def test_deprecated_names_warn_and_make_the_new_classes():
    with pytest.warns(DeprecationWarning, match="renamed to .* `IGeomDispatcher'"):
        assert type(InteractionGeometryDispatcher([Ig2_Sphere_Sphere_ScGeom()])) is IGeomDispatcher
    with pytest.warns(DeprecationWarning, match="IPhysDispatcher"):
        assert type(InteractionPhysicsDispatcher()) is IPhysDispatcher
