// The box variant of the pore network (the periodic one is PeriodicNetwork.cpp): triangulation
// and topology, and the construction steps both variants share.
#include "flow/pore/CgalTriangulation.h"
#include "flow/pore/CurveOrder.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <stdexcept>
#include <tuple>

#ifdef CGAL_LINKED_WITH_TBB
#include <tbb/parallel_sort.h>
#include <tbb/task_arena.h>
#endif
#ifdef _OPENMP
#include <omp.h>
#endif

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

/// Pores and throats of the finite cells `cells` (pore i is cells[i], whose info() is i), pore
/// i's vertex k being its cell's vertex local[i][k] (the cell's own order when `local` is empty).
template <class Rt>
void buildPores(PoreNetwork& net, const Rt& rt, const std::vector<typename Rt::Cell_handle>& cells,
                const std::vector<std::array<int, 4>>& local, const std::vector<int>& rank)
{
  net.pores.resize(cells.size());
  for (std::size_t i = 0; i < cells.size(); ++i)
  {
    const typename Rt::Cell_handle c = cells[i];
    Pore& p = net.pores[i];
    for (int k = 0; k < 4; ++k)
    {
      const int y = local.empty() ? k : local[i][static_cast<std::size_t>(k)];
      p.vertices[k] = c->vertex(y)->info();
      p.neighbours[k] = rt.is_infinite(c->neighbor(y)) ? -1 : c->neighbor(y)->info();
      p.throats[k] = -1;
      p.nFictitious += net.vertices[static_cast<std::size_t>(p.vertices[k])].fictitious ? 1 : 0;
    }
    p.centre = detail::weightedCentre(rt, c, rank);
  }
  net.throats.reserve(2 * net.pores.size()); // four facets per pore, each shared by two
  // the neighbours are anywhere in the array: fetched a few pores ahead instead of waited for
  constexpr std::size_t kAhead = 4;
  for (std::size_t i = 0; i < net.pores.size(); ++i)
  {
    if (i + kAhead < net.pores.size())
      for (const int other : net.pores[i + kAhead].neighbours)
        if (other > static_cast<int>(i + kAhead))
          __builtin_prefetch(&net.pores[static_cast<std::size_t>(other)]);
    for (int k = 0; k < 4; ++k)
    {
      const std::array<int, 4>& vertices = net.pores[i].vertices;
      const int other = net.pores[i].neighbours[k];
      if (other < 0 || other < static_cast<int>(i))
        continue;
      Pore& q = net.pores[static_cast<std::size_t>(other)];
      Throat t;
      t.pores = {static_cast<int>(i), other};
      t.facet = k;
      // where each facet vertex is in the other pore; the one left is opposite the facet there
      int mirror = 0 + 1 + 2 + 3;
      for (int y = 0, m = 0; y < 4; ++y)
        if (y != k)
        {
          const auto in = static_cast<int>(std::find(q.vertices.begin(), q.vertices.end(), vertices[y]) - q.vertices.begin());
          t.mirrorLocal[static_cast<std::size_t>(m++)] = in;
          mirror -= in;
        }
      detail::setFacetVertices(t, vertices, rank);
      net.pores[i].throats[k] = static_cast<int>(net.throats.size());
      q.throats[mirror] = static_cast<int>(net.throats.size());
      net.throats.push_back(t);
    }
  }
}

/// Where CGAL starts the point location of each sphere inserted one by one (Yade's order): the
/// last vertex inserted in the sphere's bucket of nested grids over the spheres (the finest about
/// one sphere a bucket, each next one half as fine, the last one bucket), the finest non-empty
/// one. Yade starts every location from the infinite cell, a walk across the sample; the
/// triangulation does not depend on where the walk starts (each new cell takes the vertices of
/// the cell it replaces, in their order), so the cells and their vertex orders stay Yade's.
template <class Rt>
class NearbyVertices
{
public:
  using Vertex_handle = typename Rt::Vertex_handle;

  NearbyVertices(const std::vector<Vertex>& vertices, const std::vector<int>& order)
  {
    std::size_t spheres = 0;
    for (const int i : order)
      if (const Vertex& v = vertices[static_cast<std::size_t>(i)]; !v.fictitious)
      {
        lo_ = lo_.cwiseMin(v.pos);
        hi_ = hi_.cwiseMax(v.pos);
        ++spheres;
      }
    for (int side = std::max(1, static_cast<int>(std::cbrt(static_cast<double>(spheres))));; side = (side + 1) / 2)
    {
      sides_.push_back(side);
      grids_.emplace_back(static_cast<std::size_t>(side) * static_cast<std::size_t>(side) * static_cast<std::size_t>(side));
      if (side == 1)
        break;
    }
    buckets_.resize(sides_.size());
  }

