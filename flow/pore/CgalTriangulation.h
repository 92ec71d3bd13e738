#pragma once
// Private to flow/pore: the CGAL regular triangulation behind a PoreNetwork and the steps of its
// construction shared by the box (PoreNetwork.cpp) and periodic (PeriodicNetwork.cpp) variants.
// Only those two translation units include it (CGAL compiles slowly).
#include "flow/pore/PoreNetwork.h"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Regular_triangulation_3.h>
#include <CGAL/Triangulation_cell_base_with_info_3.h>
#include <CGAL/Triangulation_vertex_base_with_info_3.h>

#include <memory>
#include <vector>

namespace talus::flow::pore
{
namespace cgal
{
using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using VertexBase = CGAL::Triangulation_vertex_base_with_info_3<int, Kernel, CGAL::Regular_triangulation_vertex_base_3<Kernel>>;
using CellBase = CGAL::Triangulation_cell_base_with_info_3<int, Kernel, CGAL::Regular_triangulation_cell_base_3<Kernel>>;
using Tds = CGAL::Triangulation_data_structure_3<VertexBase, CellBase>;
using Regular = CGAL::Regular_triangulation_3<Kernel, Tds>;
#ifdef CGAL_LINKED_WITH_TBB
/// The same triangulation built by several threads at once (CGAL's concurrent insertion, each
/// thread locking the cells of a coarse grid it changes). Its containers cost more to use on one
/// thread: box networks on one thread keep Regular.
using ParallelTds = CGAL::Triangulation_data_structure_3<VertexBase, CellBase, CGAL::Parallel_tag>;
using ParallelRegular =
    CGAL::Regular_triangulation_3<Kernel, ParallelTds, CGAL::Spatial_lock_grid_3<CGAL::Tag_priority_blocking>>;
#endif
using Weighted = Kernel::Weighted_point_3;
using Point = Kernel::Point_3;
} // namespace cgal

struct Triangulation
{
  cgal::Regular rt;
  /// The finite cells by their info(), where point location can start its walk (locatePore).
  std::vector<cgal::Regular::Cell_handle> cells;
#ifdef CGAL_LINKED_WITH_TBB
  /// Box networks triangulated on several threads: the triangulation and its cells by info()
  /// (rt and cells are then empty).
  std::unique_ptr<cgal::ParallelRegular> parallelRt;
  std::vector<cgal::ParallelRegular::Cell_handle> parallelCells;
#endif
  /// A finite cell around each vertex (by the vertex's info(); -1: none), see cellAtVertex.
  std::vector<int> cellAtVertex;
  /// Periodic networks: for each finite cell (by its info()), the pore it is an image of (-1:
  /// none, a cell of the outer layer of images) and by how many cells it is shifted from it.
  /// Empty for box networks, whose cell info() is the pore index.
  std::vector<int> poreOf;
  std::vector<Vec3i> periodOf;
};

namespace detail
{
/// Checks shared by both variants (count, finite values, positive radii), naming the body id.
void checkSpheres(const std::vector<PoreSphere>& spheres);
/// The fictitious sphere standing for boundary k (Yade's addBoundingPlane), around the box
/// [lo, hi].
Vertex boundaryVertex(const std::array<Boundary, kBoundaries>& boundaries, int k, const Vec3& lo, const Vec3& hi);
/// Insert the vertices net.vertices[order[0]], net.vertices[order[1]], ...: with
/// InsertionOrder::Sorted the boundaries one by one, then all the spheres (and images) as one
/// range, which CGAL sorts along a space-filling curve and inserts each next to the previous one;
/// with InsertionOrder::Yade all one by one. The vertex info() is the index in net.vertices.
/// Fills net.hiddenSpheres with the real spheres the triangulation dropped;
/// @throws std::logic_error if a boundary vertex was dropped.
template <class Rt>
void insertVertices(PoreNetwork& net, Rt& rt, const std::vector<int>& order, InsertionOrder insertion);
/// The canonical order of the vertices for InsertionOrder::Sorted: boundaries first, then by
/// body id (an image after its sphere, by index), independent of CGAL's and of the input's
/// order; rank[i] is vertex i's place in it. Empty for InsertionOrder::Yade (CGAL's cell order).
/// Ranked once per network: the sorts below compared (fictitious, id, index) keys read from the
/// vertices, a visible part of a remesh (docs/flow.md, "Measurements behind the code").
std::vector<int> canonicalRanks(const std::vector<Vertex>& vertices, InsertionOrder insertion);
/// The facet vertices of throat t (the facet opposite t.facet in pore `poreVertices`): in the
/// cell's order when `rank` is empty (InsertionOrder::Yade), else in the canonical order, with
/// t.mirrorLocal (given in the cell's order) permuted alike, so that the throat formulas that
/// depend on the order of the facet vertices give the same value whatever order CGAL left them
/// in and whatever order the spheres were given in.
void setFacetVertices(Throat& t, const std::array<int, 4>& poreVertices, const std::vector<int>& rank);
/// Fill `cells` (by info()) and tri.cellAtVertex from the cells' info(), once they are numbered.
template <class Rt>
void indexCells(Triangulation& tri, const Rt& rt, std::vector<typename Rt::Cell_handle>& cells, std::size_t vertices);
/// Pore centre (CGAL's weighted circumcentre) of a finite cell, from its vertices in the
/// canonical order (`rank`, see canonicalRanks; the centres of pores touching a wall come from
/// the fictitious spheres' huge weights and carry round-off that depends on the order: up to
/// 6e-5 of the box on the 400-sphere reference; where two such centres nearly coincide the
/// throat length changes by percents), in the cell's order when `rank` is empty.
template <class Rt>
Vec3 weightedCentre(const Rt& rt, typename Rt::Cell_handle c, const std::vector<int>& rank);
} // namespace detail
} // namespace talus::flow::pore
