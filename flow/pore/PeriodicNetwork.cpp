// The periodic pore network (Yade's PeriodicFlowEngine): the spheres wrapped into the cell, images
// of those near its faces added so that every pore of the cell is complete, and the pores of the
// triangulation grouped by periodic translation: one pore (one pressure unknown) per group, the
// others being its images.
#include "flow/pore/CgalTriangulation.h"
#include "flow/pore/CurveOrder.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <stdexcept>
#include <string>
#include <unordered_map>

namespace talus::flow::pore
{
namespace
{
using cgal::Regular;
using Cell = Regular::Cell_handle;

/// A vertex up to periodic translation: the real vertex it is (an image of) and its shift.
struct VertexKey
{
  int base = 0;
  Vec3i period = Vec3i::Zero();
  bool operator<(const VertexKey& o) const
  {
    if (base != o.base)
      return base < o.base;
    return std::lexicographical_compare(period.data(), period.data() + 3, o.period.data(), o.period.data() + 3);
  }
  bool operator==(const VertexKey& o) const { return base == o.base && period == o.period; }
};

/// A pore up to periodic translation: its four vertices, shifted so that the smallest sphere
/// vertex has period 0, sorted. Every image of a pore has the same key.
struct PoreKey
{
  std::array<VertexKey, 4> v;
  bool operator==(const PoreKey& o) const { return v == o.v; }
};

struct PoreKeyHash
{
  std::size_t operator()(const PoreKey& k) const
  {
    std::size_t h = 0;
    for (const VertexKey& v : k.v)
      for (const int x : {v.base, v.period[0], v.period[1], v.period[2]})
        h = h * 1000003u ^ static_cast<std::size_t>(x + 7);
    return h;
  }
};

bool lexLess(const Vec3i& a, const Vec3i& b)
{
  return std::lexicographical_compare(a.data(), a.data() + 3, b.data(), b.data() + 3);
}

VertexKey vertexKey(const PoreNetwork& net, int v)
{
  const Vertex& vx = net.vertices[static_cast<std::size_t>(v)];
  return vx.image >= 0 ? VertexKey{vx.image, vx.period} : VertexKey{v, Vec3i::Zero()};
}

/// Local index (0..3) in cell c of the vertex `key` (in c's frame), -1 if absent.
int localIndex(const PoreNetwork& net, Cell c, const VertexKey& key)
{
  for (int y = 0; y < 4; ++y)
    if (vertexKey(net, c->vertex(y)->info()) == key)
      return y;
  return -1;
}

void checkPeriodicInput(const std::vector<PoreSphere>& spheres, const std::array<Boundary, kBoundaries>& boundaries,
                        const std::array<bool, kBoundaries>& hasBoundary, const Vec3& cellSize, double duplicateThreshold)
{
  detail::checkSpheres(spheres);
  if (!cellSize.allFinite() || !(cellSize.minCoeff() > 0))
    throw std::invalid_argument("periodic pore network: the cell size must be positive and finite");
  if (!(duplicateThreshold >= 0) || !std::isfinite(duplicateThreshold))
    throw std::invalid_argument("PeriodicFlowEngine.duplicateThreshold must be >= 0");
  for (int k = 0; k < kBoundaries; ++k)
  {
    const Boundary& b = boundaries[static_cast<std::size_t>(k)];
    if (!hasBoundary[static_cast<std::size_t>(k)])
      continue;
    for (const PoreSphere& s : spheres)
      if ((s.pos[b.coordinate] - b.position) * b.normal[b.coordinate] < 0)
        throw std::invalid_argument("periodic pore network: the centre of body " + std::to_string(s.id) +
                                    " is outside the boundary at " + "xyz"[b.coordinate] + " = " + std::to_string(b.position));
  }
}

/// The boundary vertices, then the spheres wrapped into the cell, each followed by its images
/// within radius + duplicateThreshold of the cell (Yade's order). Returns the insertion order.
std::vector<int> addVertices(PoreNetwork& net, const std::vector<PoreSphere>& spheres, double duplicateThreshold)
{
  const Vec3& cellSize = net.cellSize;
  // The box the boundary spheres are placed around: the walls on walled axes, the cell otherwise.
  Vec3 lo = Vec3::Zero();
  Vec3 hi = cellSize;
  for (int a = 0; a < 3; ++a)
    if (!net.periodicAxis(a))
    {
      if (net.hasBoundary[static_cast<std::size_t>(2 * a)])
        lo[a] = net.boundaries[static_cast<std::size_t>(2 * a)].position;
      if (net.hasBoundary[static_cast<std::size_t>(2 * a + 1)])
        hi[a] = net.boundaries[static_cast<std::size_t>(2 * a + 1)].position;
    }
  std::vector<int> order;
  for (int k = 0; k < kBoundaries; ++k)
  {
    net.vertices.push_back(detail::boundaryVertex(net.boundaries, k, lo, hi));
    if (net.hasBoundary[static_cast<std::size_t>(k)])
      order.push_back(k);
  }
  net.wrap.resize(spheres.size(), Vec3i::Zero());
  for (std::size_t i = 0; i < spheres.size(); ++i)
  {
    const PoreSphere& s = spheres[i];
    for (int a = 0; a < 3; ++a)
      if (net.periodicAxis(a))
        net.wrap[i][a] = static_cast<int>(std::floor(s.pos[a] / cellSize[a]));
    net.vertices.push_back(Vertex{s.pos - net.shift(net.wrap[i]), s.radius, false, s.id});
  }
  for (std::size_t i = 0; i < spheres.size(); ++i)
  {
    const int real = static_cast<int>(kBoundaries + i);
    order.push_back(real);
    const Vec3 at = net.vertices[static_cast<std::size_t>(real)].pos;
    const double half = spheres[i].radius + duplicateThreshold;
    Vec3i c;
    for (c[0] = -1; c[0] <= 1; ++c[0])
      for (c[1] = -1; c[1] <= 1; ++c[1])
        for (c[2] = -1; c[2] <= 1; ++c[2])
        {
          bool near = c != Vec3i::Zero();
          for (int a = 0; a < 3 && near; ++a)
          {
            if (c[a] != 0 && !net.periodicAxis(a))
              near = false;
            const double x = at[a] + c[a] * cellSize[a];
            if (net.periodicAxis(a) && (x - half > cellSize[a] || x + half < 0))
              near = false;
          }
          if (!near)
            continue;
          Vertex image{at + net.shift(c), spheres[i].radius, false, spheres[i].id};
          image.image = real;
          image.period = c;
          order.push_back(static_cast<int>(net.vertices.size()));
          net.vertices.push_back(image);
        }
  }
  return order;
}

/// Numbers the finite cells and groups them by periodic translation. Each group's
/// representative point (the centroid of its sphere vertices, from the key so that every image
/// computes the same number) falls in the cell for exactly one translate: that one is the pore,
/// the others its images. Fills owner.poreOf and owner.periodOf; returns the pores' cells.
std::vector<Cell> groupCellsByTranslation(const PoreNetwork& net, Triangulation& owner)
{
  Regular& rt = owner.rt;
  int nCells = 0;
  for (auto c = rt.finite_cells_begin(); c != rt.finite_cells_end(); ++c)
    c->info() = nCells++;
  detail::indexCells(owner, rt, owner.cells, net.vertices.size());
  std::vector<PoreKey> keys(static_cast<std::size_t>(nCells));
  std::vector<Vec3i> shiftOf(static_cast<std::size_t>(nCells), Vec3i::Zero());
  std::vector<char> isReal(static_cast<std::size_t>(nCells), 0);
  std::vector<Vec3i> realShift(static_cast<std::size_t>(nCells), Vec3i::Zero());
  for (auto c = rt.finite_cells_begin(); c != rt.finite_cells_end(); ++c)
  {
    const auto ci = static_cast<std::size_t>(c->info());
    PoreKey key;
    for (int y = 0; y < 4; ++y)
      key.v[static_cast<std::size_t>(y)] = vertexKey(net, c->vertex(y)->info());
    bool any = false;
    VertexKey smallest;
    for (const VertexKey& v : key.v)
      if (v.base >= kBoundaries && (!any || v < smallest))
      {
        smallest = v;
        any = true;
      }
    const Vec3i s = any ? smallest.period : Vec3i::Zero();
    for (VertexKey& v : key.v)
      if (v.base >= kBoundaries)
        v.period -= s;
    std::sort(key.v.begin(), key.v.end());
    Vec3 centroid = Vec3::Zero();
    int n = 0;
    for (const VertexKey& v : key.v)
      if (v.base >= kBoundaries)
      {
        centroid += net.vertices[static_cast<std::size_t>(v.base)].pos + net.shift(v.period);
        ++n;
      }
    // the translate whose centroid, centroid + w L, is in [0, L)
    Vec3i w = Vec3i::Zero();
    if (n > 0)
    {
      centroid /= n;
      for (int a = 0; a < 3; ++a)
        if (net.periodicAxis(a))
          w[a] = -static_cast<int>(std::floor(centroid[a] / net.cellSize[a]));
    }
    keys[ci] = key;
    shiftOf[ci] = s;
    realShift[ci] = w;
    isReal[ci] = n > 0 && s == w ? 1 : 0;
  }
  std::unordered_map<PoreKey, int, PoreKeyHash> poreOfKey;
  std::vector<Cell> poreCell;
  for (auto c = rt.finite_cells_begin(); c != rt.finite_cells_end(); ++c)
    if (isReal[static_cast<std::size_t>(c->info())])
    {
      poreOfKey.emplace(keys[static_cast<std::size_t>(c->info())], static_cast<int>(poreCell.size()));
      poreCell.push_back(c);
    }
  owner.poreOf.assign(static_cast<std::size_t>(nCells), -1);
  owner.periodOf.assign(static_cast<std::size_t>(nCells), Vec3i::Zero());
  for (std::size_t ci = 0; ci < keys.size(); ++ci)
  {
    const auto found = poreOfKey.find(keys[ci]);
    if (found == poreOfKey.end())
      continue;
    owner.poreOf[ci] = found->second;
    owner.periodOf[ci] = shiftOf[ci] - realShift[ci];
  }
  return poreCell;
}

/// The error for a pore whose neighbour has no periodic counterpart (too few images).
std::runtime_error tooThin(int pore, double duplicateThreshold)
{
  return std::runtime_error("periodic pore network: pore " + std::to_string(pore) +
                            " of the cell has a neighbour with no periodic counterpart; increase "
                            "duplicateThreshold (now " + std::to_string(duplicateThreshold) + ")");
}

/// The pores: vertices, neighbours (up to translation) and centres.
void addPores(PoreNetwork& net, const Triangulation& owner, const std::vector<Cell>& poreCell,
              const std::vector<int>& rank, double duplicateThreshold)
{
  const Regular& rt = owner.rt;
  bool open = false; // an axis with a single boundary leaves the packing open on one side
  for (int a = 0; a < 3; ++a)
    open = open || (net.hasBoundary[static_cast<std::size_t>(2 * a)] != net.hasBoundary[static_cast<std::size_t>(2 * a + 1)]);
  net.pores.resize(poreCell.size());
  for (std::size_t pi = 0; pi < poreCell.size(); ++pi)
  {
    const Cell c = poreCell[pi];
    Pore& p = net.pores[pi];
    for (int k = 0; k < 4; ++k)
    {
      p.vertices[k] = c->vertex(k)->info();
      p.throats[k] = -1;
      p.nFictitious += net.vertices[static_cast<std::size_t>(p.vertices[k])].fictitious ? 1 : 0;
      const Cell n = c->neighbor(k);
      if (rt.is_infinite(n))
      {
        if (!open)
          throw tooThin(static_cast<int>(pi), duplicateThreshold);
        p.neighbours[k] = -1;
        continue;
      }
      const auto ni = static_cast<std::size_t>(n->info());
      if (owner.poreOf[ni] < 0)
        throw tooThin(static_cast<int>(pi), duplicateThreshold);
      p.neighbours[k] = owner.poreOf[ni];
      p.neighbourPeriod[k] = owner.periodOf[ni];
    }
    p.centre = detail::weightedCentre(rt, c, rank);
  }
}

/// One throat per facet up to translation, made from the side of the smaller pore index (or
/// towards the positive shift between a pore and its own image), linked to the mirror facet.
void addThroats(PoreNetwork& net, const Regular& rt, const std::vector<Cell>& poreCell, const std::vector<int>& rank,
                double duplicateThreshold)
{
  for (std::size_t pi = 0; pi < poreCell.size(); ++pi)
  {
    const Cell c = poreCell[pi];
    for (int k = 0; k < 4; ++k)
    {
      const int j = net.pores[pi].neighbours[k];
      const Vec3i o = net.pores[pi].neighbourPeriod[k];
      if (j < 0 || j < static_cast<int>(pi) || (j == static_cast<int>(pi) && !lexLess(Vec3i::Zero(), o)))
        continue;
      const Cell other = poreCell[static_cast<std::size_t>(j)];
      const Cell n = c->neighbor(k);
      const auto inOther = [&](int vertex) {
        VertexKey key = vertexKey(net, vertex);
        if (key.base >= kBoundaries)
          key.period -= o;
        return localIndex(net, other, key);
      };
      Throat t;
      t.pores = {static_cast<int>(pi), j};
      t.facet = k;
      t.period = o;
      for (int y = 0, m = 0; y < 4; ++y)
        if (y != k)
          t.mirrorLocal[static_cast<std::size_t>(m++)] = inOther(c->vertex(y)->info());
      detail::setFacetVertices(t, net.pores[pi].vertices, rank);
      const int mirror = inOther(n->vertex(rt.mirror_index(c, k))->info());
      if (mirror < 0 || std::find(t.mirrorLocal.begin(), t.mirrorLocal.end(), -1) != t.mirrorLocal.end() ||
          net.pores[static_cast<std::size_t>(j)].throats[mirror] >= 0)
        throw tooThin(static_cast<int>(pi), duplicateThreshold);
      const int ti = static_cast<int>(net.throats.size());
      net.pores[pi].throats[k] = ti;
      net.pores[static_cast<std::size_t>(j)].throats[mirror] = ti;
      net.throats.push_back(t);
    }
  }
  for (std::size_t pi = 0; pi < net.pores.size(); ++pi)
  {
    const Pore& p = net.pores[pi];
    for (int k = 0; k < 4; ++k)
      if (p.neighbours[k] >= 0 && p.throats[k] < 0)
        throw tooThin(static_cast<int>(pi), duplicateThreshold);
    for (int v : p.vertices)
      if (v < kBoundaries)
        net.boundaryPores[static_cast<std::size_t>(v)].push_back(static_cast<int>(pi));
  }
}
} // namespace

PoreNetwork triangulatePeriodic(const std::vector<PoreSphere>& spheres, const std::array<Boundary, kBoundaries>& boundaries,
                                const std::array<bool, kBoundaries>& hasBoundary, const Vec3& cellSize,
                                double duplicateThreshold, InsertionOrder insertion)
{
  checkPeriodicInput(spheres, boundaries, hasBoundary, cellSize, duplicateThreshold);
  PoreNetwork net;
  net.periodic = true;
  net.cellSize = cellSize;
  net.hasBoundary = hasBoundary;
  net.boundaries = boundaries;
  net.nSpheres = spheres.size();
  const std::vector<int> order = addVertices(net, spheres, duplicateThreshold);
  auto owner = std::make_shared<Triangulation>();
  detail::insertVertices(net, owner->rt, order, insertion);
  const std::vector<int> rank = detail::canonicalRanks(net.vertices, insertion);
  const std::vector<Cell> poreCell = groupCellsByTranslation(net, *owner);
  addPores(net, *owner, poreCell, rank, duplicateThreshold);
  addThroats(net, owner->rt, poreCell, rank, duplicateThreshold);
  net.curveOrder = poresAlongCurve(net);
  net.triangulation = std::move(owner);
  return net;
}
} // namespace talus::flow::pore
