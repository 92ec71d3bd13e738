"""Erasing bodies, contacts and clumps keeps the per-contact state of the laws that have one
(Hertz-Mindlin, cohesive-frictional, visco-elastic with rolling resistance) with its contact.

Each scene holds two lattices of spheres that never touch: C, appended first (so its contacts
come first in the contact list), and G. Something of C is erased in the middle of the run; G
must then move exactly as in the same run where that thing was never there: a contact of G
reading another pair's state (the contacts of C before it were removed, their state was not)
would change its forces."""
import numpy as np
import pytest

from talus.dem import (CohFrictMat, ForceResetter, FrictMat, InsertionSortCollider, InteractionLoop, NewtonIntegrator,
                       PyRunner, Scene, ViscElMat, sphere, Bo1_Sphere_Aabb, Ig2_Sphere_Sphere_ScGeom,
                       Ig2_Sphere_Sphere_ScGeom6D, Ip2_CohFrictMat_CohFrictMat_CohFrictPhys,
                       Ip2_FrictMat_FrictMat_MindlinPhys, Ip2_ViscElMat_ViscElMat_ViscElPhys,
                       Law2_ScGeom6D_CohFrictPhys_CohesionMoment, Law2_ScGeom_MindlinPhys_Mindlin,
                       Law2_ScGeom_ViscElPhys_Basic)

R = 0.01
STEPS = 400


def materials(law):
    """A material for C and another for G: a contact of G given the state of a contact of C
    would get other constants."""
    if law == "mindlin":
        return FrictMat(young=5e6, density=2600, frictionAngle=0.3), FrictMat(young=2e7, density=2600, frictionAngle=0.5)
    if law == "cohfrict":
        return [CohFrictMat(young=young, density=2600, frictionAngle=0.4, normalCohesion=c, shearCohesion=c,
                            momentRotationLaw=True, alphaKr=2.0, alphaKtw=2.0) for young, c in ((5e6, 2e3), (2e7, 1e5))]
    # (G without rolling resistance: only its contacts given C's state would resist rolling)
    return [ViscElMat(kn=kn, ks=kn / 2, cn=0.5, cs=0.2, density=2600, frictionAngle=0.4, mR=mR, mRtype=1)
            for kn, mR in ((2e4, 4e-4), (1e5, 0.0))]


def engines(law):
    geometry = Ig2_Sphere_Sphere_ScGeom6D() if law == "cohfrict" else Ig2_Sphere_Sphere_ScGeom()
    physics, contact = {
        "mindlin": (Ip2_FrictMat_FrictMat_MindlinPhys(betan=0.2, betas=0.2), Law2_ScGeom_MindlinPhys_Mindlin()),
        "cohfrict": (Ip2_CohFrictMat_CohFrictMat_CohFrictPhys(setCohesionNow=True),
                     Law2_ScGeom6D_CohFrictPhys_CohesionMoment(useIncrementalForm=True)),
        "viscel": (Ip2_ViscElMat_ViscElMat_ViscElPhys(), Law2_ScGeom_ViscElPhys_Basic()),
    }[law]
    return [ForceResetter(), InsertionSortCollider([Bo1_Sphere_Aabb()]),
            InteractionLoop([geometry], [physics], [contact]), NewtonIntegrator(gravity=(0.3, -0.5, -9.81), damping=0.1)]


def lattice(S, origin, material, rng):
    """4 x 4 x 4 spheres of slightly different radii, overlapping their neighbours, the bottom
    layer fixed; top layer first (the first contacts of G, those a misaligned state would
    shift, are then between moving spheres)."""
    ids = []
    for i in range(4):
        for j in range(4):
            for k in (3, 2, 1, 0):
                centre = np.asarray(origin) + 1.96 * R * np.array([i, j, k]) + rng.uniform(-0.02, 0.02, 3) * R
                ids.append(S.bodies.append(sphere(centre, R * rng.uniform(0.99, 1.02), material=material,
                                                  fixed=k == 0)))
    return ids


def build(law):
    S = Scene()
    mc, mg = (S.materials[S.materials.append(m)] for m in materials(law))
    rng = np.random.default_rng(7)
    c = lattice(S, (0, 0, 0), mc, rng)
    g = lattice(S, (1, 0, 0), mg, rng)
    S.engines = engines(law)
    S.dt = 2e-6 if law != "viscel" else 1e-5
    return S, c, g


def state_of(S, ids):
    """Positions, velocities and rotations of bodies ``ids``, and the state of their contacts."""
    b = [S.bodies[i].state for i in ids]
    motion = np.array([[*s.pos, *s.vel, *s.angVel] for s in b])
    members = set(ids)
    contacts = {(i.id1, i.id2): (i.phys.kn, *i.phys.normalForce, *i.phys.shearForce)
                for i in S.interactions if i.isReal and i.id1 in members}
    return motion, contacts


