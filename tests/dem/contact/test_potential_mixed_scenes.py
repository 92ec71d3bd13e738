"""Mixed scenes: spheres, Potential Blocks and Potential Particles in one scene and one
InteractionLoop with a law for each (the seed gives no contact between a block and a particle,
nor between them and spheres or facets; Yade has no such functors either): every contact goes to
its family's law, and each body rests on the floor wall at the overlap its own law gives."""
import math

import numpy as np
import pytest

from talus import _dem
from talus.dem import (ForceResetter, FrictMat, Ig2_PB_PB_ScGeom, Ig2_PP_PP_ScGeom, Ig2_Sphere_Sphere_ScGeom,
                       Ig2_Wall_Sphere_ScGeom, InsertionSortCollider, InteractionLoop, Ip2_FrictMat_FrictMat_FrictPhys,
                       Ip2_FrictMat_FrictMat_KnKsPBPhys, Ip2_FrictMat_FrictMat_KnKsPhys,
                       Law2_SCG_KnKsPBPhys_KnKsPBLaw, Law2_SCG_KnKsPhys_KnKsLaw, Law2_ScGeom_FrictPhys_CundallStrack,
                       NewtonIntegrator, PotentialBlock, PotentialBlock2AABB, PotentialParticle, PotentialParticle2AABB,
                       Scene, potentialBlock, potentialParticle, sphere, wall)

pytestmark = pytest.mark.skipif(not _dem.have_potential_blocks, reason="built without CLP")
YOUNG, KNORMAL, G = 1e7, 1e8, 9.81


def mixed_scene(laws=("spheres", "blocks", "particles")) -> tuple:
    """A floor wall; a sphere, a cube block and a cube particle resting side by side on it, and a
    sphere placed inside the block (no contact exists between them)."""
    S = Scene()
    m = S.materials.append(FrictMat(young=YOUNG, poisson=0.3, density=1000, frictionAngle=0.5))
    S.bodies.append(wall(0, axis=2, sense=1, material=m))
    ball = S.bodies.append(sphere((-2, 0, 0.2), 0.2, material=m))
    block = S.bodies.append(potentialBlock(PotentialBlock.cuboid((0.5, 0.5, 0.5), r=0.02), pos=(0, 0, 0.5),
                                           material=m))
    cube = PotentialParticle.cuboid((0.5, 0.5, 0.5), r=0.05, k=0.2)
    particle = S.bodies.append(potentialParticle(cube, pos=(2, 0, 0.5), material=m))
    inside = S.bodies.append(sphere((0, 0, 0.6), 0.1, material=m, fixed=True))
    family = {"spheres": ([Ig2_Sphere_Sphere_ScGeom(), Ig2_Wall_Sphere_ScGeom()], [Ip2_FrictMat_FrictMat_FrictPhys()],
                          [Law2_ScGeom_FrictPhys_CundallStrack()]),
              "blocks": ([Ig2_PB_PB_ScGeom()], [Ip2_FrictMat_FrictMat_KnKsPBPhys(Knormal=KNORMAL, kn_i=KNORMAL,
                                                                                  viscousDamping=0.5)],
                         [Law2_SCG_KnKsPBPhys_KnKsPBLaw()]),
              "particles": ([Ig2_PP_PP_ScGeom()], [Ip2_FrictMat_FrictMat_KnKsPhys(Knormal=KNORMAL, viscousDamping=0.5)],
                            [Law2_SCG_KnKsPhys_KnKsLaw()])}
    geom, phys, law = ([f for name in laws for f in family[name][k]] for k in range(3))
    S.engines = [ForceResetter(),
                 InsertionSortCollider([PotentialBlock2AABB(), PotentialParticle2AABB()], verletDist=0.01),
                 InteractionLoop(geom, phys, law), NewtonIntegrator(gravity=(0, 0, -G), damping=0.3)]
    S.dt = 1e-4
    return S, ball, block, particle, inside


def test_each_family_rests_on_the_floor_with_its_own_law():
    S, ball, block, particle, _ = mixed_scene()
    S.run(6000, True)
    contacts = {(c["id1"], c["id2"]): c for c in S._cpp.contacts()}
    assert set(contacts) == {(0, ball), (0, block), (0, particle)}
    areas = dict(zip(((c["id1"], c["id2"]) for c in S._cpp.contacts()), _dem.contact_areas(S._cpp)))
    mass = S._cpp.mass()
    for body in (ball, block, particle):
        assert contacts[(0, body)]["normalForce"][2] == pytest.approx(mass[body] * G, rel=1e-4)
    # the sphere: Cundall-Strack's kn = E r (Yade's wall-sphere stiffness), the blocks and
    # particles: Knormal times their contact area
    assert contacts[(0, ball)]["penetrationDepth"] == pytest.approx(mass[ball] * G / (YOUNG * 0.2), rel=1e-3)
    for body in (block, particle):
        expected = mass[body] * G / (KNORMAL * areas[(0, body)])
        assert contacts[(0, body)]["penetrationDepth"] == pytest.approx(expected, rel=1e-3)


@pytest.mark.parametrize("laws, body, shape", [(("blocks", "particles"), 1, "Sphere"),
                                               (("spheres",), 2, "PotentialBlock")])
def test_a_family_without_its_law_is_refused(laws, body, shape):
    S, *_ = mixed_scene(laws)
    message = (rf"cannot handle the contacts of body {body} \({shape}\)" if len(laws) == 1 else
               rf"no contact law of the InteractionLoop handles the contact of bodies 0 and {body} .*Wall and {shape}")
    with pytest.raises(RuntimeError, match=message):
        S.run(200, True)
