"""Per-body stress (bodyStressTensors) and fabric tensor against closed forms: a sphere squeezed
between two walls, a sphere in a cubic lattice."""
import math

import numpy as np
import pytest

from talus.dem import *  # noqa: F401,F403


def stepped(scene, steps=1):
    scene.engines = [ForceResetter(), InsertionSortCollider(),
                     InteractionLoop([], [Ip2_FrictMat_FrictMat_FrictPhys()], [Law2_ScGeom_FrictPhys_CundallStrack()]),
                     NewtonIntegrator(damping=0)]
    scene.dt = 1e-7
    scene.run(steps)
    return scene


def test_sphere_squeezed_between_walls_has_the_contour_integral_stress():
    r, delta = 0.1, 1e-3
    S = Scene()
    S.materials.append(FrictMat(young=1e7))
    S.bodies.append([wall(delta / 2, axis=2), wall(2 * r - delta / 2, axis=2), sphere((0, 0, r), r)])
    stepped(S)
    contacts = S.contacts()
    assert len(contacts) == 2
    F = abs(contacts[0]["normalForce"][2])
    assert F > 0
    # two opposite forces F at arms r - delta/4 (each contact point is mid-overlap) along z
    expected = -2 * F * (r - delta / 4) / (4 / 3 * math.pi * r ** 3)
    s = bodyStressTensors(scene=S)
    assert s[2][2, 2] == pytest.approx(expected, rel=1e-12)
    assert np.max(np.abs(np.delete(s[2].ravel(), 8))) < 1e-12 * abs(expected)
    assert np.all(s[0] == 0) and np.all(s[1] == 0)                    # walls: no volume
    assert bodyStressTensors(revertSign=True, scene=S)[2][2, 2] == -s[2][2, 2]


def test_fabric_of_a_cubic_lattice_is_isotropic_and_of_a_chain_uniaxial():
    S = Scene()
    S.materials.append(FrictMat(young=1e7))
    r, a = 0.1, 0.199                     # spacing a little below the diameter: six contacts each
    S.bodies.append([sphere((i * a, j * a, k * a), r) for i in range(4) for j in range(4) for k in range(4)])
    stepped(S)
    assert len(S.contacts()) == 3 * 4 * 4 * 3
    assert np.allclose(fabricTensor(scene=S), np.eye(3) / 3, atol=1e-15)
    chain = Scene()
    chain.materials.append(FrictMat(young=1e7))
    chain.bodies.append([sphere((0, 0, k * a), r) for k in range(5)])
    stepped(chain)
    assert np.allclose(fabricTensor(scene=chain), np.diag([0, 0, 1]), atol=1e-15)


def test_kinetic_energy_in_a_deforming_cell_counts_the_fluctuations():
    """Free spheres in a cell deformed by velGrad (changed half-way): their velocities carry the
    cell's field and spin, utils.kineticEnergy only what they had of their own, which nothing
    changes (Yade 2023.02a gives the same bits on this scene: 6846.049802157553)."""
    from talus.dem import Matrix3, NewtonIntegrator, Scene, Vector3, sphere
    from talus.dem.analysis.measure import kineticEnergy
    S = Scene()
    S.periodic = True
    S.cell.setBox(2.5, 2.5, 3)
    S.bodies.append([sphere((1, 1, 1), .5), sphere((1, 2, 31), .5), sphere((2, 1, -4), .3)])
    S.bodies[1].state.vel = Vector3(0, 0, 5)
    S.bodies[2].state.vel = Vector3(1, 2, 0)
    S.bodies[2].state.angVel = Vector3(0, 3, 0)
    own = sum(0.5 * b.state.mass * b.state.vel.squaredNorm() + 0.5 * b.state.inertia[1] * b.state.angVel[1] ** 2
              for b in S.bodies)
    S.engines = [NewtonIntegrator()]
    S.cell.velGrad = Matrix3(0.1, 0, 0, 0, 0, 0, 0.2, 0, -1)
    S.dt = 1e-3
    for gradient in (None, Matrix3(0.3, 0, 0, 0, 0, 0, 0.2, 0, -2)):
        if gradient is not None:
            S.cell.velGrad = gradient
        S.run(2, True)
        assert S.bodies[1].state.vel[2] < -20         # the cell's field is in the velocities
        assert kineticEnergy(scene=S) == pytest.approx(own, rel=1e-12)
        assert S.energy["kinetic"] == pytest.approx(own, rel=1e-12)
