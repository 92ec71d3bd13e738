"""The default pore network is Yade's: the spheres enter CGAL one by one in the input's order, as
in Yade's FlowEngine, so every cell has Yade's vertices in Yade's order, and the formulas that
depend on that order (the weighted centres of the pores touching a wall, computed from the
fictitious spheres' huge weights; Yade's sphere-edge overlap S0) give Yade's numbers. Each
location starts near the new sphere (Talus) instead of at the infinite cell (Yade): the same
triangulation. The sorted insertion (yadeInsertionOrder=False) gives the same cells with their
vertices in another order, hence other round-off in the wall pores' centres."""
import json
import shutil
import subprocess

import numpy as np
import pytest

from talus.dem.packing.pack import SpherePack
from talus.flow import FlowEngine, HiddenSphereWarning

YADE = shutil.which("yade")
# Yade 2023.02a's FlowEngine (pore_yade_reference.py) on the 10 000-sphere cloud of
# cloud(10000): inlet flux (boundary 2)
YADE_FLUX_10K = -0.0025880279888367656


def cloud(num):
    """The bench clouds of cases/pore/flow_bench_pore.py: x y z r rows."""
    side = (num / 1000) ** (1 / 3)
    sp = SpherePack()
    sp.makeCloud((0, 0, 0), (side, side, side), rMean=0.035, rRelFuzz=0.3, num=num, seed=num)
    assert len(sp) == num
    return np.array([[*c, r] for c, r in sp])


def flow_on(spheres, **kw):
    flow = FlowEngine(bndCondIsPressure=[0, 0, 1, 1, 0, 0], bndCondValue=[0, 0, 1, 0, 0, 0], **kw)
    flow.triangulate(spheres[:, :3].copy(), spheres[:, 3].copy(), np.arange(6, 6 + len(spheres)))
    flow.solve()
    return flow


def test_default_permeability_is_yades_on_a_10000_sphere_cloud():
    spheres = cloud(10000)
    flux = flow_on(spheres).getBoundaryFlux(2)
    # measured 1.1e-13 (CHOLMOD on another pore numbering: round-off)
    assert abs(flux / YADE_FLUX_10K - 1) < 1e-6
    # the sorted insertion, the default before: 2.4e-6 (2.1e-4 at 100 000 spheres)
    assert abs(flow_on(spheres, yadeInsertionOrder=False).getBoundaryFlux(2) / YADE_FLUX_10K - 1) > 1e-6


@pytest.mark.skipif(YADE is None, reason="yade not installed")
def test_every_cell_has_yades_vertices_in_yades_order_live(tmp_path):
    spheres = cloud(2000)
    packing, out = tmp_path / "packing.txt", tmp_path / "yade.json"
    np.savetxt(packing, spheres)
    subprocess.run([YADE, "-n", "-x", "pore_yade_reference.py", str(packing), str(out)],
                   cwd=str(__import__("pathlib").Path(__file__).parent), check=True, capture_output=True, timeout=300)
    ref = json.load(open(out))
    flow = flow_on(spheres)
    ours = {frozenset(int(v) for v in row): tuple(int(v) for v in row) for row in flow.cellVertexIds}
    assert len(ours) == ref["nCells"]
    assert all(ours[frozenset(c["vertices"])] == tuple(c["vertices"]) for c in ref["cells"])
    assert flow.getBoundaryFlux(2) == pytest.approx(ref["boundaryFlux"][2], rel=1e-12)
    sorted_order = flow_on(spheres, yadeInsertionOrder=False).cellVertexIds
    assert sum(tuple(int(v) for v in row) == ours[frozenset(int(v) for v in row)] for row in sorted_order) < 0.5 * len(ours)


def test_spheres_hidden_by_a_later_one_leave_the_same_pores_as_the_sorted_insertion():
    # small spheres first, then a large one over them: inserting it removes (hides) them, whose
    # handles the next locations must no longer start from
    spheres = cloud(1000)
    centre = spheres[500, :3]
    near = np.linalg.norm(spheres[:, :3] - centre, axis=1) < 0.12
    spheres[near, 3] *= 0.2
    spheres = np.vstack([spheres, [*centre, 0.12]])
    with pytest.warns(HiddenSphereWarning):
        yade = flow_on(spheres)
    with pytest.warns(HiddenSphereWarning):
        ranged = flow_on(spheres, yadeInsertionOrder=False)
    assert sorted(yade._flow.hiddenSpheres()) == sorted(ranged._flow.hiddenSpheres())
    assert len(yade._flow.hiddenSpheres()) > 1
    assert {frozenset(map(int, r)) for r in yade.cellVertexIds} == {frozenset(map(int, r)) for r in ranged.cellVertexIds}
    assert yade.getBoundaryFlux(2) == pytest.approx(ranged.getBoundaryFlux(2), rel=1e-3)


def test_concurrent_insertion_needs_the_sorted_order():
    with pytest.raises(ValueError, match="yadeInsertionOrder=False"):
        flow_on(cloud(1000), concurrentTriangulation=True)
