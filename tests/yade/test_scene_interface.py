"""The scene interface Yade scripts use: O.interactions, O.forces, bodies set up before they are
appended, shape colours, engine lists in Yade's older spellings, the periodic cell's refSize."""
import numpy as np
import pytest

from talus.dem import (FrictMat, ForceResetter, InsertionSortCollider, InteractionLoop, NewtonIntegrator, PyRunner,
                       Scene, Vector3, sphere, wall, Bo1_Sphere_Aabb, Ig2_Sphere_Sphere_ScGeom, Ig2_Wall_Sphere_ScGeom,
                       Ip2_FrictMat_FrictMat_FrictPhys, Law2_ScGeom_FrictPhys_CundallStrack,
                       Ip2_FrictMat_FrictMat_MindlinPhys, Law2_ScGeom_MindlinPhys_Mindlin, IGeomDispatcher,
                       IPhysDispatcher, LawDispatcher)


def two_spheres(law="linear"):
    S = Scene()
    S.bodies.append([sphere((0, 0, 0.099), 0.1), sphere((0, 0, -0.099), 0.1, fixed=True)])
    phys, law2 = ((Ip2_FrictMat_FrictMat_FrictPhys(), Law2_ScGeom_FrictPhys_CundallStrack()) if law == "linear"
                  else (Ip2_FrictMat_FrictMat_MindlinPhys(), Law2_ScGeom_MindlinPhys_Mindlin()))
    S.engines = [ForceResetter(), InsertionSortCollider([Bo1_Sphere_Aabb()]),
                 InteractionLoop([Ig2_Sphere_Sphere_ScGeom()], [phys], [law2]), NewtonIntegrator(gravity=(0, 0, -9.81))]
    S.dt = 1e-5
    return S


def test_interactions_by_pair_iteration_and_erase():
    S = two_spheres()
    S.run(1)
    assert len(S.interactions) == 1 and S.interactions.countReal() == 1
    i = S.interactions[1, 0]                      # either order, as in Yade
    assert (i.id1, i.id2) == (0, 1) and i.isReal
    assert i.geom.penetrationDepth == pytest.approx(0.002)
    assert isinstance(i.geom.normal, Vector3) and i.geom.normal.norm() == pytest.approx(1)
    # Force on body 2 (the lower one) pushes it down: kn times the overlap.
    assert i.phys.normalForce[2] == pytest.approx(-i.phys.kn * 0.002)
    assert [(j.id1, j.id2) for j in S.interactions] == [(0, 1)] and len(S.interactions.withBody(1)) == 1
    with pytest.raises(IndexError, match="bodies 0 and 5"):
        S.interactions[0, 5]
    with pytest.raises(AttributeError, match="read-only"):
        i.phys.kn = 3
    assert S.interactions.erase(0, 1) and len(S.interactions) == 0 and not S.interactions.erase(0, 1)


def test_erase_keeps_contact_state_aligned_with_a_law_that_has_state():
    """Erasing a body compacts the per-contact state of Hertz-Mindlin with the contact list:
    every remaining contact keeps its own stiffness (it used to read its neighbour's)."""
    S = Scene()
    S.materials.append(FrictMat(young=1e7, density=2000))
    S.bodies.append([sphere((0.19 * k, 0, 0), 0.1) for k in range(6)])
    S.engines = [ForceResetter(), InsertionSortCollider([Bo1_Sphere_Aabb()]),
                 InteractionLoop([Ig2_Sphere_Sphere_ScGeom()], [Ip2_FrictMat_FrictMat_MindlinPhys()],
                                 [Law2_ScGeom_MindlinPhys_Mindlin()]), NewtonIntegrator()]
    S.dt = 1e-6
    S.run(2)
    before = {(i.id1, i.id2): i.phys.kn for i in S.interactions}
    S.bodies.erase(1)
    S.run(1)
    after = {(i.id1, i.id2): i.phys.kn for i in S.interactions}
    assert set(after) == set(before) - {(0, 1), (1, 2)}
    for pair, kn in after.items():
        assert kn == pytest.approx(before[pair], rel=1e-3) and kn > 0


