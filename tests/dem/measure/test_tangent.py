"""Contact-stiffness tangent operator (getStressAndTangent): exact on a simple cubic lattice, and
predicting the stress change of a dense periodic packing under small affine strains."""
import json
from pathlib import Path

import numpy as np
import pytest

from talus.dem import (FrictMat, ForceResetter, InsertionSortCollider, InteractionLoop,
                       Ip2_FrictMat_FrictMat_FrictPhys, Law2_ScGeom_FrictPhys_CundallStrack, Matrix3,
                       NewtonIntegrator, Scene, getStress, getStressAndTangent, sphere)
from talus import twin

TWINS = Path(__file__).parents[1] / "yade_twins" / "periodic"  # the scripts Yade and Talus both run


def periodic(hsize, centres, radii):
    S = Scene()
    S.periodic = True
    S.cell.hSize = Matrix3(*np.asarray(hsize, dtype=float).ravel())
    S.materials.append(FrictMat(young=1e7, poisson=0.3, frictionAngle=1.5, density=2600))
    S.bodies.append([sphere(tuple(c), r) for c, r in zip(centres, radii)])
    for b in S.bodies:
        b.state.blockedDOFs = "xyzXYZ"          # particles follow the affine field exactly
    S.engines = [ForceResetter(), InsertionSortCollider(),
                 InteractionLoop([], [Ip2_FrictMat_FrictMat_FrictPhys()], [Law2_ScGeom_FrictPhys_CundallStrack()]),
                 NewtonIntegrator(damping=0)]
    S.dt = 1e-6
    S.step()
    return S


def test_simple_cubic_lattice_has_the_analytic_tangent():
    a, r = 0.02, 0.0101                         # spacing a, overlap 2r - a along x, y, z
    # 3 x 3 x 3 spheres: with fewer, a pair would touch through two images (one contact per
    # pair, as in Yade) or a sphere its own image
    n = 3
    centres = [(a * (i + 0.5), a * (j + 0.5), a * (k + 0.5)) for i in range(n) for j in range(n) for k in range(n)]
    S = periodic(np.diag([n * a] * 3), centres, [r] * n**3)
    contact = S.contacts()[0]
    assert len(S.contacts()) == 3 * n**3
    kn, ks = contact["kn"], contact["ks"]
    stress, C = getStressAndTangent(scene=S)
    alpha = 2 * r / a                           # the shear increment's ratcheting factor
    expected = np.diag([kn / a] * 3 + [alpha * ks / (2 * a)] * 3)
    np.testing.assert_allclose(C, expected, rtol=1e-12, atol=1e-12 * kn / a)
    np.testing.assert_allclose(stress, -kn * (2 * r - a) / a**2 * np.eye(3), rtol=1e-12)


def voigt(t):
    t = 0.5 * (t + t.T)
    return np.array([t[0, 0], t[1, 1], t[2, 2], t[1, 2], t[0, 2], t[0, 1]])


@pytest.mark.parametrize("strain", [[1e-7, 0, 0, 0, 0, 0], [0, 0, 0, 0, 0, 1e-7], [0, -2e-8, 0, 3e-8, 0, 0]],
                         ids=["axial", "shear-xy", "mixed"])
def test_tangent_predicts_the_stress_increment_of_a_packing(strain):
    data = json.loads((TWINS / "periodic_packing.json").read_text())
    S = periodic(data["hSize"], data["pos"], data["radius"])
    e = np.array(strain)
    E = np.array([[e[0], e[5] / 2, e[4] / 2], [e[5] / 2, e[1], e[3] / 2], [e[4] / 2, e[3] / 2, e[2]]])
    S.cell.velGrad = Matrix3(*(E / S.dt).ravel())
    S.step()                                    # forces of the reference state, positions strained once
    stress, C = getStressAndTangent(scene=S)
    rotation = force_rotation(S, E)
    S.step()                                    # forces after one strain increment
    measured = voigt(getStress(scene=S) - stress)
    # Besides C eps, the read-out changes by known geometric terms: the branch vectors and the
    # cell volume change (sigma eps^T - sigma tr(eps)), and the normal forces turn with their
    # normals. Each is of relative size |sigma| / C ~ 6 % in this dense packing; with them the
    # prediction must hold to O(eps).
    geometric = voigt(stress @ E.T - stress * np.trace(E)) + rotation
    scale = np.abs(C @ e).max()
    assert np.abs(measured - C @ e - geometric).max() < 1e-6 * scale
    assert np.abs(measured - C @ e).max() > 0.01 * scale    # the geometric terms are not negligible here


def force_rotation(S, E):
    """Stress change from normal forces turning with their normals, dn = (I - n n) E n, over a
    strain increment E (the shear forces are zero in this first-step state)."""
    radii, total = S.radii(), np.zeros((3, 3))
    for c in S.contacts():
        n = c["normal"]
        length = radii[c["id1"]] + radii[c["id2"]] - c["penetrationDepth"]
        fn = np.dot(c["normalForce"], n)
        total -= fn * length * np.outer((np.eye(3) - np.outer(n, n)) @ E @ n, n)
    return voigt(total / S.cell.volume)


@pytest.mark.skipif(not twin.yade_available(), reason="yade is not installed (./setup.sh installs it)")
def test_yade_form_equals_yades_get_stress_and_tangent():
    def run(program):
        result = twin.run(TWINS / "packing_tangent.py", {}, program, timeout=300)
        return {k: np.array(v) if isinstance(v, list) else v for k, v in result.items()}
    ours, yade = run("talus"), run("yade")
    assert ours["shearing"] > 100                      # the shear part of Yade's form is exercised
    assert np.abs(ours["tangent"] - yade["tangent"]).max() < 1e-9 * np.abs(yade["tangent"]).max()
    assert np.abs(ours["stress"] - yade["stress"]).max() < 1e-6 * np.abs(yade["stress"]).max()
    # The full form keeps the shear stiffness in every tangential direction: visibly stiffer.
    assert np.abs(ours["full"] - ours["tangent"]).max() > 0.02 * np.abs(ours["tangent"]).max()
