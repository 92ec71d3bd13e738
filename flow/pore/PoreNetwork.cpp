// The only translation unit that includes CGAL (it compiles slowly): triangulation and topology.
#include "flow/pore/PoreNetwork.h"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Regular_triangulation_3.h>
#include <CGAL/Triangulation_cell_base_with_info_3.h>
#include <CGAL/Triangulation_vertex_base_with_info_3.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace talus::flow::pore
{
namespace
{
using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using VertexBase = CGAL::Triangulation_vertex_base_with_info_3<int, Kernel, CGAL::Regular_triangulation_vertex_base_3<Kernel>>;
using CellBase = CGAL::Triangulation_cell_base_with_info_3<int, Kernel, CGAL::Regular_triangulation_cell_base_3<Kernel>>;
using Tds = CGAL::Triangulation_data_structure_3<VertexBase, CellBase>;
using Regular = CGAL::Regular_triangulation_3<Kernel, Tds>;
using Weighted = Kernel::Weighted_point_3;
using Point = Kernel::Point_3;

/// Yade's FAR: the fictitious sphere of a boundary has radius FAR * (height of the box along y),
/// large enough for its surface to be flat to round-off over the sample.
constexpr double kFar = 50000;

std::string bodyName(std::int64_t id) { return "body " + std::to_string(id); }
} // namespace

struct Triangulation
{
  Regular rt;
};

std::array<Boundary, kBoundaries> boundingBoxBoundaries(const std::vector<PoreSphere>& spheres)
{
  Vec3 lo = Vec3::Constant(std::numeric_limits<double>::max());
  Vec3 hi = -lo;
  for (const PoreSphere& s : spheres)
  {
    lo = lo.cwiseMin(s.pos - Vec3::Constant(s.radius));
    hi = hi.cwiseMax(s.pos + Vec3::Constant(s.radius));
  }
  std::array<Boundary, kBoundaries> b{};
  for (int k = 0; k < kBoundaries; ++k)
  {
    const int c = k / 2;
    const bool isMin = k % 2 == 0;
    b[k].coordinate = c;
    b[k].position = isMin ? lo[c] : hi[c];
    b[k].normal = Vec3::Zero();
    b[k].normal[c] = isMin ? 1.0 : -1.0;
  }
  return b;
}

PoreNetwork triangulate(const std::vector<PoreSphere>& spheres, const std::array<Boundary, kBoundaries>& boundaries)
{
  if (spheres.size() < 4)
    throw std::invalid_argument("pore network: needs at least 4 spheres, got " + std::to_string(spheres.size()));
  for (const PoreSphere& s : spheres)
  {
    if (!s.pos.allFinite() || !std::isfinite(s.radius))
      throw std::invalid_argument("pore network: " + bodyName(s.id) + " has a non-finite position or radius");
    if (s.radius <= 0)
      throw std::invalid_argument("pore network: " + bodyName(s.id) + " has a non-positive radius");
    for (const Boundary& b : boundaries)
      if ((s.pos[b.coordinate] - b.position) * b.normal[b.coordinate] < 0)
        throw std::invalid_argument("pore network: the centre of " + bodyName(s.id) + " is outside the boundary at " +
                                    "xyz"[b.coordinate] + " = " + std::to_string(b.position));
  }
  for (int k = 0; k < kBoundaries; k += 2)
    if (!(boundaries[k + 1].position > boundaries[k].position))
      throw std::invalid_argument("pore network: empty box along " + std::string(1, "xyz"[k / 2]));

  PoreNetwork net;
  net.boundaries = boundaries;
  const Vec3 lo(boundaries[0].position, boundaries[2].position, boundaries[4].position);
  const Vec3 hi(boundaries[1].position, boundaries[3].position, boundaries[5].position);
  const Vec3 mid = 0.5 * (lo + hi);
  const double far = kFar * (hi.y() - lo.y());

  auto owner = std::make_shared<Triangulation>();
  Regular& rt = owner->rt;
  // Boundaries first, then the spheres in the caller's order, one by one as Yade does (the
  // triangulation is unique anyway unless points are degenerate).
  for (int k = 0; k < kBoundaries; ++k)
  {
    const Boundary& b = boundaries[k];
    Vec3 c = mid;
    c[b.coordinate] = b.position - b.normal[b.coordinate] * far;
    Vertex v;
    v.pos = c;
    v.radius = far;
    v.fictitious = true;
    v.id = k;
    net.vertices.push_back(v);
  }
  for (const PoreSphere& s : spheres)
    net.vertices.push_back(Vertex{s.pos, s.radius, false, s.id});
  for (std::size_t i = 0; i < net.vertices.size(); ++i)
  {
    const Vertex& v = net.vertices[i];
    const Regular::Vertex_handle h = rt.insert(Weighted(Point(v.pos.x(), v.pos.y(), v.pos.z()), v.radius * v.radius));
    if (h != Regular::Vertex_handle())
      h->info() = static_cast<int>(i);
  }
  // A sphere is hidden if it was not inserted or a later one removed it.
  std::vector<char> present(net.vertices.size(), 0);
  for (auto v = rt.finite_vertices_begin(); v != rt.finite_vertices_end(); ++v)
    present[static_cast<std::size_t>(v->info())] = 1;
  for (int k = 0; k < kBoundaries; ++k)
    if (!present[static_cast<std::size_t>(k)])
      throw std::logic_error("pore network: a boundary vertex was dropped by the triangulation");
  for (std::size_t i = kBoundaries; i < net.vertices.size(); ++i)
    if (!present[i])
      net.hiddenSpheres.push_back(net.vertices[i].id);

  int n = 0;
  for (auto c = rt.finite_cells_begin(); c != rt.finite_cells_end(); ++c)
    c->info() = n++;
  net.pores.resize(static_cast<std::size_t>(n));
  const auto centre = rt.geom_traits().construct_weighted_circumcenter_3_object();
  for (auto c = rt.finite_cells_begin(); c != rt.finite_cells_end(); ++c)
  {
    Pore& p = net.pores[static_cast<std::size_t>(c->info())];
    for (int k = 0; k < 4; ++k)
    {
      p.vertices[k] = c->vertex(k)->info();
      p.neighbours[k] = rt.is_infinite(c->neighbor(k)) ? -1 : c->neighbor(k)->info();
      p.throats[k] = -1;
      p.nFictitious += net.vertices[static_cast<std::size_t>(p.vertices[k])].fictitious ? 1 : 0;
    }
    const Point q = centre(c->vertex(0)->point(), c->vertex(1)->point(), c->vertex(2)->point(), c->vertex(3)->point());
    p.centre = Vec3(q.x(), q.y(), q.z());
    for (int k = 0; k < 4; ++k)
    {
      const int other = p.neighbours[k];
      if (other < 0 || other < c->info())
        continue;
      Throat t;
      t.pores = {c->info(), other};
      t.facet = k;
      p.throats[k] = static_cast<int>(net.throats.size());
      net.throats.push_back(t);
    }
  }
  // The mirror side of each throat.
  for (std::size_t ti = 0; ti < net.throats.size(); ++ti)
  {
    const Throat& t = net.throats[ti];
    Pore& q = net.pores[static_cast<std::size_t>(t.pores[1])];
    for (int k = 0; k < 4; ++k)
      if (q.neighbours[k] == t.pores[0])
        q.throats[k] = static_cast<int>(ti);
  }
  for (std::size_t pi = 0; pi < net.pores.size(); ++pi)
    for (int v : net.pores[pi].vertices)
      if (v < kBoundaries)
        net.boundaryPores[static_cast<std::size_t>(v)].push_back(static_cast<int>(pi));
  net.triangulation = std::move(owner);
  return net;
}

int locatePore(const PoreNetwork& net, const Vec3& x)
{
  if (!net.triangulation)
    return -1;
  const Regular& rt = net.triangulation->rt;
  const Regular::Cell_handle c = rt.locate(Weighted(Point(x.x(), x.y(), x.z()), 0.0));
  return rt.is_infinite(c) ? -1 : c->info();
}
} // namespace talus::flow::pore
