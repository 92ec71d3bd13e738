"""Periodic cells: contacts across the boundary, homogeneous deformation of the cell and of the
particles (checked against Yade step by step), stress equal to Yade's on a sheared cell."""
from pathlib import Path

import numpy as np
import pytest

from talus.dem import (FrictMat, ForceResetter, InsertionSortCollider, InteractionLoop,
                       Ip2_FrictMat_FrictMat_FrictPhys, Ip2_FrictMat_FrictMat_MindlinPhys,
                       Ip2_ViscElMat_ViscElMat_ViscElPhys, Law2_ScGeom_FrictPhys_CundallStrack,
                       Law2_ScGeom_MindlinPhys_Mindlin, Law2_ScGeom_ViscElPhys_Basic, Matrix3, NewtonIntegrator,
                       Scene, ViscElMat, facet, getStress, sphere, wall)
from talus import twin

TWINS = Path(__file__).parents[1] / "yade_twins" / "periodic"  # the scripts Yade and Talus both run
LINEAR = ([Ip2_FrictMat_FrictMat_FrictPhys()], [Law2_ScGeom_FrictPhys_CundallStrack()])


def periodic_scene(size=(1, 1, 1), damping=0.0, material=None, laws=LINEAR):
    S = Scene()
    S.periodic = True
    S.cell.setBox(size)
    S.materials.append(material or FrictMat(young=1e7, poisson=0.3, frictionAngle=0.5, density=2600))
    S.engines = [ForceResetter(), InsertionSortCollider(), InteractionLoop([], *laws), NewtonIntegrator(damping=damping)]
    return S


def test_contact_across_the_boundary():
    S = periodic_scene()
    S.bodies.append([sphere((0.035, 0.5, 0.5), 0.06), sphere((0.935, 0.5, 0.5), 0.06)])
    S.dt = 1e-9
    S.step()
    (c,) = S.contacts()
    # Through the boundary the centres are 0.1 apart: overlap 0.02, normal from 1 to 2's image.
    assert c["penetrationDepth"] == pytest.approx(0.02, rel=1e-9)
    assert c["normal"] == pytest.approx((-1, 0, 0), abs=1e-12)
    assert c["normalForce"][0] == pytest.approx(-c["kn"] * 0.02, rel=1e-9)
    f = S.forces()
    assert f[0, 0] > 0 and f[1, 0] < 0 and f[0, 0] == pytest.approx(-f[1, 0])
    stress = getStress(scene=S)
    assert stress[0, 0] == pytest.approx(-c["kn"] * 0.02 * 0.1, rel=1e-9)   # -(f l) / V, V = 1


@pytest.mark.parametrize("step, vel, pos", [  # Yade 2023.02a, the same single free particle
    (1, (-0.25, -0.35, -0.25), (0.4975, 0.6965, 0.4975)),
    (2, (-0.24875, -0.34825, -0.24875), (0.4950125, 0.6930175, 0.4950125)),
    (3, (0.34650875, 0, 0), (0.49847758750000004, 0.6930175, 0.4950125)),
    (5, (0.34650875, 0, 0), (0.5054077625, 0.6930175, 0.4950125)),
])
def test_homogeneous_deformation_matches_yade(step, vel, pos):
    S = periodic_scene()
    S.bodies.append(sphere((0.5, 0.7, 0.5), 0.1))
    S.dt = 0.01
    S.cell.velGrad = Matrix3(-0.5, 0, 0, 0, -0.5, 0, 0, 0, -0.5)
    for k in range(1, step + 1):
        if k == 3:
            S.cell.velGrad = Matrix3(0, 0.5, 0, 0, 0, 0, 0, 0, 0)
        S.step()
    assert S.bodies[0].state.vel == pytest.approx(vel, abs=1e-15)
    assert S.bodies[0].state.pos == pytest.approx(pos, abs=1e-15)


def test_free_particles_follow_the_cell_exactly():
    S = periodic_scene()
    S.bodies.append([sphere((0.2, 0.3, 0.4), 0.05), sphere((0.7, 0.8, 0.1), 0.05)])
    frac0 = np.linalg.solve(S.cell.hSize, S.positions().T)
    S.dt = 1e-3
    S.cell.velGrad = Matrix3(0.3, 0.8, 0, -0.2, -0.1, 0.4, 0, 0.1, 0.2)
    S.run(500)
    frac = np.linalg.solve(S.cell.hSize, S.positions().T)
    assert np.abs(frac - frac0).max() < 1e-12
    assert S.cell.trsf == pytest.approx(S.cell.hSize, abs=1e-15)


