"""Clumps in periodic cells: SpherePack.makeClumpCloud (Yade's, with numpy's random numbers:
tested on its properties), clumps following the cell's affine field, contacts through the
periodic images, a PeriTriaxController compression of a clump cloud, bit-identical restarts."""
import numpy as np
import pytest

from talus.dem import (FrictMat, ForceResetter, InsertionSortCollider, InteractionLoop,
                       Ip2_FrictMat_FrictMat_FrictPhys, Law2_ScGeom_FrictPhys_CundallStrack, Matrix3,
                       NewtonIntegrator, PeriTriaxController, PWaveTimeStep, Scene, getStress, sphere,
                       unbalancedForce)
from talus.dem.files import io
from talus.dem.packing import pack

# The seed's tutorial template: a sphere with two smaller ones stuck on it.
C1 = [((0, 0, 0), .03333), ((.03, 0, 0), .017), ((0, .03, 0), .017)]


def engines(*controllers, damping=0.0):
    return [ForceResetter(), InsertionSortCollider(),
            InteractionLoop([], [Ip2_FrictMat_FrictMat_FrictPhys()], [Law2_ScGeom_FrictPhys_CundallStrack()]),
            *controllers, NewtonIntegrator(damping=damping)]


def periodic_scene(size=(1, 1, 1)):
    S = Scene()
    S.periodic = True
    S.cell.setBox(size)
    S.materials.append(FrictMat(young=1e7, poisson=0.3, frictionAngle=0.5, density=2600))
    S.engines = engines()
    return S


def template_distances(spheres):
    x = np.array([c for c, _ in spheres], dtype=float)
    return np.linalg.norm(x[:, None] - x[None], axis=2)


def min_gap(x, r, cell=None):
    d = x[:, None] - x[None]
    if cell is not None:
        d -= cell * np.round(d / cell)
    gap = np.linalg.norm(d, axis=2) - (r[:, None] + r[None])
    np.fill_diagonal(gap, np.inf)
    return gap


@pytest.mark.parametrize("periodic", [True, False])
def test_clump_cloud_properties(periodic):
    sp = pack.SpherePack()
    big = [((0, 0, 0), .05), ((.06, 0, 0), .03)]
    n = sp.makeClumpCloud((0, 0, 0), (1, 1, 1), [C1, big], periodic=periodic, num=150, seed=3)
    assert n == 150
    ids = sp.clumpIds
    assert sorted(set(ids)) == list(range(150)) and len(sp) == len(ids)
    standalone, clumps = sp.getClumps()
    assert standalone == [] and len(clumps) == 150 and sum(map(len, clumps)) == len(sp)
    x, r = np.array([c for c, _ in sp]), np.array([rr for _, rr in sp])
    gap = min_gap(x, r, np.ones(3) if periodic else None)
    same = ids[:, None] == ids[None]
    assert gap[~same].min() >= 0, "two clumps overlap"
    if periodic:   # clumps cross the boundary: the gaps above were taken through the images
        assert sp.isPeriodic and np.allclose(sp.cellSize, 1)
        assert np.any((x - r[:, None] < 0) | (x + r[:, None] > 1))
    else:
        assert np.all(x - r[:, None] >= 0) and np.all(x + r[:, None] <= 1)
    for c in range(150):   # each clump is a template moved rigidly, centred on its centroid
        members = np.flatnonzero(ids == c)
        template = C1 if len(members) == 3 else big
        assert np.allclose(r[members], [rr for _, rr in template])
        assert np.allclose(template_distances([(x[m], 0) for m in members]), template_distances(template), atol=1e-12)
        centroid = (r[members, None] ** 3 * x[members]).sum(axis=0) / (r[members] ** 3).sum()
        assert np.all(centroid >= 0) and np.all(centroid <= 1)
    # without num, clumps are added until one cannot be placed in 200 tries: a dense cloud
    dense = pack.SpherePack()
    m = dense.makeClumpCloud((0, 0, 0), (.4, .4, .4), [C1], periodic=periodic, seed=1)
    assert m > 20 and len(dense) == 3 * m


