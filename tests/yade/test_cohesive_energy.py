"""Elastic energies of the cohesive-frictional law and kinSplit's O.energy keys as Yade 2023.02a."""
from pathlib import Path

import numpy as np
import pytest

from talus.dem import (CohFrictMat, ForceResetter, InsertionSortCollider, InteractionLoop,
                       Ig2_Sphere_Sphere_ScGeom6D, Ip2_CohFrictMat_CohFrictMat_CohFrictPhys,
                       Law2_ScGeom6D_CohFrictPhys_CohesionMoment, NewtonIntegrator, Scene, sphere)
from talus import twin

HERE = Path(__file__).parent


@pytest.mark.skipif(not twin.yade_available(), reason="yade is not installed")
def test_elastic_energies_as_yade():
    ours, theirs = (twin.run(HERE / "side_by_side" / "cohesive_energy_side_by_side.py", {}, who) for who in ("talus", "yade"))
    assert theirs["contacts"] == ours["contacts"] == 2
    assert theirs["keys"] == ours["keys"] == ["kinRot", "kinTrans"]
    assert min(theirs["energies"]) > 0            # every spring is loaded
    np.testing.assert_allclose(ours["energies"], theirs["energies"], rtol=1e-9)
    np.testing.assert_allclose(ours["angVel"], theirs["angVel"], rtol=1e-9, atol=1e-12)


def test_kinetic_split_adds_up():
    S = Scene()
    S.materials.append(CohFrictMat(density=2000))
    S.bodies.append([sphere((0, 0, 0), 1), sphere((0, 0, 2.5), 1)])
    S.bodies[1].state.vel = (0, 1, -2)
    S.bodies[1].state.angVel[2] = 4
    newton = NewtonIntegrator(damping=0)
    S.engines = [ForceResetter(), InsertionSortCollider(),
                 InteractionLoop([Ig2_Sphere_Sphere_ScGeom6D()], [Ip2_CohFrictMat_CohFrictMat_CohFrictPhys()],
                                 [Law2_ScGeom6D_CohFrictPhys_CohesionMoment()]), newton]
    S.trackEnergy = True
    S.dt = 1e-4
    S.run(10)
    kinetic = S.energy["kinetic"]
    newton.kinSplit = True
    mass, inertia = S.bodies[1].state.mass, S.bodies[1].state.inertia[2]
    assert S.energy["kinTrans"] == pytest.approx(0.5 * mass * 5, rel=1e-12)
    assert S.energy["kinRot"] == pytest.approx(0.5 * inertia * 16, rel=1e-12)
    assert S.energy["kinTrans"] + S.energy["kinRot"] == pytest.approx(kinetic, rel=1e-14)
    assert "kinetic" not in S.energy.keys()
    with pytest.raises(KeyError, match="kinTrans, kinRot"):
        S.energy["kinetic"]