def test_forces_per_body_and_the_bulk_array():
    S = two_spheres()
    S.run(1)
    f = S.forces.f(0)
    assert isinstance(f, Vector3) and f[2] > 0 and np.array_equal(S.forces()[0], f)
    S.forces.setPermF(0, (1, 2, 3))
    assert S.forces.permF(0) == pytest.approx([1, 2, 3])
    S.run(1)
    assert S.forces.f(0)[0] == pytest.approx(1)
    with pytest.raises(ValueError, match="3 finite"):
        S.forces.addF(0, (1, 2))


def test_a_body_set_up_before_it_is_appended():
    S = Scene()
    b = sphere((0, 0, 1), 0.1, color=(1, 0, 0))
    b.state.vel = (1, 0, 0)
    b.state.mass = 5.0
    b.shape.color = (0, 1, 0)
    assert b.id == -1 and b.state.vel[0] == 1
    with pytest.raises(AttributeError, match="not yet appended|known once"):
        b.state.inertia
    S.bodies.append(b)
    assert b.id == 0 and b.state.mass == 5.0 and b.state.vel == pytest.approx([1, 0, 0])
    assert b.shape.color == pytest.approx([0, 1, 0]) and S.bodies[0].shape.color == pytest.approx([0, 1, 0])
    S.bodies[0].shape.color = (0, 0, 1)
    assert b.shape.color == pytest.approx([0, 0, 1]) and not b.isClump
    with pytest.raises(ValueError, match="already body 0"):
        S.bodies.append(b)


def test_spheres_given_outside_a_periodic_cell_stay_there():
    S = Scene()
    S.periodic = True
    S.cell.setBox(1, 1, 1)
    i = S.bodies.append(sphere((-0.25, 2.5, 0.5), 0.05))
    assert S.bodies[i].state.pos == pytest.approx([-0.25, 2.5, 0.5])   # as in Yade: never wrapped
    assert S.cell.refSize == pytest.approx([1, 1, 1])
    S.cell.refSize = (2, 2, 2)
    assert S.cell.hSize == pytest.approx(2 * np.eye(3))


def test_engine_lists_in_yades_older_spellings():
    S = two_spheres()
    S.engines = [ForceResetter(), InsertionSortCollider([Bo1_Sphere_Aabb()], nBins=5, allowBiggerThanPeriod=True),
                 IGeomDispatcher([Ig2_Sphere_Sphere_ScGeom()]), IPhysDispatcher([Ip2_FrictMat_FrictMat_FrictPhys()]),
                 LawDispatcher([Law2_ScGeom_FrictPhys_CundallStrack()]), NewtonIntegrator(exactAsphericalRot=True)]
    assert [type(e).__name__ for e in S.engines] == ["ForceResetter", "InsertionSortCollider", "InteractionLoop",
                                                     "NewtonIntegrator"]
    assert S.typedEngine("InteractionLoop").lawDispatcher.functors[0].__class__.__name__ == \
        "Law2_ScGeom_FrictPhys_CundallStrack"
    S.run(1)
    assert S.interactions.countReal() == 1
    with pytest.raises(TypeError, match="no parameter"):
        InsertionSortCollider(noSuchSetting=1)
    with pytest.raises(ValueError, match="exactAsphericalRot=False"):
        NewtonIntegrator(exactAsphericalRot=False)


def test_pyrunner_commands_and_labels_see_the_script_under_talus_run(talus_cmd, tmp_path):
    script = tmp_path / "labels.py"
    script.write_text(
        "calls = []\n"
        "def record():\n"
        "    calls.append(O.iter)\n"
        "O.bodies.append(sphere((0, 0, 0), 0.1))\n"
        "O.engines = [ForceResetter(), NewtonIntegrator(label='newton'), PyRunner(command='record()', iterPeriod=5)]\n"
        "O.dt = 1e-4\n"
        "O.run(10, True)\n"
        "print('calls', calls, 'label', newton is O.engines[1])\n"
        "O.materials.append([FrictMat(), FrictMat()])\n"
        "O.run()\n")
    done = talus_cmd("run", script)
    assert "calls [5] label True" in done.stdout        # iterations 0-9: the runner sees 5
    assert "open-ended" in done.stderr            # the pending O.run() is reported, as yade -x drops it