  /// A cell to start locating x from (none before the first sphere); x's buckets are kept for
  /// inserted().
  typename Rt::Cell_handle near(const Vec3& x)
  {
    const Eigen::Array3d unit = unitOf(x);
    Vertex_handle found;
    for (std::size_t l = 0; l < sides_.size(); ++l)
    {
      buckets_[l] = bucket(unit, l);
      if (found == Vertex_handle())
        found = grids_[l][buckets_[l]];
    }
    return found == Vertex_handle() ? typename Rt::Cell_handle() : found->cell();
  }

  /// The vertex near() would start from now (none: a null handle), without keeping x's buckets:
  /// a look ahead, for prefetching.
  [[nodiscard]] Vertex_handle peek(const Vec3& x) const
  {
    const Eigen::Array3d unit = unitOf(x);
    for (std::size_t l = 0; l < sides_.size(); ++l)
      if (const Vertex_handle v = grids_[l][bucket(unit, l)]; v != Vertex_handle())
        return v;
    return Vertex_handle();
  }

  /// v was inserted at the x of the last near().
  void inserted(Vertex_handle v)
  {
    for (std::size_t l = 0; l < sides_.size(); ++l)
      grids_[l][buckets_[l]] = v;
  }

  /// An insertion removed vertices (it hid them): their handles are no start any more.
  void forget()
  {
    for (std::vector<Vertex_handle>& g : grids_)
      std::fill(g.begin(), g.end(), Vertex_handle());
  }

private:
  [[nodiscard]] Eigen::Array3d unitOf(const Vec3& x) const
  {
    return ((x - lo_).array() / (hi_ - lo_).array().max(1e-300)).max(0.0).min(1.0);
  }
  /// x's bucket (from unitOf) in grid l.
  [[nodiscard]] std::size_t bucket(const Eigen::Array3d& unit, std::size_t l) const
  {
    const auto side = static_cast<std::size_t>(sides_[l]);
    std::size_t b = 0;
    for (int a = 0; a < 3; ++a)
      b = b * side + std::min(side - 1, static_cast<std::size_t>(unit[a] * static_cast<double>(side)));
    return b;
  }

  Vec3 lo_ = Vec3::Constant(std::numeric_limits<double>::max());
  Vec3 hi_ = Vec3::Constant(std::numeric_limits<double>::lowest());
  std::vector<int> sides_;
  std::vector<std::vector<Vertex_handle>> grids_;
  std::vector<std::size_t> buckets_;
};

/// The finite cell (its info()) holding y, -1 outside; CGAL walks from the cell `near` points
/// to (if given and valid; from an arbitrary cell otherwise, across the triangulation) and
/// leaves the cell found there.
template <class Rt>
int walkTo(const Rt& rt, const std::vector<typename Rt::Cell_handle>& cells, const Vec3& y, int* near)
{
  const bool hinted = near && *near >= 0 && static_cast<std::size_t>(*near) < cells.size();
  const typename Rt::Cell_handle c = rt.locate(Weighted(Point(y.x(), y.y(), y.z()), 0.0),
                                               hinted ? cells[static_cast<std::size_t>(*near)] : typename Rt::Cell_handle());
  if (rt.is_infinite(c))
    return -1;
  if (near)
    *near = c->info();
  return c->info();
}

#ifdef CGAL_LINKED_WITH_TBB
using cgal::ParallelRegular;

/// Cells per axis of the grid whose cells the threads of a parallel insertion lock (CGAL's
/// meshes use 50).
constexpr int kLockGridCells = 50;

/// How many threads the caller asked for (OpenMP's setting, which the rest of the pore flow
/// follows).
int callerThreads()
{
#ifdef _OPENMP
  return omp_get_max_threads();
#else
  return 1;
#endif
}