def test_clump_cloud_to_simulation_makes_clumps_in_the_cell():
    sp = pack.SpherePack()
    sp.makeClumpCloud((0, 0, 0), (1, 1, 1), [C1], periodic=True, num=100, seed=5)
    S = Scene()
    S.materials.append(FrictMat(young=1e7, poisson=0.3, frictionAngle=0.5, density=2600))
    made = sp.toSimulation(S)
    assert S.periodic and np.allclose(S.cell.hSize, np.eye(3)) and len(made) == 100
    sticking_out = 0
    for clump, members in made:
        assert len(members) == 3 and S.bodies[clump].isClump
        centre = np.asarray(S.bodies[clump].state.pos)
        assert np.all(centre >= 0) and np.all(centre < 1)
        pos = np.array([S.bodies[m].state.pos for m in members])
        assert np.allclose(np.linalg.norm(pos[:, None] - pos[None], axis=2), template_distances(C1), atol=1e-12)
        sticking_out += np.any((pos < 0) | (pos >= 1))
    assert sticking_out > 0, "some clumps should cross the boundary"


def test_free_clump_follows_the_affine_field_exactly():
    # Pure shear (symmetric L, no spin): the clump's centre keeps its fractional coordinates, it
    # does not turn; with a spin it turns at the field's spin.
    for L, spin in [(Matrix3(0.3, 0.5, 0, 0.5, -0.1, 0.2, 0, 0.2, -0.2), (0, 0, 0)),
                    (Matrix3(0.3, 0.8, 0, -0.2, -0.1, 0.4, 0, 0.1, 0.2), (-0.15, 0, -0.5))]:
        S = periodic_scene()
        clump, members = S.bodies.appendClumped([sphere((0.97, 0.3, 0.4), 0.05), sphere((1.04, 0.3, 0.4), 0.04)])
        ori0 = np.array(S.bodies[clump].state.ori)
        frac0 = np.linalg.solve(S.cell.hSize, S.bodies[clump].state.pos)
        S.dt = 1e-3
        S.cell.velGrad = L
        S.run(500)
        st = S.bodies[clump].state
        assert np.abs(np.linalg.solve(S.cell.hSize, st.pos) - frac0).max() < 1e-12
        # the field at the position the step started from
        assert st.vel == pytest.approx(np.array(S.cell.velGrad) @ (st.pos - S.dt * st.vel), abs=1e-12)
        assert st.angVel == pytest.approx(spin, abs=1e-12)
        if spin == (0, 0, 0):
            assert np.array(st.ori) == pytest.approx(ori0, abs=1e-14)
        else:   # turned by |spin| t about the spin's axis
            angle = 2 * np.arccos(min(1.0, abs(np.dot(np.array(st.ori), ori0))))
            assert angle == pytest.approx(np.linalg.norm(spin) * S.time, rel=1e-9)
        # members follow rigidly
        d = np.array(S.bodies[members[1]].state.pos) - np.array(S.bodies[members[0]].state.pos)
        assert np.linalg.norm(d) == pytest.approx(0.07, rel=1e-12)
        assert len(S.contacts()) == 0, "members of a clump must not touch, not even through an image"