def run(law, erase):
    """The run with ``erase(S, c)`` called at mid-run (None: never)."""
    S, c, g = build(law)
    S.run(STEPS // 2)
    if erase is not None:
        erase(S, c)
    S.run(STEPS // 2)
    return S, c, g


def erase_body(S, c):
    S.bodies.erase(c[21])          # inside C: contacts with six neighbours


def erase_interaction(S, c):
    pair = next(i for i in S.interactions if i.isReal and i.id1 == c[21])
    assert S.interactions.erase(pair.id1, pair.id2)


def erase_clump(S, c):
    S.bodies.erase(S.bodies[c[21]].clumpId, eraseClumpMembers=True)


@pytest.mark.parametrize("law", ["mindlin", "cohfrict", "viscel"])
@pytest.mark.parametrize("what", ["body", "interaction"])
def test_erasing_in_one_lattice_leaves_the_other_as_if_nothing_was_erased(law, what):
    erase = {"body": erase_body, "interaction": erase_interaction}[what]
    S, c, g = run(law, erase)
    # The reference: the body never there (erased before the first step), or nothing erased
    # (an erased interaction's pair only touches C).
    if what == "body":
        T, _, _ = build(law)
        erase(T, c)
        T.run(STEPS)
    else:
        T, _, _ = run(law, None)
    motion, contacts = state_of(S, g)
    expected_motion, expected_contacts = state_of(T, g)
    assert len(contacts) > 15 and all(v[0] > 0 for v in contacts.values())
    assert contacts.keys() == expected_contacts.keys()
    np.testing.assert_array_equal(np.array(list(contacts.values())), np.array(list(expected_contacts.values())))
    np.testing.assert_array_equal(motion, expected_motion)
    # C did change: the erase did something.
    assert not np.array_equal(state_of(S, c[:21])[0], state_of(T, c[:21])[0]) or what == "interaction"


@pytest.mark.parametrize("law", ["mindlin", "cohfrict", "viscel"])
def test_erasing_a_clump_with_its_members_leaves_the_other_lattice_as_if_it_was_never_there(law):
    def with_clump(law):
        S, c, g = build(law)
        S.bodies.clump([c[21], c[22]])
        return S, c, g
    S, c, g = with_clump(law)
    S.run(STEPS // 2)
    erase_clump(S, c)
    S.run(STEPS // 2)
    T, _, _ = with_clump(law)
    erase_clump(T, c)
    T.run(STEPS)
    assert S.bodies[c[21]] is None and S.bodies[c[22]] is None
    motion, contacts = state_of(S, g)
    expected_motion, expected_contacts = state_of(T, g)
    assert contacts.keys() == expected_contacts.keys() and len(contacts) > 15
    np.testing.assert_array_equal(np.array(list(contacts.values())), np.array(list(expected_contacts.values())))
    np.testing.assert_array_equal(motion, expected_motion)


def test_a_silo_that_erases_the_spheres_leaving_it_runs_on():
    """Hertz-Mindlin spheres drain through a hole in a silo's floor and are erased once below
    it, every 50 steps: the run goes on without overlap errors, every real contact keeping a
    positive stiffness (erasing used to hand contacts the state of others, kn = 0, until a step
    failed with an overlap blamed on the time step)."""
    from talus.dem import Bo1_Facet_Aabb, Ig2_Facet_Sphere_ScGeom, PWaveTimeStep, facet
    from talus.dem.geometry import geom
    from talus.dem.packing import pack
    S = Scene()
    S.materials.append(FrictMat(young=1e7, poisson=0.3, density=2600, frictionAngle=0.4))
    a, hole = 0.1, 0.05
    S.bodies.append(geom.facetBox((0, 0, 0.2), (a, a, 0.2), wallMask=15))
    for (x0, y0), (x1, y1) in [((-a, -a), (a, -hole)), ((-a, hole), (a, a)), ((-a, -hole), (-hole, hole)),
                               ((hole, -hole), (a, hole))]:
        S.bodies.append([facet([(x0, y0, 0), (x1, y0, 0), (x1, y1, 0)]), facet([(x0, y0, 0), (x1, y1, 0), (x0, y1, 0)])])
    sp = pack.SpherePack()
    sp.makeCloud((-a + 0.005, -a + 0.005, 0.005), (a - 0.005, a - 0.005, 0.4), rMean=0.01, rRelFuzz=0.2, num=400,
                 seed=1)
    spheres = sp.toSimulation(S)
    erased, softest = [], []

    def drain():
        z = S._cpp.pos()[:, 2]
        for i in spheres:
            if z[i] < -0.05 and S.bodies.erase(i):
                erased.append(i)
        if S.iter % 500 == 0:
            softest.append(min((i.phys.kn for i in S.interactions if i.isReal), default=1.0))

    S.engines = [ForceResetter(), InsertionSortCollider([Bo1_Sphere_Aabb(), Bo1_Facet_Aabb()]),
                 InteractionLoop([Ig2_Sphere_Sphere_ScGeom(), Ig2_Facet_Sphere_ScGeom()],
                                 [Ip2_FrictMat_FrictMat_MindlinPhys()], [Law2_ScGeom_MindlinPhys_Mindlin()]),
                 NewtonIntegrator(gravity=(0, 0, -9.81), damping=0.2), PyRunner(drain, iterPeriod=50)]
    S.dt = 0.5 * PWaveTimeStep(S)
    S.run(12000)
    assert len(erased) > 100 and S.interactions.countReal() > 200
    assert min(softest) > 0
