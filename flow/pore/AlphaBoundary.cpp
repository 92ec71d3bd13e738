#include "flow/pore/AlphaBoundary.h"

#include <CGAL/Alpha_shape_3.h>
#include <CGAL/Alpha_shape_cell_base_3.h>
#include <CGAL/Alpha_shape_vertex_base_3.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Regular_triangulation_3.h>

#include <Eigen/Dense>

#include <algorithm>
#include <cmath>
#include <set>
#include <stdexcept>
#include <string>

namespace talus::flow::pore
{
namespace
{
using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using VertexBase = CGAL::Alpha_shape_vertex_base_3<Kernel, CGAL::Regular_triangulation_vertex_base_3<Kernel>>;
using CellBase = CGAL::Alpha_shape_cell_base_3<Kernel, CGAL::Regular_triangulation_cell_base_3<Kernel>>;
using Tds = CGAL::Triangulation_data_structure_3<VertexBase, CellBase>;
using Regular = CGAL::Regular_triangulation_3<Kernel, Tds>;
using AlphaShape = CGAL::Alpha_shape_3<Regular>;

Vec3 position(const AlphaShape::Vertex_handle& v)
{
  const auto& p = v->point().point();
  return {p.x(), p.y(), p.z()};
}

/// The point of equal power to the weighted points a, b, c in their plane, and that power.
std::pair<Vec3, double> facetOrthocentre(const Vec3& a, double wa, const Vec3& b, double wb, const Vec3& c, double wc)
{
  Eigen::Matrix3d m;
  m.row(0) = 2 * (b - a);
  m.row(1) = 2 * (c - a);
  m.row(2) = (b - a).cross(c - a);
  const Eigen::Vector3d rhs(b.squaredNorm() - a.squaredNorm() - (wb - wa), c.squaredNorm() - a.squaredNorm() - (wc - wa),
                            m.row(2).dot(a));
  const Vec3 x = m.fullPivLu().solve(rhs);
  return {x, (x - a).squaredNorm() - wa};
}
} // namespace

AlphaVertices alphaVertices(const std::vector<PoreSphere>& spheres, double alphaBound)
{
  if (!std::isfinite(alphaBound) || alphaBound < 0)
    throw std::invalid_argument("FlowEngine.alphaBound must be >= 0 for the alpha-shape boundary (0: CGAL's optimal "
                                "alpha), got " + std::to_string(alphaBound));
  std::vector<Kernel::Weighted_point_3> points;
  points.reserve(spheres.size());
  for (const PoreSphere& s : spheres)
    points.emplace_back(Kernel::Point_3(s.pos.x(), s.pos.y(), s.pos.z()), s.radius * s.radius);
  Regular rt(points.begin(), points.end());
  AlphaShape shape(rt); // Yade's mode, REGULARIZED
  AlphaVertices out;
  out.alpha = alphaBound > 0 ? alphaBound : CGAL::to_double(*shape.find_optimal_alpha(1));
  shape.set_alpha(out.alpha);

  std::vector<AlphaShape::Facet> facets;
  shape.get_alpha_shape_facets(std::back_inserter(facets), AlphaShape::REGULAR);
  std::set<AlphaShape::Cell_handle> used; // one alpha vertex per outer cell
  for (AlphaShape::Facet f : facets)
  {
    // Yade gives an alpha vertex only to the facets CGAL lists from their interior cell: about
    // half of them, which half depending on where CGAL's cells lie in memory (in Talus it
    // changed with the number of threads); every facet gets one here, a superset of Yade's
    if (shape.classify(f.first) != AlphaShape::INTERIOR)
      f = shape.mirror_facet(f);
    const AlphaShape::Cell_handle outer = f.first->neighbor(f.second);
    PoreSphere v;
    v.id = -1 - static_cast<std::int64_t>(out.vertices.size());
    if (shape.is_infinite(outer))
    {
      // the sphere of squared radius alpha orthogonal to the facet's spheres, outside
      Vec3 x[3];
      double w[3];
      for (int k = 0; k < 3; ++k)
      {
        const auto vh = f.first->vertex((f.second + 1 + k) % 4);
        x[k] = position(vh);
        w[k] = vh->point().weight();
      }
      const auto [c0, power] = facetOrthocentre(x[0], w[0], x[1], w[1], x[2], w[2]);
      Vec3 n = (x[1] - x[0]).cross(x[2] - x[0]).normalized();
      if (n.dot(position(f.first->vertex(f.second)) - x[0]) > 0)
        n = -n;
      v.pos = c0 + std::sqrt(std::max(out.alpha - power, 0.0)) * n;
      v.radius = std::sqrt(out.alpha);
    }
    else
    {
      if (!used.insert(outer).second)
        continue;
      const auto c = shape.dual(outer); // the outer cell's orthogonal sphere
      v.pos = Vec3(c.x(), c.y(), c.z());
      const auto& p0 = outer->vertex(0)->point();
      v.radius = std::sqrt(std::max(CGAL::squared_distance(c, p0.point()) - p0.weight(), 0.0));
    }
    out.vertices.push_back(v);
  }
  // An alpha vertex is orthogonal to the spheres it sits on: a degenerate regular triangulation,
  // which CGAL resolves by insertion order. A fixed order (by position) keeps the pores
  // independent of the order CGAL lists the facets in.
  std::sort(out.vertices.begin(), out.vertices.end(), [](const PoreSphere& a, const PoreSphere& b) {
    return std::lexicographical_compare(a.pos.data(), a.pos.data() + 3, b.pos.data(), b.pos.data() + 3);
  });
  for (std::size_t k = 0; k < out.vertices.size(); ++k)
    out.vertices[k].id = -1 - static_cast<std::int64_t>(k);
  return out;
}

AlphaBoundary alphaBoundary(const PoreNetwork& net, double alpha)
{
  AlphaBoundary out;
  out.alpha = alpha;
  out.exteriorPores.assign(net.pores.size(), 0);
  out.boundaryVertices.assign(net.vertices.size(), 0);
  for (std::size_t i = 0; i < net.pores.size(); ++i)
  {
    bool alphaPore = false;
    for (int v : net.pores[i].vertices)
    {
      const Vertex& vertex = net.vertices[static_cast<std::size_t>(v)];
      out.exteriorPores[i] = out.exteriorPores[i] || vertex.fictitious || vertex.alpha;
      alphaPore = alphaPore || vertex.alpha;
    }
    if (alphaPore)
      for (int v : net.pores[i].vertices)
        if (!net.vertices[static_cast<std::size_t>(v)].alpha && !net.vertices[static_cast<std::size_t>(v)].fictitious)
          out.boundaryVertices[static_cast<std::size_t>(v)] = 1;
  }
  return out;
}
} // namespace talus::flow::pore