def test_clump_across_the_boundary_touches_a_sphere_through_the_image():
    S = periodic_scene()
    clump, members = S.bodies.appendClumped([sphere((0.95, 0.5, 0.5), 0.05), sphere((1.03, 0.5, 0.5), 0.04)])
    ball = S.bodies.append(sphere((0.11, 0.5, 0.5), 0.05))
    S.dt = 1e-6
    S.step()
    (c,) = S.contacts()
    # member 2 at x = 1.03 touches the sphere's image at 1.11: overlap 0.04 + 0.05 - 0.08
    assert {c["id1"], c["id2"]} == {members[1], ball}
    assert c["penetrationDepth"] == pytest.approx(0.01, rel=1e-9)
    # The clump is pushed back (-x), the sphere forward (+x), momentum is conserved.
    S.dt = 0.2 * PWaveTimeStep(S)
    S.run(200)
    assert S.bodies[clump].state.vel[0] < 0 < S.bodies[ball].state.vel[0]
    total = S.bodies[clump].state.mass * np.array(S.bodies[clump].state.vel) \
        + S.bodies[ball].state.mass * np.array(S.bodies[ball].state.vel)
    assert np.abs(total).max() < 1e-12 * S.bodies[ball].state.mass * abs(S.bodies[ball].state.vel[0])


def clump_cloud(num=120, seed=2):
    sp = pack.SpherePack()
    sp.makeClumpCloud((0, 0, 0), (.5, .5, .5), [C1], periodic=True, num=num, seed=seed)
    S = Scene()
    S.materials.append(FrictMat(young=1e7, poisson=0.3, frictionAngle=0.3, density=2600))
    sp.toSimulation(S)
    return S


def test_peri_triax_compresses_a_clump_cloud_to_the_stress_goal():
    S = clump_cloud()
    done = []
    triax = PeriTriaxController(goal=(-1e4, -1e4, -1e4), stressMask=7, dynCell=True, maxStrainRate=(2, 2, 2),
                                maxUnbalanced=.05, relStressTol=2e-3,
                                doneHook=lambda: (done.append(S.iter), S.pause()))
    S.engines = engines(triax, damping=0.2)
    S.dt = 0.5 * PWaveTimeStep(S)
    S.run(30000)
    assert done, "the goal was not reached in 30000 steps"
    stress = getStress(scene=S)
    assert np.allclose(np.diag(stress), -1e4, rtol=3e-3)
    assert unbalancedForce(scene=S) < .05


@pytest.mark.skipif(not io.available(), reason="built without HDF5")
def test_periodic_clump_restart_is_bit_identical(tmp_path):
    # Saved in the middle of a PeriTriaxController compaction (the cell moving, contacts forming).
    A = clump_cloud()
    A.engines = engines(PeriTriaxController(goal=(-1e4, -1e4, -1e4), stressMask=7, dynCell=True,
                                            maxStrainRate=(2, 2, 2), maxUnbalanced=.05), damping=0.2)
    A.dt = 0.5 * PWaveTimeStep(A)
    A.run(1500)
    io.save(A, tmp_path / "c.h5")
    A.run(500)
    assert A._cpp.realContactCount() > 100
    B = Scene()
    io.load(B, tmp_path / "c.h5")
    B.run(500)
    assert np.array_equal(np.array(B.cell.hSize), np.array(A.cell.hSize))
    for name in ("positions", "velocities"):
        assert np.array_equal(np.asarray(getattr(B, name)()), np.asarray(getattr(A, name)())), name
    for i in range(len(A.bodies)):
        assert np.array_equal(np.array(A.bodies[i].state.ori), np.array(B.bodies[i].state.ori))
        assert np.array_equal(np.array(A.bodies[i].state.angVel), np.array(B.bodies[i].state.angVel))


def test_bad_periodic_clump_input():
    S = periodic_scene()
    # A clump outside the cell stays where it was put, as in Yade.
    clump, _ = S.bodies.appendClumped([sphere((1.03, 0.5, 0.5), 0.05), sphere((1.1, 0.5, 0.5), 0.04)])
    assert S.periodic and S.bodies[clump].state.pos[0] > 1
    with pytest.raises(ValueError, match="maxCorner"):
        pack.SpherePack().makeClumpCloud((0, 0, 0), (1, 0, 1), [C1])
    with pytest.raises(ValueError, match="template #0 is empty"):
        pack.SpherePack().makeClumpCloud((0, 0, 0), (1, 1, 1), [[]])
