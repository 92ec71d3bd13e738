#include "flow/pore/AlphaBoundary.h"

#include <CGAL/Alpha_shape_3.h>
#include <CGAL/Alpha_shape_cell_base_3.h>
#include <CGAL/Alpha_shape_vertex_base_3.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Regular_triangulation_3.h>
#include <CGAL/Triangulation_vertex_base_with_info_3.h>

#include <cmath>
#include <stdexcept>
#include <string>
#include <utility>

namespace talus::flow::pore
{
namespace
{
using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using InfoBase = CGAL::Triangulation_vertex_base_with_info_3<int, Kernel, CGAL::Regular_triangulation_vertex_base_3<Kernel>>;
using VertexBase = CGAL::Alpha_shape_vertex_base_3<Kernel, InfoBase>;
using CellBase = CGAL::Alpha_shape_cell_base_3<Kernel, CGAL::Regular_triangulation_cell_base_3<Kernel>>;
using Tds = CGAL::Triangulation_data_structure_3<VertexBase, CellBase>;
using Regular = CGAL::Regular_triangulation_3<Kernel, Tds>;
using AlphaShape = CGAL::Alpha_shape_3<Regular>;
} // namespace

AlphaBoundary alphaBoundary(const PoreNetwork& net, double alphaBound)
{
  if (net.periodic)
    throw std::invalid_argument("FlowEngine.alphaBound: the alpha-shape boundary needs a box network, not a periodic one");
  if (!std::isfinite(alphaBound) || alphaBound < 0)
    throw std::invalid_argument("FlowEngine.alphaBound must be >= 0 for the alpha-shape boundary (0: CGAL's optimal "
                                "alpha), got " + std::to_string(alphaBound));
  // the spheres alone (no box vertices): the alpha shape is theirs
  std::vector<std::pair<Kernel::Weighted_point_3, int>> points;
  points.reserve(net.nSpheres);
  for (std::size_t v = kBoundaries; v < kBoundaries + net.nSpheres; ++v)
  {
    const Vertex& s = net.vertices[v];
    points.emplace_back(Kernel::Weighted_point_3(Kernel::Point_3(s.pos.x(), s.pos.y(), s.pos.z()), s.radius * s.radius),
                        static_cast<int>(v));
  }
  Regular rt(points.begin(), points.end());
  AlphaShape shape(rt, 0, AlphaShape::GENERAL);
  AlphaBoundary out;
  out.alpha = alphaBound > 0 ? alphaBound : CGAL::to_double(*shape.find_optimal_alpha(1));
  shape.set_alpha(out.alpha);

  std::vector<AlphaShape::Vertex_handle> handle(net.vertices.size());
  for (auto v = shape.finite_vertices_begin(); v != shape.finite_vertices_end(); ++v)
    handle[static_cast<std::size_t>(v->info())] = v;
  out.boundaryVertices.assign(net.vertices.size(), 0);
  for (auto v = shape.finite_vertices_begin(); v != shape.finite_vertices_end(); ++v)
  {
    const auto type = shape.classify(AlphaShape::Vertex_handle(v));
    if (type == AlphaShape::REGULAR || type == AlphaShape::SINGULAR)
      out.boundaryVertices[static_cast<std::size_t>(v->info())] = 1;
  }
  out.exteriorPores.assign(net.pores.size(), 1);
  for (std::size_t i = 0; i < net.pores.size(); ++i)
  {
    const Pore& pore = net.pores[i];
    if (pore.nFictitious > 0)
      continue;
    AlphaShape::Vertex_handle v[4];
    bool present = true;
    for (int k = 0; k < 4; ++k)
    {
      v[k] = handle[static_cast<std::size_t>(pore.vertices[static_cast<std::size_t>(k)])];
      present = present && v[k] != AlphaShape::Vertex_handle();
    }
    AlphaShape::Cell_handle c;
    // a pore of the network is a cell of the spheres' triangulation unless a box vertex cut it
    if (present && shape.is_cell(v[0], v[1], v[2], v[3], c) && shape.classify(c) == AlphaShape::INTERIOR)
      out.exteriorPores[i] = 0;
  }
  return out;
}
} // namespace talus::flow::pore
