// The box variant of the pore network (the periodic one is PeriodicNetwork.cpp): triangulation
// and topology, and the construction steps both variants share.
#include "flow/pore/CgalTriangulation.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <stdexcept>
#include <tuple>

namespace talus::flow::pore
{
namespace
{
using cgal::Point;
using cgal::Regular;
using cgal::Weighted;

/// Yade's FAR: the fictitious sphere of a boundary has radius FAR * (height of the box along y),
/// large enough for its surface to be flat to round-off over the sample.
constexpr double kFar = 50000;

std::string bodyName(std::int64_t id) { return "body " + std::to_string(id); }
} // namespace

namespace detail
{
void checkSpheres(const std::vector<PoreSphere>& spheres)
{
  if (spheres.size() < 4)
    throw std::invalid_argument("pore network: needs at least 4 spheres, got " + std::to_string(spheres.size()));
  for (const PoreSphere& s : spheres)
  {
    if (!s.pos.allFinite() || !std::isfinite(s.radius))
      throw std::invalid_argument("pore network: " + bodyName(s.id) + " has a non-finite position or radius");
    if (s.radius <= 0)
      throw std::invalid_argument("pore network: " + bodyName(s.id) + " has a non-positive radius");
  }
}

Vertex boundaryVertex(const std::array<Boundary, kBoundaries>& boundaries, int k, const Vec3& lo, const Vec3& hi)
{
  const Boundary& b = boundaries[static_cast<std::size_t>(k)];
  const double far = kFar * (hi.y() - lo.y());
  Vec3 c = 0.5 * (lo + hi);
  c[b.coordinate] = b.position - b.normal[b.coordinate] * far;
  Vertex v;
  v.pos = c;
  v.radius = far;
  v.fictitious = true;
  v.id = k;
  return v;
}

void insertVertices(PoreNetwork& net, Regular& rt, const std::vector<int>& order, InsertionOrder insertion)
{
  std::vector<char> inserted(net.vertices.size(), 0);
  std::vector<std::pair<Weighted, int>> range;
  range.reserve(order.size());
  for (const int i : order)
  {
    const Vertex& v = net.vertices[static_cast<std::size_t>(i)];
    inserted[static_cast<std::size_t>(i)] = 1;
    const Weighted w(Point(v.pos.x(), v.pos.y(), v.pos.z()), v.radius * v.radius);
    if (i >= kBoundaries && insertion == InsertionOrder::Sorted)
    {
      range.emplace_back(w, i);
      continue;
    }
    // the six boundaries first, one by one (they enclose the sample, the spheres' range goes
    // inside them); everything one by one in Yade's order
    const Regular::Vertex_handle h = rt.insert(w);
    if (h != Regular::Vertex_handle())
      h->info() = i;
  }
  rt.insert(range.begin(), range.end());
  // A sphere is hidden if it was not inserted or a later one removed it.
  std::vector<char> present(net.vertices.size(), 0);
  for (auto v = rt.finite_vertices_begin(); v != rt.finite_vertices_end(); ++v)
    present[static_cast<std::size_t>(v->info())] = 1;
  for (int k = 0; k < kBoundaries; ++k)
    if (inserted[static_cast<std::size_t>(k)] && !present[static_cast<std::size_t>(k)])
      throw std::logic_error("pore network: a boundary vertex was dropped by the triangulation");
  for (std::size_t i = kBoundaries; i < kBoundaries + net.nSpheres; ++i)
    if (!present[i])
      net.hiddenSpheres.push_back(net.vertices[i].id);
}

std::vector<int> canonicalRanks(const std::vector<Vertex>& vertices, InsertionOrder insertion)
{
  if (insertion == InsertionOrder::Yade)
    return {};
  std::vector<int> order(vertices.size());
  std::iota(order.begin(), order.end(), 0);
  const auto key = [&](int i) {
    const Vertex& v = vertices[static_cast<std::size_t>(i)];
    return std::tuple<bool, std::int64_t, int>{!v.fictitious, v.id, i};
  };
  std::sort(order.begin(), order.end(), [&](int a, int b) { return key(a) < key(b); });
  std::vector<int> rank(vertices.size());
  for (std::size_t r = 0; r < order.size(); ++r)
    rank[static_cast<std::size_t>(order[r])] = static_cast<int>(r);
  return rank;
}

void setFacetVertices(Throat& t, const std::array<int, 4>& poreVertices, const std::vector<int>& rank)
{
  constexpr int kFacetVertices[4][3] = {{1, 2, 3}, {0, 2, 3}, {0, 1, 3}, {0, 1, 2}};
  std::array<std::array<int, 2>, 3> facet{}; // (vertex, its local index in the other pore)
  for (std::size_t k = 0; k < 3; ++k)
    facet[k] = {poreVertices[static_cast<std::size_t>(kFacetVertices[t.facet][k])], t.mirrorLocal[k]};
  if (!rank.empty())
    std::sort(facet.begin(), facet.end(), [&](const auto& a, const auto& b) {
      return rank[static_cast<std::size_t>(a[0])] < rank[static_cast<std::size_t>(b[0])];
    });
  for (std::size_t k = 0; k < 3; ++k)
  {
    t.vertices[k] = facet[k][0];
    t.mirrorLocal[k] = facet[k][1];
  }
}

void indexCells(Triangulation& tri, std::size_t vertices)
{
  tri.cells.clear();
  tri.cellAtVertex.assign(vertices, -1);
  for (auto c = tri.rt.finite_cells_begin(); c != tri.rt.finite_cells_end(); ++c)
  {
    tri.cells.push_back(c);
    for (int k = 0; k < 4; ++k)
      tri.cellAtVertex[static_cast<std::size_t>(c->vertex(k)->info())] = c->info();
  }
}

Vec3 weightedCentre(const Regular& rt, Regular::Cell_handle c, const std::vector<int>& rank)
{
  std::array<Regular::Vertex_handle, 4> v{c->vertex(0), c->vertex(1), c->vertex(2), c->vertex(3)};
  if (!rank.empty())
    std::sort(v.begin(), v.end(), [&](Regular::Vertex_handle a, Regular::Vertex_handle b) {
      return rank[static_cast<std::size_t>(a->info())] < rank[static_cast<std::size_t>(b->info())];
    });
  const auto centre = rt.geom_traits().construct_weighted_circumcenter_3_object();
  const Point q = centre(v[0]->point(), v[1]->point(), v[2]->point(), v[3]->point());
  return {q.x(), q.y(), q.z()};
}
} // namespace detail

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

PoreNetwork triangulate(const std::vector<PoreSphere>& spheres, const std::array<Boundary, kBoundaries>& boundaries,
                        InsertionOrder insertion)
{
  detail::checkSpheres(spheres);
  for (const PoreSphere& s : spheres)
    for (const Boundary& b : boundaries)
      if ((s.pos[b.coordinate] - b.position) * b.normal[b.coordinate] < 0)
        throw std::invalid_argument("pore network: the centre of " + bodyName(s.id) + " is outside the boundary at " +
                                    "xyz"[b.coordinate] + " = " + std::to_string(b.position));
  for (int k = 0; k < kBoundaries; k += 2)
    if (!(boundaries[k + 1].position > boundaries[k].position))
      throw std::invalid_argument("pore network: empty box along " + std::string(1, "xyz"[k / 2]));

  PoreNetwork net;
  net.boundaries = boundaries;
  net.nSpheres = spheres.size();
  const Vec3 lo(boundaries[0].position, boundaries[2].position, boundaries[4].position);
  const Vec3 hi(boundaries[1].position, boundaries[3].position, boundaries[5].position);
  auto owner = std::make_shared<Triangulation>();
  Regular& rt = owner->rt;
  // Boundaries first, then the spheres (see insertVertices).
  for (int k = 0; k < kBoundaries; ++k)
    net.vertices.push_back(detail::boundaryVertex(boundaries, k, lo, hi));
  for (const PoreSphere& s : spheres)
    net.vertices.push_back(Vertex{s.pos, s.radius, false, s.id});
  std::vector<int> order(net.vertices.size());
  for (std::size_t i = 0; i < order.size(); ++i)
    order[i] = static_cast<int>(i);
  detail::insertVertices(net, rt, order, insertion);
  const std::vector<int> rank = detail::canonicalRanks(net.vertices, insertion);

  int n = 0;
  for (auto c = rt.finite_cells_begin(); c != rt.finite_cells_end(); ++c)
    c->info() = n++;
  detail::indexCells(*owner, net.vertices.size());
  net.pores.resize(static_cast<std::size_t>(n));
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
    p.centre = detail::weightedCentre(rt, c, rank);
  }
  net.throats.reserve(2 * net.pores.size()); // four facets per pore, each shared by two
  for (auto c = rt.finite_cells_begin(); c != rt.finite_cells_end(); ++c)
    for (int k = 0; k < 4; ++k)
    {
      const int other = net.pores[static_cast<std::size_t>(c->info())].neighbours[k];
      if (other < 0 || other < c->info())
        continue;
      Throat t;
      t.pores = {c->info(), other};
      t.facet = k;
      const int mirror = rt.mirror_index(c, k);
      for (int y = 0, m = 0; y < 4; ++y)
        if (y != k)
          t.mirrorLocal[static_cast<std::size_t>(m++)] = c->neighbor(k)->index(c->vertex(y));
      detail::setFacetVertices(t, net.pores[static_cast<std::size_t>(c->info())].vertices, rank);
      net.pores[static_cast<std::size_t>(c->info())].throats[k] = static_cast<int>(net.throats.size());
      net.pores[static_cast<std::size_t>(other)].throats[mirror] = static_cast<int>(net.throats.size());
      net.throats.push_back(t);
    }
  for (std::size_t pi = 0; pi < net.pores.size(); ++pi)
    for (int v : net.pores[pi].vertices)
      if (v < kBoundaries)
        net.boundaryPores[static_cast<std::size_t>(v)].push_back(static_cast<int>(pi));
  net.triangulation = std::move(owner);
  return net;
}

