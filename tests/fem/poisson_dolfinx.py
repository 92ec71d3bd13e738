"""-lap(u) = -6 on the unit square with u = 1 + x^2 + 2y^2 on the boundary, P2 elements: the
discrete solution is exact, so the printed nodal error is round-off. The fem/ drivers build on
this stack (dolfinx, PETSc, MPI); run serial and under mpirun by tests/fem/test_toolchain.py."""
import numpy as np, ufl
from mpi4py import MPI
from petsc4py import PETSc
import dolfinx, dolfinx.fem.petsc
mesh = dolfinx.mesh.create_unit_square(MPI.COMM_WORLD, 8, 8)
V = dolfinx.fem.FunctionSpace(mesh, ("Lagrange", 2))
uD = dolfinx.fem.Function(V); uD.interpolate(lambda x: 1 + x[0]**2 + 2*x[1]**2)
fdim = mesh.topology.dim - 1
mesh.topology.create_connectivity(fdim, mesh.topology.dim)
facets = dolfinx.mesh.exterior_facet_indices(mesh.topology)
bc = dolfinx.fem.dirichletbc(uD, dolfinx.fem.locate_dofs_topological(V, fdim, facets))
u, v = ufl.TrialFunction(V), ufl.TestFunction(V)
f = dolfinx.fem.Constant(mesh, PETSc.ScalarType(-6))
a = ufl.dot(ufl.grad(u), ufl.grad(v)) * ufl.dx; L = f * v * ufl.dx
uh = dolfinx.fem.petsc.LinearProblem(a, L, bcs=[bc], petsc_options={"ksp_type": "preonly", "pc_type": "lu"}).solve()
err = np.max(np.abs(uh.x.array - uD.x.array))
err = MPI.COMM_WORLD.allreduce(err, op=MPI.MAX)
if MPI.COMM_WORLD.rank == 0:
    print("err", err, flush=True)
