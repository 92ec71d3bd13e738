#include "dem/Collider.h"

#include "dem/CellGrid.h"
#include "dem/ContactGeometry.h"
#include "dem/Scene.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

#ifdef _OPENMP
#include <omp.h>
#endif

namespace talus::dem
{
namespace
{
using PairKey = std::uint64_t;

PairKey key(BodyId a, BodyId b) { return (static_cast<PairKey>(a) << 32) | static_cast<std::uint32_t>(b); }

/// Candidate sphere-sphere pairs (i < j, centres closer than ri + rj + skin), appended to
/// `pairs`; `perThread` is scratch space kept between calls.
void spherePairs(const Bodies& b, const std::vector<BodyId>& spheres, const CellGrid& grid, double skin,
                 std::vector<std::vector<PairKey>>& perThread, std::vector<PairKey>& pairs)
{
  perThread.resize(1);
#pragma omp parallel
  {
#ifdef _OPENMP
#pragma omp single
    perThread.resize(static_cast<std::size_t>(omp_get_num_threads()));
    std::vector<PairKey>& out = perThread[static_cast<std::size_t>(omp_get_thread_num())];
#else
    std::vector<PairKey>& out = perThread[0];
#endif
    out.clear();
#pragma omp for schedule(dynamic, 256)
    for (std::int64_t s = 0; s < static_cast<std::int64_t>(spheres.size()); ++s)
    {
      const BodyId id = spheres[static_cast<std::size_t>(s)];
      const auto i = static_cast<std::size_t>(id);
      const Vec3 reach = Vec3::Constant(grid.width());
      grid.forEachInBox(b.pos[i] - reach, b.pos[i] + reach, [&](BodyId other) {
        if (other <= id)
          return;
        const auto j = static_cast<std::size_t>(other);
        const double range = b.radius[i] + b.radius[j] + skin;
        if ((b.pos[j] - b.pos[i]).squaredNorm() < range * range)
          out.push_back(key(id, other));
      });
    }
  }
  for (const auto& part : perThread)
    pairs.insert(pairs.end(), part.begin(), part.end());
}

/// Candidate facet-sphere pairs: spheres whose centre is within r + skin of the triangle.
void facetPairs(const Bodies& b, BodyId facet, const CellGrid& grid, double rmax, double skin, std::vector<PairKey>& out)
{
  const std::array<Vec3, 3> v = facetVertices(b, static_cast<std::size_t>(facet));
  const Vec3 grow = Vec3::Constant(rmax + skin);
  const Vec3 lo = v[0].cwiseMin(v[1]).cwiseMin(v[2]) - grow, hi = v[0].cwiseMax(v[1]).cwiseMax(v[2]) + grow;
  grid.forEachInBox(lo, hi, [&](BodyId s) {
    const auto i = static_cast<std::size_t>(s);
    const double range = b.radius[i] + skin;
    if ((b.pos[i] - closestPointOnTriangle(b.pos[i], v[0], v[1], v[2])).squaredNorm() < range * range)
      out.push_back(key(facet, s));
  });
}
} // namespace

bool Collider::needsRebuild(const Scene& scene) const
{
  if (scene.bodiesVersion != seenBodiesVersion_ || referencePos_.size() != scene.bodies.size())
    return true;
  const Bodies& b = scene.bodies;
  const double limit2 = 0.25 * skin_ * skin_;
  const auto n = static_cast<std::int64_t>(b.size());
  bool moved = false;
#pragma omp parallel for reduction(|| : moved) schedule(static)
  for (std::int64_t k = 0; k < n; ++k)
  {
    const auto i = static_cast<std::size_t>(k);
    if (b.alive[i] && (b.pos[i] - referencePos_[i]).squaredNorm() > limit2)
      moved = true;
  }
  return moved;
}

void Collider::run(Scene& scene)
{
  if (needsRebuild(scene))
    rebuild(scene);
}

void Collider::rebuild(Scene& scene)
{
  const Bodies& b = scene.bodies;
  std::vector<BodyId>& spheres = spheres_;
  std::vector<BodyId>& walls = walls_;
  std::vector<BodyId>& facets = facets_;
  spheres.clear();
  walls.clear();
  facets.clear();
  double rmin = std::numeric_limits<double>::infinity(), rmax = 0;
  for (std::size_t i = 0; i < b.size(); ++i)
  {
    if (!b.alive[i])
      continue;
    if (b.shape[i] == ShapeKind::Sphere)
    {
      spheres.push_back(static_cast<BodyId>(i));
      rmin = std::min(rmin, b.radius[i]);
      rmax = std::max(rmax, b.radius[i]);
    }
    else if (b.shape[i] == ShapeKind::Wall)
      walls.push_back(static_cast<BodyId>(i));
    else
      facets.push_back(static_cast<BodyId>(i));
  }
  skin_ = verletDist >= 0 ? verletDist : (spheres.empty() ? 0.0 : -verletDist * rmin);

  grid_.build(b, spheres, 2 * rmax + skin_);
  std::vector<PairKey>& pairs = pairs_;
  pairs.clear();
  spherePairs(b, spheres, grid_, skin_, perThread_, pairs);
  for (BodyId f : facets)
    facetPairs(b, f, grid_, rmax, skin_, pairs);
  for (BodyId w : walls)
  {
    const auto wi = static_cast<std::size_t>(w);
    const WallShape& wall = b.walls[static_cast<std::size_t>(b.shapeIndex[wi])];
    for (BodyId s : spheres)
    {
      const auto si = static_cast<std::size_t>(s);
      const double d = b.pos[si][wall.axis] - b.pos[wi][wall.axis];
      const bool side = wall.sense == 0 || (wall.sense > 0 ? d > -b.radius[si] : d < b.radius[si]);
      if (side && std::abs(d) < b.radius[si] + skin_)
        pairs.push_back(key(w, s));
    }
  }
  std::sort(pairs.begin(), pairs.end());

  // Merge with the existing list (also sorted by key): surviving pairs keep their history.
  std::vector<Contact>& old = scene.contacts.list;
  std::vector<Contact>& merged = spare_;
  merged.clear();
  if (merged.capacity() < pairs.size()) // with room to grow: a reallocation faults in fresh pages
    merged.reserve(pairs.size() + pairs.size() / 4);
  std::size_t o = 0;
  for (PairKey k : pairs)
  {
    while (o < old.size() && key(old[o].id1, old[o].id2) < k)
      ++o;
    if (o < old.size() && key(old[o].id1, old[o].id2) == k)
    {
      merged.push_back(old[o]);
      continue;
    }
    Contact c;
    c.id1 = static_cast<BodyId>(k >> 32);
    c.id2 = static_cast<BodyId>(k & 0xffffffffu);
    switch (b.shape[static_cast<std::size_t>(c.id1)])
    {
    case ShapeKind::Wall: c.kind = ContactGeometryKind::WallSphere; break;
    case ShapeKind::Facet: c.kind = ContactGeometryKind::FacetSphere; break;
    case ShapeKind::Sphere: c.kind = ContactGeometryKind::SphereSphere; break;
    }
    merged.push_back(c);
  }
  old.swap(merged);
  scene.contacts.index(b.size());
  referencePos_ = b.pos;
  seenBodiesVersion_ = scene.bodiesVersion;
  ++rebuilds;
}
} // namespace talus::dem
