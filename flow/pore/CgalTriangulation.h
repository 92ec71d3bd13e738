#pragma once
// Private to flow/pore: the CGAL regular triangulation behind a PoreNetwork and the steps of its
// construction shared by the box (PoreNetwork.cpp) and periodic (PeriodicNetwork.cpp) variants.
// Only those two translation units include it (CGAL compiles slowly).
#include "flow/pore/PoreNetwork.h"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Regular_triangulation_3.h>
#include <CGAL/Triangulation_cell_base_with_info_3.h>
#include <CGAL/Triangulation_vertex_base_with_info_3.h>

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
using Weighted = Kernel::Weighted_point_3;
using Point = Kernel::Point_3;
} // namespace cgal

struct Triangulation
{
  cgal::Regular rt;
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
/// Insert the vertices net.vertices[order[0]], net.vertices[order[1]], ... one by one, as Yade
/// does; the vertex info() is the index in net.vertices. Fills net.hiddenSpheres with the real
/// spheres the triangulation dropped; @throws std::logic_error if a boundary vertex was dropped.
void insertVertices(PoreNetwork& net, cgal::Regular& rt, const std::vector<int>& order);
/// Pore centre (CGAL's weighted circumcentre) of a finite cell.
Vec3 weightedCentre(const cgal::Regular& rt, cgal::Regular::Cell_handle c);
} // namespace detail
} // namespace talus::flow::pore
