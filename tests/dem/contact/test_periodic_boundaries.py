"""Facets and boxes in periodic cells: spheres meet them through periodic images, with Yade's
contacts and forces; positions are never wrapped into the cell (as in Yade)."""
from pathlib import Path

import numpy as np
import pytest

from talus.dem import (Bo1_Facet_Aabb, Bo1_Sphere_Aabb, ForceResetter, Ig2_Facet_Sphere_ScGeom,
                       InsertionSortCollider, InteractionLoop, Ip2_FrictMat_FrictMat_FrictPhys,
                       Law2_ScGeom_FrictPhys_CundallStrack, NewtonIntegrator, Scene, facet, sphere)
from talus import twin

TWINS = Path(__file__).parents[1] / "yade_twins" / "periodic"  # the scripts Yade and Talus both run


@pytest.mark.skipif(not twin.yade_available(), reason="yade is not installed")
@pytest.mark.parametrize("shape", ["facet", "box"])
def test_spheres_on_facets_and_boxes_across_the_boundary_match_yade(shape):
    ours, theirs = (twin.run(TWINS / "periodic_boundaries_side_by_side.py", {"shape": shape}, who, timeout=600)
                    for who in ("talus", "yade"))
    mine, yade = np.array(ours["positions"]), np.array(theirs["positions"])
    assert np.abs(yade[-1] - yade[0]).max() > 0.1                 # they landed and rolled
    assert ours["contacts"] == theirs["contacts"] >= 2            # on the floor, through periodic images
    assert np.abs(mine - yade).max() < 1e-11                      # 20000 steps
    force = np.abs(theirs["force"]).max()
    assert force > 1 and np.abs(np.array(ours["force"]) - theirs["force"]).max() < 1e-8 * force


def sphere_on_a_facet(facet_width: float, bigger: bool = False) -> Scene:
    S = Scene()
    S.periodic = True
    S.cell.setBox(1, 1, 1)
    S.bodies.append(facet([(0.9, 0.4, 0.1), (0.9 + facet_width, 0.4, 0.1), (0.9, 0.6, 0.1)]))
    S.bodies.append(sphere((2.0, 0.45, 0.149), 0.05))     # two periods to the right of the facet's part in the cell
    S.engines = [ForceResetter(), InsertionSortCollider([Bo1_Sphere_Aabb(), Bo1_Facet_Aabb()], allowBiggerThanPeriod=bigger),
                 InteractionLoop([Ig2_Facet_Sphere_ScGeom()], [Ip2_FrictMat_FrictMat_FrictPhys()],
                                 [Law2_ScGeom_FrictPhys_CundallStrack()]),
                 NewtonIntegrator(gravity=(0, 0, -9.81))]
    S.dt = 1e-5
    return S


def test_a_facet_meets_a_sphere_through_its_image_and_positions_stay_unwrapped():
    S = sphere_on_a_facet(0.2)
    S.step()
    i = S.interactions[0, 1]
    assert i.isReal and i.cellDist == (-1, 0, 0)
    assert i.geom.penetrationDepth == pytest.approx(0.001)
    assert S.bodies[1].state.pos[0] == pytest.approx(2.0)     # not wrapped, as in Yade


def test_a_facet_wider_than_half_the_cell_needs_allowBiggerThanPeriod():
    with pytest.raises(RuntimeError, match=r"body 0 \(Facet\) spans more than half of the periodic cell along axis 0"):
        sphere_on_a_facet(0.6).step()
    S = sphere_on_a_facet(0.6, bigger=True)
    S.step()         # along x the sphere is taken where it is: 2.0 is beyond the facet's reach
    assert not any(i.isReal for i in S.interactions)
