// The two libraries the pore-flow solver is built on work as flow/ will use them:
// a CGAL regular triangulation of spheres (weights r^2) and a CHOLMOD Cholesky solve.
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Regular_triangulation_3.h>
#include <cholmod.h>

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

namespace
{
using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using Regular = CGAL::Regular_triangulation_3<Kernel>;
using Weighted = Kernel::Weighted_point_3;
using Point = Kernel::Point_3;
} // namespace

TEST(FlowToolchain, RegularTriangulationOfSpheres)
{
  // Five spheres: four at the corners of a tetrahedron and one in the middle, big enough to
  // appear; the regular triangulation then has four finite tetrahedra around the middle one.
  Regular rt;
  rt.insert(Weighted(Point(0, 0, 0), 0.25));
  rt.insert(Weighted(Point(1, 0, 0), 0.25));
  rt.insert(Weighted(Point(0, 1, 0), 0.25));
  rt.insert(Weighted(Point(0, 0, 1), 0.25));
  rt.insert(Weighted(Point(0.25, 0.25, 0.25), 0.04));
  EXPECT_TRUE(rt.is_valid());
  EXPECT_EQ(rt.number_of_vertices(), 5u);
  EXPECT_EQ(rt.number_of_finite_cells(), 4u);

  // A tiny sphere deep inside a big one is hidden: the regular triangulation drops it, which
  // the pore-flow code must detect and report.
  const Regular::Vertex_handle hidden = rt.insert(Weighted(Point(0.01, 0.0, 0.0), 1e-6));
  EXPECT_EQ(rt.number_of_vertices(), 5u);
  EXPECT_EQ(hidden, Regular::Vertex_handle());
}

TEST(FlowToolchain, CholmodSolvesTheOneDimensionalPoissonProblem)
{
  // -u'' = 1 on (0,1), u(0) = u(1) = 0, n interior nodes: the finite-difference solution equals
  // the exact one, x(1-x)/2, at the nodes.
  const int n = 50;
  const double h = 1.0 / (n + 1);
  cholmod_common common;
  cholmod_start(&common);
  cholmod_triplet* t = cholmod_allocate_triplet(n, n, 2 * n, 1 /* lower half stored */, CHOLMOD_REAL, &common);
  auto* ti = static_cast<int*>(t->i);
  auto* tj = static_cast<int*>(t->j);
  auto* tx = static_cast<double*>(t->x);
  for (int k = 0; k < n; ++k)
  {
    ti[t->nnz] = k, tj[t->nnz] = k, tx[t->nnz] = 2.0 / (h * h), ++t->nnz;
    if (k + 1 < n)
      ti[t->nnz] = k + 1, tj[t->nnz] = k, tx[t->nnz] = -1.0 / (h * h), ++t->nnz;
  }
  cholmod_sparse* a = cholmod_triplet_to_sparse(t, 0, &common);
  cholmod_dense* b = cholmod_ones(n, 1, CHOLMOD_REAL, &common);
  common.supernodal = CHOLMOD_SUPERNODAL;
  cholmod_factor* l = cholmod_analyze(a, &common);
  ASSERT_TRUE(cholmod_factorize(a, l, &common));
  EXPECT_EQ(common.status, CHOLMOD_OK);
  cholmod_dense* x = cholmod_solve(CHOLMOD_A, l, b, &common);
  const auto* u = static_cast<const double*>(x->x);
  for (int k = 0; k < n; ++k)
  {
    const double xk = (k + 1) * h;
    EXPECT_NEAR(u[k], 0.5 * xk * (1 - xk), 1e-12);
  }
  cholmod_free_dense(&x, &common);
  cholmod_free_dense(&b, &common);
  cholmod_free_factor(&l, &common);
  cholmod_free_sparse(&a, &common);
  cholmod_free_triplet(&t, &common);
  cholmod_finish(&common);
}
