"""FEniCSx driver in 3D: one hexahedron, each Gauss point's stress path against a direct DEM run."""
import numpy as np
import pytest

import talus

pytestmark = pytest.mark.skipif(not talus.build_info()["features"].get("fenicsx", (False,))[0],
                                reason="this build has no FEniCSx (see `talus info`)")
STRAIN, N_STEPS = 0.004, 20


def test_one_hexahedron_equals_direct_dem(rve_file):
    """3D: a unit hexahedron (2x2x2 Gauss points), symmetry planes x, y, z = 0, top lowered, the
    faces x = 1 and y = 1 under 100 kPa; each Gauss point against its direct DEM replay."""
    from dolfinx import mesh as dmesh
    from mpi4py import MPI

    from talus.fem import MultiscaleRVEs
    from talus.fem.direct import replay
    from talus.fem.fenicsx import Dirichlet, MultiscaleSolver, Traction
    msh = dmesh.create_box(MPI.COMM_SELF, [np.zeros(3), np.ones(3)], [1, 1, 1], dmesh.CellType.hexahedron)
    rves = MultiscaleRVEs(str(rve_file[0]), numPoints=8, nSteps=N_STEPS)
    solver = MultiscaleSolver(
        msh, rves, tol=1e-5,
        dirichlet=[Dirichlet(lambda x: np.isclose(x[i], 0), i) for i in range(3)]
        + [Dirichlet(lambda x: x[2] > 0.5, 2, lambda t: -STRAIN * t)],
        tractions=[Traction(lambda x: x[0] > 0.5, lambda t: (-1e5, 0, 0)),
                   Traction(lambda x: x[1] > 0.5, lambda t: (0, -1e5, 0))])
    solver.step(0.5)
    solver.step(1.0)
    assert min(r.iterations for r in solver.history) >= 2
    for p in (0, 7):
        ours = np.array([r.stress[p] for r in solver.history])
        assert ours.shape == (len(solver.history), 3, 3)
        direct = replay(rve_file[0], [r.gradients[p] for r in solver.history], [r.nSteps for r in solver.history])[1]
        assert np.abs(ours - direct).max() < 1e-8 * np.abs(direct).max()
    assert solver.mesh.geometry.x[:, 2].max() == pytest.approx(1 - STRAIN, rel=1e-12)
