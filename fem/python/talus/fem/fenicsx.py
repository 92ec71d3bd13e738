"""FEniCSx (dolfinx 0.5) driver of the FEM x DEM multiscale procedure (seed chapter 13.3).

The unknown of a load step is the displacement increment du from the last converged
configuration (updated Lagrangian, as the seed's procedure): Newton-Raphson on

    R(du) = int_Omega sigma(grad du) : eps(v) dx - int_Gamma t . v ds = 0,

with sigma and the tangent D the RVEs' Cauchy stress and contact-stiffness operator at the
quadrature points (dolfinx quadrature spaces), K = int eps(v) : D : eps(du) dx. Every Newton
iteration re-runs every RVE from its committed state with the current grad du (the trial state);
a converged step commits the RVEs and moves the mesh by du. A step that does not converge (or
whose RVE runs fail) is rolled back and cut in half, down to ``minStepFraction``.

Plane strain in 2D (the RVE is deformed with zero out-of-plane components), full 3D in 3D.
Voigt order: 2D xx, yy, xy; 3D xx, yy, zz, yz, xz, xy, with engineering shear strains.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Callable, Sequence

import numpy as np

from talus.fem.newton import NewtonDivergence, NewtonLoadStepping, StepReport

__all__ = ["Dirichlet", "MultiscaleSolver", "NewtonDivergence", "StepReport", "Traction", "gaussPointCoordinates",
           "shearStrain"]


@dataclass
class Dirichlet:
    """Prescribed displacement of component ``component`` (0, 1, 2) on the boundary nodes where
    ``where(x)`` is true (x: coordinates (3, n) of the current configuration); ``value(t)`` is
    the total displacement at load factor t (0..1), applied incrementally."""
    where: Callable[[np.ndarray], np.ndarray]
    component: int
    value: Callable[[float], float] = lambda t: 0.0


@dataclass
class Traction:
    """Surface traction vector ``value(t)`` (Pa, current configuration) on the boundary facets
    where ``where(x)`` is true."""
    where: Callable[[np.ndarray], np.ndarray]
    value: Callable[[float], Sequence[float]]


def shearStrain(grads: np.ndarray) -> np.ndarray:
    """The deviatoric (shear) strain magnitude sqrt(2/3 e':e') of displacement gradients
    (n, d, d), e' the deviator of sym(grad u); in 2D with eps_zz = 0 (plane strain)."""
    d = grads.shape[-1]
    eps = np.zeros((len(grads), 3, 3))            # plane strain: eps_zz = 0, but it has a deviator
    eps[:, :d, :d] = 0.5 * (grads + grads.transpose(0, 2, 1))
    dev = eps - np.trace(eps, axis1=1, axis2=2)[:, None, None] * np.eye(3) / 3
    return np.sqrt(2 / 3 * np.einsum("pij,pij->p", dev, dev))


def gaussPointCoordinates(mesh, quadratureDegree: int = 2) -> np.ndarray:
    """The coordinates (numPoints, d) of the quadrature points of the mesh's local cells, numbered
    as :class:`MultiscaleSolver` numbers the RVEs (cell c, point q -> c * nq + q): to give each
    Gauss point its RVE by position (a heterogeneous sample) before the solver exists."""
    import basix
    import ufl
    from dolfinx import fem
    points, _ = basix.make_quadrature(basix.cell.string_to_type(mesh.topology.cell_type.name), quadratureDegree)
    cells = np.arange(mesh.topology.index_map(mesh.topology.dim).size_local, dtype=np.int32)
    return fem.Expression(ufl.SpatialCoordinate(mesh), points).eval(cells).reshape(-1, mesh.geometry.dim)


def _voigt_pairs(d: int):
    return [(0, 0), (1, 1), (0, 1)] if d == 2 else [(0, 0), (1, 1), (2, 2), (1, 2), (0, 2), (0, 1)]