/// Numbers (info()) the finite cells of a triangulation built by several threads, whose cell
/// order depends on how the threads met: along a Morton curve through the centroid of each
/// cell's spheres (neighbouring pores stay close in memory), ties broken by the vertices'
/// canonical ranks (a cell is its four vertices). Returns for each pore the cell's local index
/// of each of its vertices, in rank order, the last two swapped when that is an odd permutation
/// of the cell's (a pore stays positively oriented, as CGAL's cells are). Pores, throats and
/// solver then come out the same whatever order the threads left.
std::vector<std::array<int, 4>> numberCellsCanonically(ParallelRegular& rt, const PoreNetwork& net,
                                                       const std::vector<int>& rank, const Vec3& lo, const Vec3& hi)
{
  struct Entry
  {
    std::uint64_t morton = 0;
    std::array<int, 4> ranks{};
    std::array<int, 4> local{};
    ParallelRegular::Cell_handle cell;
  };
  std::vector<Entry> entries;
  entries.reserve(rt.number_of_finite_cells());
  for (auto c = rt.finite_cells_begin(); c != rt.finite_cells_end(); ++c)
  {
    Entry e;
    e.cell = c;
    e.local = {0, 1, 2, 3};
    const auto rankOf = [&](int y) { return rank[static_cast<std::size_t>(c->vertex(y)->info())]; };
    std::sort(e.local.begin(), e.local.end(), [&](int a, int b) { return rankOf(a) < rankOf(b); });
    int inversions = 0;
    for (std::size_t a = 0; a < 4; ++a)
      for (std::size_t b = a + 1; b < 4; ++b)
        inversions += e.local[a] > e.local[b] ? 1 : 0;
    Vec3 centroid = Vec3::Zero();
    int spheres = 0;
    for (std::size_t k = 0; k < 4; ++k)
    {
      e.ranks[k] = rankOf(e.local[k]);
      const Vertex& v = net.vertices[static_cast<std::size_t>(c->vertex(e.local[k])->info())];
      if (!v.fictitious)
      {
        centroid += v.pos;
        ++spheres;
      }
    }
    if (inversions % 2 != 0)
      std::swap(e.local[2], e.local[3]);
    e.morton = mortonKey(spheres > 0 ? Vec3(centroid / spheres) : lo, lo, hi);
    entries.push_back(e);
  }
  tbb::parallel_sort(entries.begin(), entries.end(), [](const Entry& a, const Entry& b) {
    return std::tie(a.morton, a.ranks) < std::tie(b.morton, b.ranks);
  });
  std::vector<std::array<int, 4>> local(entries.size());
  for (std::size_t i = 0; i < entries.size(); ++i)
  {
    entries[i].cell->info() = static_cast<int>(i);
    local[i] = entries[i].local;
  }
  return local;
}
#endif
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

/// Ask the processor to fetch what a CGAL handle points to, if it points to anything.
template <class Handle>
void prefetchHandle(const Handle& h)
{
  if (h != Handle())
    __builtin_prefetch(&*h);
}