def test_rigid_rotation_of_the_cell_spins_the_particles_and_makes_no_shear():
    # Heavy spheres (no fluctuation) in a cell rotating rigidly about z: they spin with the
    # cell, and the ScGeom shear increment (lever arms = radii, translation scaled by
    # alpha = (r1 + r2) / (r1 + r2 - u) as Yade's avoidGranularRatcheting) vanishes for a rigid
    # motion: no shear force beyond round-off. Without the spin the shear / normal ratio would
    # be (ks / kn) (distance / penetration) angle (0.7 here), with radii arms but no alpha
    # (ks / kn) angle (6e-4).
    S = periodic_scene()
    S.materials[0].density = 1e12
    S.bodies.append([sphere((0.45, 0.5, 0.5), 0.06), sphere((0.5699, 0.5, 0.5), 0.06)])
    S.dt = 1e-5
    S.cell.velGrad = Matrix3(0, -1, 0, 1, 0, 0, 0, 0, 0)
    S.run(200)
    assert S.bodies[0].state.angVel == pytest.approx((0, 0, 1), abs=1e-9)
    (c,) = S.contacts()
    angle = S.time * 1.0
    ratio = np.linalg.norm(c["shearForce"]) / np.linalg.norm(c["normalForce"])
    assert ratio < 1e-3 * c["ks"] / c["kn"] * angle


@pytest.mark.skipif(not twin.yade_available(), reason="yade is not installed (./setup.sh installs it)")
def test_stress_of_a_sheared_periodic_packing_equals_yades():
    ours = twin.run(TWINS / "periodic_stress.py", {}, "talus", timeout=300)
    yade = twin.run(TWINS / "periodic_stress.py", {}, "yade", timeout=300)
    assert ours["contacts"] == yade["contacts"] > 2
    scale = np.abs(yade["stress"]).max()
    assert np.abs(np.array(ours["stress"]) - np.array(yade["stress"])).max() < 1e-12 * scale


def test_bad_periodic_input():
    S = periodic_scene()
    # A sphere given outside the cell stays where it was put, as in Yade.
    assert S.bodies[S.bodies.append(sphere((1.2, 0.5, 0.5), 0.1))].state.pos[0] == pytest.approx(1.2)
    with pytest.raises(ValueError, match="positive volume"):
        S.cell.hSize = Matrix3(1, 0, 0, 0, 0, 0, 0, 0, 1)
    with pytest.raises(ValueError, match="finite 3x3"):
        S.cell.velGrad = [1, 2, 3]
    T = Scene()
    T.bodies.append(sphere((5, 5, 5), 0.1))
    T.periodic = True     # bodies outside the cell are fine (Yade's periodic-simple.py sets the cell after them)
    assert T.periodic and T.bodies[0].state.pos == pytest.approx([5, 5, 5])


def spheres_on_a_wall(periodic: bool):
    """Spheres bouncing and rolling on a bed wall, crossing the cell's side boundaries."""
    S = Scene()
    if periodic:
        S.periodic = True
        S.cell.setBox(0.5, 0.5, 2.0)
    S.materials.append(FrictMat(young=1e7, poisson=0.3, frictionAngle=0.5, density=2600))
    S.bodies.append(wall(0.2, axis=2, sense=1))
    ids = S.bodies.append([sphere((0.47, 0.25, 0.2501), 0.05), sphere((0.25, 0.43, 0.2501), 0.05),
                           sphere((0.25, 0.07, 0.27), 0.05)])
    for i, v in zip(ids, [(1.0, 0.1, 0), (0.0, 0.5, 0), (0, -0.5, -0.5)]):
        S.bodies[i].state.vel = v
    S.engines = [ForceResetter(), InsertionSortCollider(),
                 InteractionLoop([], [Ip2_FrictMat_FrictMat_FrictPhys()], [Law2_ScGeom_FrictPhys_CundallStrack()]),
                 NewtonIntegrator(gravity=(0, 0, -9.81), damping=0.1)]
    S.dt = 2e-5
    return S, ids


