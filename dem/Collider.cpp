#include "dem/Collider.h"

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

/// Candidate sphere-sphere pairs (i < j, centres closer than ri + rj + skin), by linked cells.
std::vector<PairKey> spherePairs(const Bodies& b, const std::vector<BodyId>& spheres, double skin)
{
  if (spheres.size() < 2)
    return {};
  Vec3 lo = Vec3::Constant(std::numeric_limits<double>::infinity()), hi = -lo;
  double rmax = 0;
  for (BodyId id : spheres)
  {
    const auto i = static_cast<std::size_t>(id);
    lo = lo.cwiseMin(b.pos[i]);
    hi = hi.cwiseMax(b.pos[i]);
    rmax = std::max(rmax, b.radius[i]);
  }
  // Cells at least as wide as the largest interaction range; coarser if the box is sparse,
  // so memory stays proportional to the number of spheres.
  double h = 2 * rmax + skin;
  const Vec3 extent = (hi - lo).cwiseMax(Vec3::Constant(1e-300));
  while ((extent / h).array().floor().prod() > 8.0 * static_cast<double>(spheres.size()) + 27)
    h *= 1.5;
  std::array<int, 3> dims{};
  for (int d = 0; d < 3; ++d)
    dims[static_cast<std::size_t>(d)] = static_cast<int>(std::floor(extent[d] / h)) + 1;
  using Cell = std::array<int, 3>;
  auto cellOf = [&](const Vec3& p) {
    Cell c{};
    for (std::size_t d = 0; d < 3; ++d)
      c[d] = std::clamp(static_cast<int>(std::floor((p[static_cast<int>(d)] - lo[static_cast<int>(d)]) / h)), 0, dims[d] - 1);
    return c;
  };
  auto flat = [&](const Cell& c) { return (static_cast<std::int64_t>(c[2]) * dims[1] + c[1]) * dims[0] + c[0]; };

  const std::int64_t cellCount = static_cast<std::int64_t>(dims[0]) * dims[1] * dims[2];
  std::vector<std::int64_t> cellStart(static_cast<std::size_t>(cellCount) + 1, 0);
  std::vector<std::int64_t> cellOfSphere(spheres.size());
  for (std::size_t s = 0; s < spheres.size(); ++s)
  {
    cellOfSphere[s] = flat(cellOf(b.pos[static_cast<std::size_t>(spheres[s])]));
    ++cellStart[static_cast<std::size_t>(cellOfSphere[s]) + 1];
  }
  for (std::int64_t c = 0; c < cellCount; ++c)
    cellStart[static_cast<std::size_t>(c) + 1] += cellStart[static_cast<std::size_t>(c)];
  std::vector<BodyId> sorted(spheres.size());
  {
    std::vector<std::int64_t> fill(cellStart.begin(), cellStart.end() - 1);
    for (std::size_t s = 0; s < spheres.size(); ++s)
      sorted[static_cast<std::size_t>(fill[static_cast<std::size_t>(cellOfSphere[s])]++)] = spheres[s];
  }

  std::vector<std::vector<PairKey>> perThread(1);
#pragma omp parallel
  {
#ifdef _OPENMP
#pragma omp single
    perThread.resize(static_cast<std::size_t>(omp_get_num_threads()));
    std::vector<PairKey>& out = perThread[static_cast<std::size_t>(omp_get_thread_num())];
#else
    std::vector<PairKey>& out = perThread[0];
#endif
#pragma omp for schedule(dynamic, 256)
    for (std::int64_t s = 0; s < static_cast<std::int64_t>(spheres.size()); ++s)
    {
      const BodyId id = spheres[static_cast<std::size_t>(s)];
      const auto i = static_cast<std::size_t>(id);
      const Cell c = cellOf(b.pos[i]);
      for (int dz = -1; dz <= 1; ++dz)
        for (int dy = -1; dy <= 1; ++dy)
          for (int dx = -1; dx <= 1; ++dx)
          {
            const Cell nc{c[0] + dx, c[1] + dy, c[2] + dz};
            if (nc[0] < 0 || nc[1] < 0 || nc[2] < 0 || nc[0] >= dims[0] || nc[1] >= dims[1] || nc[2] >= dims[2])
              continue;
            const auto f = static_cast<std::size_t>(flat(nc));
            for (std::int64_t k = cellStart[f]; k < cellStart[f + 1]; ++k)
            {
              const BodyId other = sorted[static_cast<std::size_t>(k)];
              if (other <= id)
                continue;
              const auto j = static_cast<std::size_t>(other);
              const double reach = b.radius[i] + b.radius[j] + skin;
              if ((b.pos[j] - b.pos[i]).squaredNorm() < reach * reach)
                out.push_back(key(id, other));
            }
          }
    }
  }
  std::vector<PairKey> pairs;
  for (const auto& part : perThread)
    pairs.insert(pairs.end(), part.begin(), part.end());
  return pairs;
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
  std::vector<BodyId> spheres, walls;
  double rmin = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < b.size(); ++i)
  {
    if (!b.alive[i])
      continue;
    if (b.shape[i] == ShapeKind::Sphere)
    {
      spheres.push_back(static_cast<BodyId>(i));
      rmin = std::min(rmin, b.radius[i]);
    }
    else
      walls.push_back(static_cast<BodyId>(i));
  }
  skin_ = verletDist >= 0 ? verletDist : (spheres.empty() ? 0.0 : -verletDist * rmin);

  std::vector<PairKey> pairs = spherePairs(b, spheres, skin_);
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
  std::vector<Contact> merged;
  merged.reserve(pairs.size());
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
    c.kind = b.shape[static_cast<std::size_t>(c.id1)] == ShapeKind::Wall ? ContactGeometryKind::WallSphere
                                                                          : ContactGeometryKind::SphereSphere;
    merged.push_back(c);
  }
  old.swap(merged);
  scene.contacts.index(b.size());
  referencePos_ = b.pos;
  seenBodiesVersion_ = scene.bodiesVersion;
  ++rebuilds;
}
} // namespace talus::dem
