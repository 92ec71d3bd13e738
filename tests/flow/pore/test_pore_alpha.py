"""Alpha-shape boundary (FlowEngine.alphaBound) against Yade 2023.02a on the packing of Yade's
examples/FluidCouplingPFV/alphaShape.py (reference: pore_yade_alpha.py).

Both triangulate the spheres with "alpha vertices" (spheres orthogonal to the outer spheres, over
the alpha shape's boundary facets) and impose alphaBoundValue in the pores they touch. Yade gives
a vertex only to the facets CGAL lists from their interior cell (about half, chosen by where
CGAL's cells lie in memory); Talus to every boundary facet: its 100 alpha vertices include all 50
of Yade's, its boundary pores Yade's. Measured: Talus's 422 free pores all among Yade's 439;
their pressures within 0.016 of Yade's (imposed 1); flux out of the imposed pore 0.078636
against Yade's 0.078402 (+0.30 %).
"""
import json
import math
import os

import numpy as np
import pytest

from talus.flow.periodic import PeriodicFlowEngine
from talus.flow.pore import FlowEngine

HERE = os.path.dirname(__file__)
REFERENCE = os.path.join(HERE, "..", "data", "pore_yade_alpha.json")


@pytest.fixture(scope="module")
def yade():
    with open(REFERENCE) as f:
        return json.load(f)


def _engine(spheres, **kw):
    sp = np.asarray(spheres)
    flow = FlowEngine(permeabilityFactor=-1e-1, alphaBound=0.3, alphaBoundValue=0, fixedAlpha=False, **kw)
    flow.imposePressure((0, 0, 0), 1)
    flow.triangulate(sp[:, 1:4], sp[:, 4], sp[:, 0].astype(int))
    flow._flow.solve()
    return flow


@pytest.fixture(scope="module")
def talus(yade):
    return _engine(yade["spheres"])


def _yade_free_cells(yade):
    """Yade's cells of free pressure, and the imposed point's cell (pressure 1), by vertex ids."""
    return {tuple(sorted(c["vertices"])): c for c in yade["cells"] if not c["imposed"] or c["pressure"] == 1.0}


def test_free_pores_near_yades(yade, talus):
    _, exterior, _ = talus.alphaShape()
    free = {tuple(sorted(talus.getVertices(i))) for i in range(talus.nCells()) if not exterior[i]}
    yade_free = set(_yade_free_cells(yade))
    assert (len(yade_free), len(free)) == (440, 423) and free <= yade_free
    # every pore touching a box or an alpha vertex is outside, every other one inside
    assert all(exterior[i] == (min(talus.getVertices(i)) < 6) for i in range(talus.nCells()))


def test_alpha_vertices_and_spheres_on_the_shape(yade, talus):
    real = {int(s[0]) for s in yade["spheres"]}
    yade_side = {v for c in yade["cells"] for v in c["vertices"]
                 if v in real and any(w not in real for w in c["vertices"])}
    alpha, _, on_shape = talus.alphaShape()
    assert alpha == 0.3
    assert (len(on_shape), len(yade_side)) == (102, 99) and yade_side <= set(on_shape)
    # Yade's file flags its alpha vertices (ids after the spheres), never a real sphere
    flags = {int(r[0]): r[5] for r in yade["vertices"]}
    assert all(flags[i] == 0 for i in real) and sum(flags.values()) == len(flags) - len(real) == 50
    ours = talus._flow.vertexSpheres()[6 + len(real):]
    theirs = np.array([r[1:5] for r in yade["vertices"] if int(r[0]) not in real])
    # (Yade's file has six significant digits)
    alike = sum(np.min(np.linalg.norm(theirs - v, axis=1)) < 1e-5 * (1 + np.linalg.norm(v)) for v in ours)
    assert (len(ours), alike) == (100, 50)


def test_pressures_and_flux_near_yade(yade, talus):
    _, exterior, _ = talus.alphaShape()
    cell = {tuple(sorted(talus.getVertices(i))): i for i in range(talus.nCells()) if not exterior[i]}
    diff = [abs(talus.getCellPressure(cell[k]) - c["pressure"]) for k, c in _yade_free_cells(yade).items() if k in cell]
    assert 0.005 < max(diff) < 0.02  # measured 0.0157
    assert all(talus.getCellPressure(i) == 0 for i in range(talus.nCells()) if exterior[i])
    flux = talus.getCellFlux(0)
    assert flux == pytest.approx(yade["originFlux"], rel=5e-3)  # measured +0.30 %
    assert flux != yade["originFlux"]
    # the box is no boundary: no force on it
    assert all(talus.boundaryForce(k) == (0, 0, 0) for k in range(6))


def test_boundary_value_and_optimal_alpha(yade):
    flow = _engine(yade["spheres"])
    flow.alphaBoundValue = 0.25
    flow._flow.solve()
    _, exterior, _ = flow.alphaShape()
    assert all(flow.getCellPressure(i) == 0.25 for i in range(flow.nCells()) if exterior[i])
    flow.alphaBound = 0  # CGAL's smallest alpha keeping every sphere in one solid
    with pytest.raises(ValueError, match="alphaBound changed since the triangulation"):
        flow._flow.solve()
    sp = np.asarray(yade["spheres"])
    flow.triangulate(sp[:, 1:4], sp[:, 4], sp[:, 0].astype(int))
    flow._flow.solve()
    alpha, exterior, on_shape = flow.alphaShape()
    assert 0 < alpha < 0.3 and 0 < exterior.sum() < flow.nCells() and on_shape
    flow.alphaBound = -2  # Yade's meaning of any negative value: the box's boundaries again
    flow.triangulate(sp[:, 1:4], sp[:, 4], sp[:, 0].astype(int))
    flow._flow.solve()
    assert flow.alphaShape()[1].size == 0 and len(flow._flow.vertexSpheres()) == 6 + len(sp)


def test_print_vertices_and_vtk(yade, talus, tmp_path):
    path = tmp_path / "vertices.txt"
    talus.printVertices(str(path))
    rows = np.loadtxt(path, skiprows=1)
    assert open(path).readline().split() == ["id", "x", "y", "z", "r", "alpha", "fictious"]
    assert len(rows) == len(yade["spheres"]) + 100 and rows[:, 5].sum() == 100 and rows[:, 0].min() == -100
    pores_file = talus.saveVtk(str(tmp_path / "alpha"), withBoundaries=False)[0]
    assert "alpha" in open(pores_file).read()


def test_bad_input_refused(yade):
    sp = np.asarray(yade["spheres"])
    with pytest.raises(ValueError, match="fixedAlpha"):
        FlowEngine(fixedAlpha=True)
    with pytest.raises(ValueError, match="alphaBound"):
        FlowEngine(alphaBound=math.nan)
    periodic = PeriodicFlowEngine(gradP=(0, 1, 0), duplicateThreshold=0.1, alphaBound=0.3)
    with pytest.raises(ValueError, match="alphaBound"):
        periodic.triangulate(sp[:, 1:4] + 1.2, sp[:, 4], sp[:, 0].astype(int), cellSize=(2.4, 2.4, 2.4))