namespace talus::flow::pore
{
PoreNetwork triangulateAlphaShape(const std::vector<PoreSphere>& spheres, double alphaBound, AlphaBoundary& boundary)
{
  const AlphaVertices extra = alphaVertices(spheres, alphaBound);
  std::vector<PoreSphere> all = spheres;
  all.insert(all.end(), extra.vertices.begin(), extra.vertices.end());
  // Yade's order, one by one on one thread: the degenerate configuration of the alpha vertices
  // (see alphaVertices) is resolved by insertion order (a threaded insertion changed a few pores
  // from run to run)
  PoreNetwork net = triangulate(all, boundingBoxBoundaries(all), InsertionOrder::Yade);
  for (std::size_t v = kBoundaries + spheres.size(); v < net.vertices.size(); ++v)
    net.vertices[v].alpha = true;
  net.nSpheres = spheres.size();
  // alpha vertices hidden by others are no loss; a sphere of the packing hidden is reported
  net.hiddenSpheres.erase(std::remove_if(net.hiddenSpheres.begin(), net.hiddenSpheres.end(),
                                         [](std::int64_t id) { return id < 0; }),
                          net.hiddenSpheres.end());
  boundary = alphaBoundary(net, extra.alpha);
  return net;
}
} // namespace talus::flow::pore