class MultiscaleSolver(NewtonLoadStepping):
    """Newton-Raphson for a mesh whose quadrature points carry RVEs (the rules of
    :class:`talus.fem.newton.NewtonLoadStepping`: tolerance, stall, backtracking, step cutting).

    ``rves``: a :class:`talus.fem.MultiscaleRVEs` with one RVE per quadrature point, numbered
    cell by cell (cell c, point q -> c * nq + q) over the mesh's local cells. ``degree``: the
    Lagrange degree of the displacement; ``quadratureDegree``: the quadrature rule (2 gives 2x2
    points on quadrilaterals)."""

    def __init__(self, mesh, rves, dirichlet: Sequence[Dirichlet] = (), tractions: Sequence[Traction] = (),
                 degree: int = 1, quadratureDegree: int = 2, tol: float = 1e-6, maxIter: int = 50,
                 minStepFraction: float = 1 / 64, stall: int = 8, backtrack: int = 4):
        import basix
        import ufl
        from dolfinx import fem
        from petsc4py import PETSc
        super().__init__(rves, tol=tol, maxIter=maxIter, minStepFraction=minStepFraction, stall=stall,
                         backtrack=backtrack)
        self.mesh = mesh
        self.dirichlet, self.tractions = list(dirichlet), list(tractions)
        d = self.d = mesh.geometry.dim
        tdim = mesh.topology.dim
        self.V = fem.VectorFunctionSpace(mesh, ("CG", degree))
        cell = basix.cell.string_to_type(mesh.topology.cell_type.name)
        self.points, _ = basix.make_quadrature(cell, quadratureDegree)
        nq = len(self.points)
        self.cells = np.arange(mesh.topology.index_map(tdim).size_local, dtype=np.int32)
        if rves.numPoints != len(self.cells) * nq:
            raise ValueError(f"MultiscaleSolver: the mesh has {len(self.cells)} cells x {nq} quadrature points = "
                             f"{len(self.cells) * nq} Gauss points, but {rves.numPoints} RVEs were given")
        v = self.v = 3 if d == 2 else 6
        qe = dict(degree=quadratureDegree, quad_scheme="default")
        self.S = fem.FunctionSpace(mesh, ufl.VectorElement("Quadrature", mesh.ufl_cell(), dim=v, **qe))
        self.T = fem.FunctionSpace(mesh, ufl.TensorElement("Quadrature", mesh.ufl_cell(), shape=(v, v), **qe))
        self.sig, self.D = fem.Function(self.S), fem.Function(self.T)
        self.qdofs = self.S.dofmap.list.array.reshape(len(self.cells), nq)   # blocks of the points, cell by cell
        self.du, self.ddu = fem.Function(self.V), fem.Function(self.V)
        self.u = fem.Function(self.V, name="displacement")
        w, dtrial = ufl.TestFunction(self.V), ufl.TrialFunction(self.V)
        dx = ufl.Measure("dx", domain=mesh, metadata={"quadrature_degree": quadratureDegree, "quadrature_scheme": "default"})

        def eps(z):
            e = ufl.sym(ufl.grad(z))
            return ufl.as_vector([(1 if i == j else 2) * e[i, j] for i, j in _voigt_pairs(d)])

        # Tractions: one facet tag per traction, each with a Constant vector updated per step.
        fdim = tdim - 1
        mesh.topology.create_connectivity(fdim, tdim)
        from dolfinx import mesh as dmesh
        facets, tags = [], []
        self._tractionValues = []
        for k, tr in enumerate(self.tractions):
            f = dmesh.locate_entities_boundary(mesh, fdim, tr.where)
            facets.append(f)
            tags.append(np.full(len(f), k + 1, dtype=np.int32))
            self._tractionValues.append(fem.Constant(mesh, PETSc.ScalarType((0.0,) * d)))
        external = 0
        if self.tractions:
            allf = np.concatenate(facets)
            order = np.argsort(allf)
            mt = dmesh.meshtags(mesh, fdim, allf[order].astype(np.int32), np.concatenate(tags)[order])
            ds = ufl.Measure("ds", domain=mesh, subdomain_data=mt)
            for k, value in enumerate(self._tractionValues):
                external += ufl.dot(value, w) * ds(k + 1)
        self.residualForm = fem.form(ufl.inner(self.sig, eps(w)) * dx - external if self.tractions
                                     else ufl.inner(self.sig, eps(w)) * dx)
        self.internalForm = fem.form(ufl.inner(self.sig, eps(w)) * dx)
        self.jacobianForm = fem.form(ufl.inner(ufl.dot(self.D, eps(dtrial)), eps(w)) * dx)
        self.gradExpr = fem.Expression(ufl.grad(self.du), self.points)

    # -- pieces -------------------------------------------------------------------------------
    def gaussGradients(self) -> np.ndarray:
        """grad du at every Gauss point, (numPoints, d, d), numbered cell by cell."""
        return self.gradExpr.eval(self.cells).reshape(-1, self.d, self.d)

    def _bcs(self, t0: float, t1: float):
        """Dirichlet conditions on du for the increment t0 -> t1 (current configuration)."""
        from dolfinx import fem
        bcs = []
        for bc in self.dirichlet:
            Vi, _ = self.V.sub(bc.component).collapse()
            dofs = fem.locate_dofs_geometrical((self.V.sub(bc.component), Vi), bc.where)
            value = fem.Function(Vi)
            value.x.array[:] = bc.value(t1) - bc.value(t0)
            bcs.append(fem.dirichletbc(value, dofs, self.V.sub(bc.component)))
        return bcs

    def _setStressAndTangent(self, stress: np.ndarray, tangent: np.ndarray):
        pairs = _voigt_pairs(self.d)
        sv = np.stack([stress[:, i, j] for i, j in pairs], axis=1)
        blocks = self.qdofs.ravel()
        self.sig.x.array.reshape(-1, self.v)[blocks] = sv
        self.D.x.array.reshape(-1, self.v * self.v)[blocks] = tangent.reshape(len(tangent), -1)

    def _assemble_vector(self, form, bcs=()):
        from dolfinx.fem.petsc import assemble_vector, set_bc
        from petsc4py import PETSc
        b = assemble_vector(form)
        b.ghostUpdate(addv=PETSc.InsertMode.ADD, mode=PETSc.ScatterMode.REVERSE)
        if bcs:
            set_bc(b, bcs, scale=0.0)   # no residual at prescribed dofs (reactions)
        return b

    # -- the hooks of NewtonLoadStepping ------------------------------------------------------
    def _start(self, t0: float, t1: float):
        from dolfinx import fem
        from petsc4py import PETSc
        for k, tr in enumerate(self.tractions):
            self._tractionValues[k].value[:] = np.asarray(tr.value(t1), dtype=float)
        bcs = self._bcs(t0, t1)
        self.du.x.array[:] = 0
        fem.set_bc(self.du.vector, bcs)
        self.du.x.scatter_forward()
        self._zero = self._bcs(t0, t0)      # the same dofs, homogeneous: for the Newton corrections
        self._ksp = PETSc.KSP().create(self.mesh.comm)
        self._ksp.setType("preonly")
        self._ksp.getPC().setType("lu")

    def _relativeResidual(self) -> float:
        self._r = self._assemble_vector(self.residualForm, self._zero)
        scale = self._assemble_vector(self.internalForm).norm()
        return self._r.norm() / max(scale, 1e-300)

    def _correct(self):
        from dolfinx.fem.petsc import assemble_matrix
        A = assemble_matrix(self.jacobianForm, bcs=self._zero)
        A.assemble()
        self._ksp.setOperators(A)
        self._r.scale(-1)
        self._ksp.solve(self._r, self.ddu.vector)
        self.ddu.x.scatter_forward()
        self.du.x.array[:] += self.ddu.x.array

    def _retract(self, fraction: float):
        self.du.x.array[:] -= fraction * self.ddu.x.array

    def _accept(self):
        self.u.x.array[:] += self.du.x.array
        self._move_mesh()

    def _move_mesh(self):
        """Updated Lagrangian: the converged configuration becomes the reference of the next step."""
        x = self.mesh.geometry.x
        gdofs = self.mesh.geometry.dofmap
        vdofs = self.V.dofmap
        bs = self.V.dofmap.bs
        moved = np.zeros(len(x), dtype=bool)
        values = self.du.x.array.reshape(-1, bs)
        for c in range(self.mesh.topology.index_map(self.mesh.topology.dim).size_local
                       + self.mesh.topology.index_map(self.mesh.topology.dim).num_ghosts):
            g, v = gdofs.links(c), vdofs.cell_dofs(c)
            if len(g) != len(v):
                raise NotImplementedError("moving the mesh needs the displacement degree to equal the mesh degree")
            fresh = ~moved[g]
            x[g[fresh], :self.d] += values[v[fresh]]
            moved[g] = True

    def reactions(self, where: Callable[[np.ndarray], np.ndarray], component: int) -> float:
        """Sum of the internal nodal forces of component `component` over the nodes where
        `where(x)` holds: the reaction force on that boundary (per unit thickness in 2D)."""
        from dolfinx import fem
        Vi, _ = self.V.sub(component).collapse()
        dofs = fem.locate_dofs_geometrical((self.V.sub(component), Vi), where)[0]
        f = self._assemble_vector(self.internalForm)
        return float(np.sum(f.array[dofs]))

    def fields(self) -> dict:
        """Per-cell averages over the Gauss points, for output: stress (d x d), void ratio, and
        the deviatoric (shear) strain magnitude of the last converged increment,
        sqrt(2/3 e':e') with e' the deviator of sym(grad du)."""
        nq = len(self.points)
        stress, _ = self.rves.getStressAndTangent()
        e = self.rves.getVoidRatio()
        g = self.history[-1].gradients if self.history else np.zeros((len(stress), self.d, self.d))
        shear = shearStrain(g)
        cells = len(self.cells)
        return {"stress": stress.reshape(cells, nq, self.d, self.d).mean(axis=1),
                "voidRatio": e.reshape(cells, nq).mean(axis=1),
                "shearStrain": shear.reshape(cells, nq).mean(axis=1)}

    def write(self, xdmf, t: float):
        """Write the displacement (total since the start) and cellwise stress components, void
        ratio and shear strain increment to an open dolfinx.io.XDMFFile (ParaView)."""
        from dolfinx import fem
        Q = fem.FunctionSpace(self.mesh, ("DG", 0))
        f = self.fields()
        xdmf.write_function(self.u, t)
        names = [("sxx", (0, 0)), ("syy", (1, 1)), ("sxy", (0, 1))] + (
            [("szz", (2, 2)), ("syz", (1, 2)), ("sxz", (0, 2))] if self.d == 3 else [])
        values = [(n, f["stress"][:, i, j]) for n, (i, j) in names]
        for name, v in values + [("voidRatio", f["voidRatio"]), ("shearStrain", f["shearStrain"])]:
            q = fem.Function(Q, name=name)
            q.x.array[:len(v)] = v
            xdmf.write_function(q, t)