def test_a_bed_wall_in_a_periodic_cell():
    """A wall in a periodic cell meets the spheres themselves: while no two spheres touch, the
    periodic run equals the same scene without a cell to round-off, spheres crossing the side
    boundaries included; across a boundary, spheres then meet each other as periodic images."""
    P, ids = spheres_on_a_wall(True)
    F, _ = spheres_on_a_wall(False)
    first_meeting, crossed, on_wall = None, False, set()
    for k in range(400):
        P.run(20)
        F.run(20)
        on_wall |= {c["id2"] for c in P.contacts() if c["id1"] == 0}
        if any(c["id1"] != 0 for c in P.contacts()):
            first_meeting = P.iter
            break
        np.testing.assert_allclose(P.positions()[ids], F.positions()[ids], rtol=0, atol=1e-12)
        np.testing.assert_allclose(P.angular_velocities()[ids], F.angular_velocities()[ids], rtol=0, atol=1e-9)
        crossed |= P.positions()[ids[0]][0] > 0.5
    assert crossed, "sphere 1 rolls out through x = 0.5 before the others meet"
    assert first_meeting is not None, "spheres 2 and 3 should meet across the y boundary"
    assert all(c["id1"] == 0 for c in F.contacts())  # without the cell they never meet
    assert on_wall == set(ids), "all three bounce on the bed wall"
    # Facets and boxes are periodic too (tests/dem/contact/test_periodic_boundaries.py), Potential
    # Blocks and Particles are not.
    T = Scene()
    T.bodies.append(facet([(0, 0, 0), (1, 0, 0), (0, 1, 0)]))
    T.periodic = True


#: Each law whose forces have AVX2 lanes: its material and its Ip2/Law2 functors.
LANE_LAWS = {"linear": (lambda: None, LINEAR),
             "hertz": (lambda: FrictMat(young=1e7, poisson=0.3, frictionAngle=0.5, density=2600),
                       ([Ip2_FrictMat_FrictMat_MindlinPhys()], [Law2_ScGeom_MindlinPhys_Mindlin()])),
             "viscoelastic": (lambda: ViscElMat(tc=1e-4, en=0.5, et=0.5, frictionAngle=0.5, density=2600),
                              ([Ip2_ViscElMat_ViscElMat_ViscElPhys()], [Law2_ScGeom_ViscElPhys_Basic()]))}


@pytest.mark.parametrize("law", LANE_LAWS)
def test_pairs_and_spheres_of_a_deforming_cell_take_the_batched_lanes_with_the_same_bits(law):
    """Sphere pairs in a periodic cell, inside it and across its boundary (their image's shift:
    the visco-elastic law's own arms and velocity at the contact point too), go four at a time
    through the AVX2 geometry and each law (where the processor has it), and the
    spheres of the deforming cell through the integrator's lanes (the affine field and its spin
    taken off and added back); energy tracking runs every contact and body one by one: a small
    sheared RVE (a jittered fcc packing, a quarter of its contacts across the boundary; a velocity
    gradient with every entry set, so that each row of L x is summed as the scalar path sums it)
    gives the same bits either way."""
    def run(track):
        rng = np.random.default_rng(1)
        r, cells = 0.01, 4
        a = 2 * np.sqrt(2) * r
        material, laws = LANE_LAWS[law]
        S = periodic_scene((cells * a,) * 3, damping=0.2, material=material(), laws=laws)
        basis = np.array([[0, 0, 0], [0.5, 0.5, 0], [0.5, 0, 0.5], [0, 0.5, 0.5]]) * a
        S.bodies.append([sphere(tuple((np.array(corner) + 0.25) * a + b + rng.uniform(-0.01, 0.01, 3) * r),
                                r * rng.uniform(0.998, 1.004))
                         for corner in np.ndindex(cells, cells, cells) for b in basis])
        S.dt = 2e-6
        S.trackEnergy = track
        S.cell.velGrad = Matrix3(-0.5, 0.1, 0.03, 0.07, 0.2, -0.04, -0.06, 0.05, 0.25)
        S.run(300, True)
        return S
    batched, one_by_one = run(False), run(True)
    contacts = batched.contacts()
    across = sum(1 for c in contacts if tuple(c["cellDist"]) != (0, 0, 0))
    assert len(contacts) > 800 and 0.1 * len(contacts) < across < 0.5 * len(contacts)
    for values in ("positions", "velocities", "angular_velocities", "forces"):
        assert np.array_equal(getattr(batched, values)(), getattr(one_by_one, values)()), values
    assert np.array_equal(getStress(scene=batched), getStress(scene=one_by_one))
