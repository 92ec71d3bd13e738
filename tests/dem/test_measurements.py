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