int cellAtVertex(const PoreNetwork& net, int vertex)
{
  if (!net.triangulation || vertex < 0 || static_cast<std::size_t>(vertex) >= net.triangulation->cellAtVertex.size())
    return -1;
  return net.triangulation->cellAtVertex[static_cast<std::size_t>(vertex)];
}

int locatePore(const PoreNetwork& net, const Vec3& x, Vec3i* period, int* near)
{
  if (period)
    *period = Vec3i::Zero();
  if (!net.triangulation)
    return -1;
  const Triangulation& tri = *net.triangulation;
  // CGAL walks from the hint to x: from an arbitrary cell that crosses the triangulation
  const auto walk = [&](const Vec3& y) {
    const bool hinted = near && *near >= 0 && static_cast<std::size_t>(*near) < tri.cells.size();
    const Regular::Cell_handle c =
        tri.rt.locate(Weighted(Point(y.x(), y.y(), y.z()), 0.0),
                      hinted ? tri.cells[static_cast<std::size_t>(*near)] : Regular::Cell_handle());
    if (near && !tri.rt.is_infinite(c))
      *near = c->info();
    return c;
  };
  if (!net.periodic)
  {
    const Regular::Cell_handle c = walk(x);
    return tri.rt.is_infinite(c) ? -1 : c->info();
  }
  // periodic: wrap x into the cell along the periodic axes, then undo the wrap in `period`
  Vec3i wrap = Vec3i::Zero();
  for (int a = 0; a < 3; ++a)
    if (net.periodicAxis(a))
      wrap[a] = static_cast<int>(std::floor(x[a] / net.cellSize[a]));
  const Regular::Cell_handle c = walk(x - net.shift(wrap));
  if (tri.rt.is_infinite(c))
    return -1;
  const auto i = static_cast<std::size_t>(c->info());
  if (period)
    *period = tri.periodOf[i] + wrap;
  return tri.poreOf[i];
}
} // namespace talus::flow::pore
