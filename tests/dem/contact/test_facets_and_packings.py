"""Facets (face, edge and vertex contacts), facet boxes and regular packings, checked against
the values Yade 2023.02a gives for the same input."""
import numpy as np
import pytest

from talus.dem import (ForceResetter, InsertionSortCollider, InteractionLoop, Ip2_FrictMat_FrictMat_FrictPhys,
                       Law2_ScGeom_FrictPhys_CundallStrack, NewtonIntegrator, Scene, facet, sphere)
from talus.dem.geometry import geom
from talus.dem.packing import pack


def test_sphere_facet_contacts_match_yade():
    S = Scene()
    S.bodies.append([facet([(0, 0, 0), (1, 0, 0), (0, 1, 0)]), sphere((0.2, 0.2, 0.09), 0.1),
                     sphere((0.5, -0.05, 0.05), 0.1), sphere((-0.03, -0.04, 0.0), 0.1)])
    S.engines = [ForceResetter(), InsertionSortCollider(),
                 InteractionLoop([], [Ip2_FrictMat_FrictMat_FrictPhys()], [Law2_ScGeom_FrictPhys_CundallStrack()]),
                 NewtonIntegrator(damping=0)]
    S.dt = 1e-6
    S.step()
    # The facet's position is its incentre.
    assert S.bodies[0].state.pos == pytest.approx([0.2928932188134525, 0.2928932188134525, 0], abs=1e-15)
    got = {c["id2"]: c for c in S.contacts()}
    yade = {  # penetration, normal, contact point, normal force on the sphere
        1: (0.010000000000000009, (0, 0, 1), (0.2, 0.2, -0.005), (0, 0, 13333.333333333345)),           # face
        2: (0.029289321881345254, (0, -0.7071067811865474, 0.7071067811865476),                         # edge
            (0.5, 0.0103553390593273606, -0.01035533905932738141), (0, -27614.23749153966, 27614.23749153967)),
        3: (0.05000000000000004, (-0.6, -0.8, 0), (0.015, 0.02, 0), (-40000.000000000015, -53333.33333333338, 0)),  # vertex
    }
    for sid, (pen, n, cp, f) in yade.items():
        c = got[sid]
        assert c["id1"] == 0
        assert c["penetrationDepth"] == pytest.approx(pen, rel=1e-12)
        assert c["normal"] == pytest.approx(n, abs=1e-15)
        assert c["contactPoint"] == pytest.approx(cp, abs=1e-15)
        assert c["normalForce"] == pytest.approx(f, rel=1e-12, abs=1e-9)
        assert c["kn"] == pytest.approx(1333333.3333333333, rel=1e-14)   # facet radius = sphere diameter


def test_facet_box_has_yades_triangles():
    S = Scene()
    ids = S.bodies.append(geom.facetBox((0, 0, 0), (1, 2, 3)))
    assert len(ids) == 12
    assert len(S.bodies.append(geom.facetBox((0, 0, 0), (1, 1, 1), wallMask=16))) == 2   # -z only
    with pytest.raises(ValueError, match="extents"):
        geom.facetBox((0, 0, 0), (1, -1, 1))
    # a flat box is Yade's one rectangle, whatever the mask; two zero extents are refused
    assert len(S.bodies.append(geom.facetBox((0, 0, 0), (1, 1, 0), wallMask=32))) == 2
    with pytest.raises(ValueError, match="two extents"):
        geom.facetBox((0, 0, 0), (1, 0, 0))


def test_degenerate_facet_is_refused():
    with pytest.raises(ValueError, match="facet #0: the three vertices are .*collinear"):
        Scene().bodies.append(facet([(0, 0, 0), (1, 0, 0), (2, 0, 0)]))


def test_regular_hexa_equals_yades_packing():
    r = 0.5 / 23.658
    spheres = pack.regularHexa(pack.inSphere((0, 0, 0), 0.5), radius=r, gap=r * 0.5)
    assert len(spheres) == 4416                     # Yade's --quickperformance packing
    assert spheres[0].center == pytest.approx((-0.4735818750528362, -0.027172141958365092, -0.02545320873462542), abs=1e-15)
    assert spheres[-1].center == pytest.approx((0.45105249809789505, 0.14060548508866666, 0.017687408653135894), abs=1e-15)
    centres = np.array([s.center for s in spheres])
    gaps = np.linalg.norm(centres[:, None] - centres[None, :100], axis=-1)
    assert gaps[gaps > 0].min() == pytest.approx(2.5 * r, rel=1e-12)


def test_regular_ortho_fills_a_box():
    spheres = pack.regularOrtho(pack.inAlignedBox((0, 0, 0), (1, 1, 1)), radius=0.1, gap=0.0)
    # Yade's grid is arange(0.1, 0.9, 0.2) per axis: 0.9 (touching the face) is left out, 4^3
    assert len(spheres) == 64
    assert sorted({s.center[0] for s in spheres}) == pytest.approx([.1, .3, .5, .7])