template <class Rt>
void insertVertices(PoreNetwork& net, Rt& rt, const std::vector<int>& order, InsertionOrder insertion)
{
  std::vector<char> inserted(net.vertices.size(), 0);
  std::vector<std::pair<Weighted, int>> range;
  range.reserve(order.size());
  NearbyVertices<Rt> nearby(net.vertices, insertion == InsertionOrder::Yade ? order : std::vector<int>{});
  // The start vertex of the insertion `d` spheres after the j-th (a null handle for none).
  const auto startAhead = [&](std::size_t j, std::size_t d) {
    const std::size_t k = j + d;
    if (insertion != InsertionOrder::Yade || k >= order.size())
      return typename Rt::Vertex_handle();
    const Vertex& w = net.vertices[static_cast<std::size_t>(order[k])];
    return w.fictitious ? typename Rt::Vertex_handle() : nearby.peek(w.pos);
  };
  for (std::size_t j = 0; j < order.size(); ++j)
  {
    const int i = order[j];
    // One by one in Yade's order, each sphere lands away from the last one, in cells and
    // vertices out of the caches: the memory of the next insertions is fetched while this one
    // runs, their start vertex four spheres ahead, its cell two ahead (the vertex read by then),
    // that cell's neighbours and vertices one ahead, where the location and the conflict zone
    // begin. Reads only: the triangulation is the same.
    // (While the triangulation has fewer than three dimensions a cell's last neighbours and
    // vertices are null handles: every handle is tested before its address is taken.)
    prefetchHandle(startAhead(j, 4));
    if (const auto v = startAhead(j, 2); v != typename Rt::Vertex_handle())
      prefetchHandle(v->cell());
    if (const auto v = startAhead(j, 1); v != typename Rt::Vertex_handle() && v->cell() != typename Rt::Cell_handle())
      for (int k = 0; k < 4; ++k)
      {
        prefetchHandle(v->cell()->neighbor(k));
        prefetchHandle(v->cell()->vertex(k));
      }
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
    const std::size_t before = rt.number_of_vertices();
    const typename Rt::Vertex_handle h = rt.insert(w, v.fictitious ? typename Rt::Cell_handle() : nearby.near(v.pos));
    if (h == typename Rt::Vertex_handle())
      continue;
    h->info() = i;
    if (rt.number_of_vertices() < before + 1)
      nearby.forget();
    if (!v.fictitious)
      nearby.inserted(h);
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

template <class Rt>
void indexCells(Triangulation& tri, const Rt& rt, std::vector<typename Rt::Cell_handle>& cells, std::size_t vertices)
{
  cells.resize(rt.number_of_finite_cells());
  for (auto c = rt.finite_cells_begin(); c != rt.finite_cells_end(); ++c)
    cells[static_cast<std::size_t>(c->info())] = c;
  tri.cellAtVertex.assign(vertices, -1);
  for (const typename Rt::Cell_handle c : cells)
    for (int k = 0; k < 4; ++k)
      tri.cellAtVertex[static_cast<std::size_t>(c->vertex(k)->info())] = c->info();
}

template <class Rt>
Vec3 weightedCentre(const Rt& rt, typename Rt::Cell_handle c, const std::vector<int>& rank)
{
  using Vertex_handle = typename Rt::Vertex_handle;
  std::array<Vertex_handle, 4> v{c->vertex(0), c->vertex(1), c->vertex(2), c->vertex(3)};
  if (!rank.empty())
    std::sort(v.begin(), v.end(), [&](Vertex_handle a, Vertex_handle b) {
      return rank[static_cast<std::size_t>(a->info())] < rank[static_cast<std::size_t>(b->info())];
    });
  const auto centre = rt.geom_traits().construct_weighted_circumcenter_3_object();
  const Point q = centre(v[0]->point(), v[1]->point(), v[2]->point(), v[3]->point());
  return {q.x(), q.y(), q.z()};
}

// the periodic variant's (PeriodicNetwork.cpp)
template void insertVertices(PoreNetwork&, Regular&, const std::vector<int>&, InsertionOrder);
template void indexCells(Triangulation&, const Regular&, std::vector<Regular::Cell_handle>&, std::size_t);
template Vec3 weightedCentre(const Regular&, Regular::Cell_handle, const std::vector<int>&);
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
                        InsertionOrder insertion, bool concurrent)
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
  // Boundaries first, then the spheres (see insertVertices).
  for (int k = 0; k < kBoundaries; ++k)
    net.vertices.push_back(detail::boundaryVertex(boundaries, k, lo, hi));
  for (const PoreSphere& s : spheres)
    net.vertices.push_back(Vertex{s.pos, s.radius, false, s.id});
  std::vector<int> order(net.vertices.size());
  for (std::size_t i = 0; i < order.size(); ++i)
    order[i] = static_cast<int>(i);
#ifdef CGAL_LINKED_WITH_TBB
  if (const int threads = callerThreads(); concurrent && insertion == InsertionOrder::Sorted && threads > 1)
  {
    ParallelRegular::Lock_data_structure locks(CGAL::Bbox_3(lo.x(), lo.y(), lo.z(), hi.x(), hi.y(), hi.z()),
                                                     kLockGridCells);
    owner->parallelRt = std::make_unique<ParallelRegular>(cgal::Kernel(), &locks);
    ParallelRegular& rt = *owner->parallelRt;
    tbb::task_arena(threads).execute([&] { detail::insertVertices(net, rt, order, insertion); });
    rt.set_lock_data_structure(nullptr); // later uses (point location) are sequential
    const std::vector<int> rank = detail::canonicalRanks(net.vertices, insertion);
    const std::vector<std::array<int, 4>> local = numberCellsCanonically(rt, net, rank, lo, hi);
    detail::indexCells(*owner, rt, owner->parallelCells, net.vertices.size());
    buildPores(net, rt, owner->parallelCells, local, rank);
  }
  else
#endif
  {
    Regular& rt = owner->rt;
    detail::insertVertices(net, rt, order, insertion);
    const std::vector<int> rank = detail::canonicalRanks(net.vertices, insertion);
    int n = 0;
    for (auto c = rt.finite_cells_begin(); c != rt.finite_cells_end(); ++c)
      c->info() = n++;
    detail::indexCells(*owner, rt, owner->cells, net.vertices.size());
    buildPores(net, rt, owner->cells, {}, rank);
  }
  for (std::size_t pi = 0; pi < net.pores.size(); ++pi)
    for (int v : net.pores[pi].vertices)
      if (v < kBoundaries)
        net.boundaryPores[static_cast<std::size_t>(v)].push_back(static_cast<int>(pi));
  net.curveOrder = poresAlongCurve(net);
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
#ifdef CGAL_LINKED_WITH_TBB
  if (tri.parallelRt)
    return walkTo(*tri.parallelRt, tri.parallelCells, x, near);
#endif
  if (!net.periodic)
    return walkTo(tri.rt, tri.cells, x, near);
  // periodic: wrap x into the cell along the periodic axes, then undo the wrap in `period`
  Vec3i wrap = Vec3i::Zero();
  for (int a = 0; a < 3; ++a)
    if (net.periodicAxis(a))
      wrap[a] = static_cast<int>(std::floor(x[a] / net.cellSize[a]));
  const int cell = walkTo(tri.rt, tri.cells, x - net.shift(wrap), near);
  if (cell < 0)
    return -1;
  const auto i = static_cast<std::size_t>(cell);
  if (period)
    *period = tri.periodOf[i] + wrap;
  return tri.poreOf[i];
}
} // namespace talus::flow::pore
