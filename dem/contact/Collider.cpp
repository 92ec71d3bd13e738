#include "dem/contact/Collider.h"
#include "dem/contact/CellGrid.h"

#include "dem/contact/ContactGeometry.h"
#include "dem/contact/PotentialBlockContact.h"
#include "dem/contact/PotentialParticleContact.h"
#include "dem/core/Scene.h"
#include "dem/base/Threads.h"

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
PairKey key(BodyId a, BodyId b) { return (static_cast<PairKey>(a) << 32) | static_cast<std::uint32_t>(b); }

bool byKey(const Candidate& a, const Candidate& b) { return a.key < b.key; }

/// Candidate sphere-sphere pairs (i < j, centres closer than ri + rj + skin), into `perThread`:
/// `spheres` is in ascending id order and thread t takes the t-th contiguous run of it (static
/// schedule), so perThread[t] holds the pairs whose first id lies in that run, each sphere's pairs
/// sorted by the partner's id, and the parts concatenate in key order (no sort of the whole list).
/// Partners are read from the grid's packed copy of centres and radii, in runs of neighbouring
/// cells: reading them body by body through their ids took three times as long.
void spherePairs(const Bodies& b, const std::vector<BodyId>& spheres, const CellGrid& grid, double skin,
                 const Collider::PairFilter& filter, std::vector<std::vector<Candidate>>& perThread)
{
  perThread.resize(1);
#pragma omp parallel if (static_cast<std::int64_t>(spheres.size()) >= parallelLoopMinimum)
  {
#ifdef _OPENMP
#pragma omp single
    perThread.resize(static_cast<std::size_t>(omp_get_num_threads()));
    std::vector<Candidate>& part = perThread[static_cast<std::size_t>(omp_get_thread_num())];
#else
    std::vector<Candidate>& part = perThread[0];
#endif
    // Filled through a vector of this thread's own: the parts' vectors lie side by side, and
    // each push_back onto them stored into a cache line the other threads were storing into.
    std::vector<Candidate> out;
    out.swap(part);
    out.clear();
#pragma omp for schedule(static)
    for (std::int64_t s = 0; s < static_cast<std::int64_t>(spheres.size()); ++s)
    {
      const BodyId id = spheres[static_cast<std::size_t>(s)];
      const auto i = static_cast<std::size_t>(id);
      const Vec3 center = b.pos[i];
      const double reach = b.radius[i] + skin;
      // Only members of a clump, or any sphere when masks are in play, may be refused a partner.
      const bool filtered = b.clumpId[i] >= 0 || filter.masks;
      const std::size_t first = out.size();
      grid.forEachRunAround(static_cast<std::size_t>(s), [&](std::int64_t begin, std::int64_t end) {
        for (std::int64_t e = begin; e < end; ++e)
        {
          // (Testing the id together with the distance, without its own branch, was slower.)
          const BodyId other = grid.entry(e);
          if (other <= id)
            continue;
          const CellGrid::Packed& p = grid.packed(e);
          const double dx = p.x - center[0], dy = p.y - center[1], dz = p.z - center[2];
          const double range = reach + p.radius;
          // Inclusive and summed as the contact's own test (spheresBegin), so that with no skin
          // a pair touching exactly stays a candidate.
          if (yadeSquaredNorm(dx, dy, dz) > range * range)
            continue;
          if (filtered && !filter(b, i, static_cast<std::size_t>(other)))
            continue;
          out.push_back({key(id, other), Eigen::Vector3i::Zero()});
        }
      });
      // A handful of pairs, in runs ascending cell by cell: insertion sort.
      for (std::size_t k = first + 1; k < out.size(); ++k)
        for (std::size_t m = k; m > first && out[m].key < out[m - 1].key; --m)
          std::swap(out[m], out[m - 1]);
    }
    out.swap(part);
  }
}

/// The candidates of `parts` (each sorted, each part's keys below the next part's) and of
/// `others` (sorted), merged into `pairs` in key order. In parallel, part by part: part t's
/// share of `others` is found by its key range, so the output is the same for every thread count.
void mergeCandidates(const std::vector<std::vector<Candidate>>& parts, const std::vector<Candidate>& others,
                     std::vector<Candidate>& pairs)
{
  const std::size_t count = parts.size();
  std::vector<std::size_t> partStart(count + 1, 0), otherStart(count + 1, others.size());
  otherStart[0] = 0;
  for (std::size_t t = 0; t < count; ++t)
  {
    partStart[t + 1] = partStart[t] + parts[t].size();
    // Part t takes the others below the first key of the next non-empty part (an empty part
    // thus takes none, and the last part takes the rest).
    for (std::size_t u = t + 1; u < count; ++u)
      if (!parts[u].empty())
      {
        otherStart[t + 1] = static_cast<std::size_t>(
            std::lower_bound(others.begin(), others.end(), parts[u].front(), byKey) - others.begin());
        break;
      }
  }
  pairs.resize(partStart[count] + others.size());
#pragma omp parallel for schedule(static, 1) num_threads(static_cast<int>(count)) if (count > 1 && pairs.size() >= static_cast<std::size_t>(parallelLoopMinimum))
  for (std::int64_t t = 0; t < static_cast<std::int64_t>(count); ++t)
  {
    const auto u = static_cast<std::size_t>(t);
    std::merge(parts[u].begin(), parts[u].end(), others.begin() + static_cast<std::ptrdiff_t>(otherStart[u]),
               others.begin() + static_cast<std::ptrdiff_t>(otherStart[u + 1]),
               pairs.begin() + static_cast<std::ptrdiff_t>(partStart[u] + otherStart[u]), byKey);
  }
}

/// Candidate sphere pairs in a periodic cell: for each pair, the nearest periodic image of the
/// second sphere, with its integer cell offset. Spheres are binned by their fractional
/// coordinates wrapped into the cell; with fewer than 3 bins along an axis (a cell not much
/// larger than the interaction range) every pair is tested. Bins are merged where the cell is
/// sparse, so that their count stays proportional to the sphere count.
void periodicSpherePairs(const Bodies& b, const std::vector<BodyId>& spheres, const Cell& cell, double rmax,
                         double skin, bool allowBiggerThanPeriod, const Collider::PairFilter& filter,
                         std::vector<Candidate>& pairs)
{
  const Mat3 inv = cell.hSize.inverse();
  const std::size_t n = spheres.size();
  std::vector<Vec3> wrapped(n);
  std::vector<Eigen::Vector3i> period(n);
  for (std::size_t s = 0; s < n; ++s)
  {
    const auto i = static_cast<std::size_t>(spheres[s]);
    const Vec3 f = inv * b.pos[i];
    const Vec3 fl = f.array().floor().matrix();
    if (!(fl.cwiseAbs().maxCoeff() < 1e9))
      throw CellGrid::lostBody(b, spheres[s], b.pos[i].allFinite() ? "is more than 1e9 periodic cells away, at"
                                                                    : "has a non-finite position");
    period[s] = fl.cast<int>();
    wrapped[s] = f - fl;
  }
  // A sphere as wide as the cell would touch its own images (Yade's collider stops there too).
  for (int d = 0; d < 3 && n > 0 && !allowBiggerThanPeriod; ++d)
  {
    const double width = 1 / inv.row(d).norm();
    if (2 * (rmax + skin) < 0.99 * width)
      continue;
    const BodyId largest = *std::find_if(spheres.begin(), spheres.end(),
                                         [&](BodyId id) { return b.radius[static_cast<std::size_t>(id)] == rmax; });
    throw std::runtime_error("sphere " + std::to_string(largest) + " (radius " + std::to_string(rmax)
                             + ") is larger than the periodic cell: its diameter plus the collider's skin spans the "
                               "cell's width "
                             + std::to_string(width) + " along axis " + std::to_string(d)
                             + " (a sphere's diameter must stay below the cell's width; "
                               "InsertionSortCollider.allowBiggerThanPeriod=True lets it run anyway)");
  }
  // Fractional reach of the interaction range along each axis: range * |row of H^-1|.
  const double range = 2 * rmax + skin;
  std::array<int, 3> bins{};
  for (int d = 0; d < 3; ++d)
    bins[static_cast<std::size_t>(d)] = static_cast<int>(std::min(std::floor(1.0 / (range * inv.row(d).norm())), 1e9));
  const double binBudget = 8.0 * static_cast<double>(n) + 27;
  while (static_cast<double>(bins[0]) * bins[1] * bins[2] > binBudget)
  {
    int& widest = *std::max_element(bins.begin(), bins.end());
    widest = std::max(3, widest * 2 / 3);
  }
  // Only members of a clump, or any sphere when masks are in play, may be refused a partner.
  const bool anyClump = std::any_of(spheres.begin(), spheres.end(),
                                    [&](BodyId id) { return b.clumpId[static_cast<std::size_t>(id)] >= 0; });
  const bool filtered = filter.masks || anyClump;
  auto consider = [&](std::size_t s, std::size_t t) {
    const BodyId a = spheres[s], c = spheres[t];
    const std::size_t first = a < c ? s : t, second = a < c ? t : s;
    const Vec3 delta = wrapped[second] - wrapped[first];
    // The nearest image: minus delta rounded half away from zero, which for delta in (-1, 1)
    // (both wrapped into [0, 1)) is -1, 0 or 1 by two comparisons; std::round is a library call
    // per component without SSE4.1, and this loop runs for every pair of neighbouring spheres.
    const Eigen::Vector3i image((delta[0] <= -0.5) - (delta[0] >= 0.5), (delta[1] <= -0.5) - (delta[1] >= 0.5),
                                (delta[2] <= -0.5) - (delta[2] >= 0.5));
    const Vec3 d = cell.hSize * (delta + image.cast<double>());
    const auto i = static_cast<std::size_t>(spheres[first]), j = static_cast<std::size_t>(spheres[second]);
    const double reach = b.radius[i] + b.radius[j] + skin;
    if (yadeSquaredNorm(d) <= reach * reach && (!filtered || filter(b, i, j)))
      pairs.push_back({key(spheres[first], spheres[second]), image + period[first] - period[second]});
  };
  if (*std::min_element(bins.begin(), bins.end()) < 3)
  {
    for (std::size_t s = 0; s < n; ++s)
      for (std::size_t t = s + 1; t < n; ++t)
        consider(s, t);
    return;
  }
  auto flat = [&](const std::array<int, 3>& c) {
    return (static_cast<std::size_t>(c[2]) * static_cast<std::size_t>(bins[1]) + static_cast<std::size_t>(c[1]))
               * static_cast<std::size_t>(bins[0])
           + static_cast<std::size_t>(c[0]);
  };
  auto binOf = [&](const Vec3& w) {
    std::array<int, 3> c{};
    for (std::size_t d = 0; d < 3; ++d)
      c[d] = std::min(static_cast<int>(w[static_cast<int>(d)] * bins[d]), bins[d] - 1);
    return c;
  };
  std::vector<std::size_t> binOfSphere(n), start(static_cast<std::size_t>(bins[0]) * static_cast<std::size_t>(bins[1])
                                                      * static_cast<std::size_t>(bins[2]) + 1,
                                                  0);
  for (std::size_t s = 0; s < n; ++s)
  {
    binOfSphere[s] = flat(binOf(wrapped[s]));
    ++start[binOfSphere[s] + 1];
  }
  for (std::size_t k = 1; k < start.size(); ++k)
    start[k] += start[k - 1];
  std::vector<std::size_t> sorted(n), fill(start.begin(), start.end() - 1);
  for (std::size_t s = 0; s < n; ++s)
    sorted[fill[binOfSphere[s]]++] = s;
  // Bin by bin: the pairs inside it, then those with the 13 neighbours of one half of the 26
  // (the other half sees it from theirs; with 3 bins or more along each axis the 26 are
  // distinct), so each pair is met once and no test asks which of its two spheres comes first.
  // Only the occupied bins, in ascending order, as runs of `sorted`: split over processes, a
  // process holds its region's spheres and its ghosts, and most of the cell's bins are empty.
  // The pairs' order does not matter: the caller sorts them.
  for (std::size_t run = 0; run < n; run = start[binOfSphere[sorted[run]] + 1])
  {
    const std::size_t k = binOfSphere[sorted[run]];
    const int cx = static_cast<int>(k % static_cast<std::size_t>(bins[0]));
    const int cy = static_cast<int>(k / static_cast<std::size_t>(bins[0]) % static_cast<std::size_t>(bins[1]));
    const int cz = static_cast<int>(k / (static_cast<std::size_t>(bins[0]) * static_cast<std::size_t>(bins[1])));
    for (std::size_t e = start[k]; e < start[k + 1]; ++e)
      for (std::size_t f = e + 1; f < start[k + 1]; ++f)
        consider(sorted[e], sorted[f]);
    for (int dz = 0; dz <= 1; ++dz)
      for (int dy = dz == 0 ? 0 : -1; dy <= 1; ++dy)
        for (int dx = dz == 0 && dy == 0 ? 1 : -1; dx <= 1; ++dx)
        {
          const std::size_t m = flat({(cx + dx + bins[0]) % bins[0], (cy + dy + bins[1]) % bins[1],
                                      (cz + dz + bins[2]) % bins[2]});
          for (std::size_t e = start[k]; e < start[k + 1]; ++e)
            for (std::size_t f = start[m]; f < start[m + 1]; ++f)
              consider(sorted[e], sorted[f]);
        }
  }
}

/// Candidate box-sphere pairs: spheres whose centre is within r + skin of the box.
void boxPairs(const Bodies& b, BodyId box, const CellGrid& grid, double rmax, double skin,
              const Collider::PairFilter& filter, std::vector<Candidate>& out)
{
  const auto k = static_cast<std::size_t>(box);
  const Vec3 extents = b.boxes[static_cast<std::size_t>(b.shapeIndex[k])].extents;
  const Mat3 R = b.ori[k].toRotationMatrix();
  const Vec3 half = R.cwiseAbs() * extents + Vec3::Constant(rmax + skin);
  grid.forEachInBox(b.pos[k] - half, b.pos[k] + half, [&](BodyId s) {
    const auto i = static_cast<std::size_t>(s);
    const Vec3 local = R.transpose() * (b.pos[i] - b.pos[k]);
    const double range = b.radius[i] + skin;
    if (filter(b, k, i) && (local - local.cwiseMax(-extents).cwiseMin(extents)).squaredNorm() < range * range)
      out.push_back({key(box, s), Eigen::Vector3i::Zero()});
  });
}

/// Candidate facet-sphere pairs: spheres whose centre is within r + skin of the triangle.
void facetPairs(const Bodies& b, BodyId facet, const CellGrid& grid, double rmax, double skin,
                const Collider::PairFilter& filter, std::vector<Candidate>& out)
{
  const std::array<Vec3, 3> v = facetVertices(b, static_cast<std::size_t>(facet));
  const Vec3 grow = Vec3::Constant(rmax + skin);
  const Vec3 lo = v[0].cwiseMin(v[1]).cwiseMin(v[2]) - grow, hi = v[0].cwiseMax(v[1]).cwiseMax(v[2]) + grow;
  grid.forEachInBox(lo, hi, [&](BodyId s) {
    const auto i = static_cast<std::size_t>(s);
    const double range = b.radius[i] + skin;
    if (filter(b, static_cast<std::size_t>(facet), i) && (b.pos[i] - closestPointOnTriangle(b.pos[i], v[0], v[1], v[2])).squaredNorm() < range * range)
      out.push_back({key(facet, s), Eigen::Vector3i::Zero()});
  });
}
/// Square of the distance from `point` to facet or box `body` (zero inside a box).
double squaredDistanceTo(const Bodies& b, std::size_t body, const Vec3& point)
{
  if (b.shape[body] == ShapeKind::Facet)
  {
    const std::array<Vec3, 3> v = facetVertices(b, body);
    return (point - closestPointOnTriangle(point, v[0], v[1], v[2])).squaredNorm();
  }
  const Vec3 extents = b.boxes[static_cast<std::size_t>(b.shapeIndex[body])].extents;
  const Vec3 local = b.ori[body].conjugate() * (point - b.pos[body]);
  return (local - local.cwiseMax(-extents).cwiseMin(extents)).squaredNorm();
}

/// Half the size of facet or box `body`'s Aabb along each axis.
Vec3 halfAabb(const Bodies& b, std::size_t body)
{
  if (b.shape[body] == ShapeKind::Facet)
  {
    const std::array<Vec3, 3> v = facetVertices(b, body);
    return 0.5 * (v[0].cwiseMax(v[1]).cwiseMax(v[2]) - v[0].cwiseMin(v[1]).cwiseMin(v[2]));
  }
  return b.ori[body].toRotationMatrix().cwiseAbs() * b.boxes[static_cast<std::size_t>(b.shapeIndex[body])].extents;
}

/// Candidate pairs of facet or box `body` and the spheres of a periodic cell: the periodic
/// images of each sphere within r + skin of the body (the nearest one, or its neighbours too
/// where the reach exceeds half the cell). A body whose Aabb grown by the skin spans more than
/// half the cell along an axis has no nearest image there: with `allowBiggerThanPeriod` the
/// sphere is taken where it is along that axis, as Yade's collider does (a floor across the
/// cell), else it is an error, as in Yade.
void periodicBoundaryPairs(const Bodies& b, BodyId body, const std::vector<BodyId>& spheres, const Cell& cell,
                           double rmax, double skin, bool allowBiggerThanPeriod, const Collider::PairFilter& filter,
                           std::vector<Candidate>& out)
{
  const auto k = static_cast<std::size_t>(body);
  const Mat3 inv = cell.hSize.inverse();
  const Vec3 half = halfAabb(b, k);
  Eigen::Vector3i follows = Eigen::Vector3i::Ones(); // 1: images along that axis
  Eigen::Vector3i spread = Eigen::Vector3i::Zero();  // 1: the nearest image's neighbours too
  for (int d = 0; d < 3; ++d)
  {
    const Vec3 row = inv.row(d).cwiseAbs();
    if (2 * row.dot(half + Vec3::Constant(skin)) > 0.5)
    {
      if (!allowBiggerThanPeriod)
        throw std::runtime_error("body " + std::to_string(body) + " (" + shapeName(b.shape[k])
                                 + ") spans more than half of the periodic cell along axis " + std::to_string(d)
                                 + " (set InsertionSortCollider.allowBiggerThanPeriod=True for a body across the cell)");
      follows[d] = 0;
    }
    else if (row.dot(half + Vec3::Constant(rmax + skin)) > 0.5)
      spread[d] = 1;
  }
  const Vec3 centre = inv * b.pos[k];
  for (BodyId s : spheres)
  {
    if (!filter(b, k, static_cast<std::size_t>(s)))
      continue;
    const auto i = static_cast<std::size_t>(s);
    const Eigen::Vector3i nearest = Vec3((centre - inv * b.pos[i]).array().round()).cast<int>().cwiseProduct(follows);
    const double range = b.radius[i] + skin;
    for (int x = -spread[0]; x <= spread[0]; ++x)
      for (int y = -spread[1]; y <= spread[1]; ++y)
        for (int z = -spread[2]; z <= spread[2]; ++z)
        {
          const Eigen::Vector3i image = nearest + Eigen::Vector3i(x, y, z);
          if (squaredDistanceTo(b, k, b.pos[i] + cell.shift(image)) < range * range)
            out.push_back({key(body, s), image});
        }
  }
}

/// Potential Blocks and Particles: shapes given by planes, bounded by exact Aabbs.
bool isBoundary(const Bodies& b, BodyId id)
{
  const auto i = static_cast<std::size_t>(id);
  const auto s = static_cast<std::size_t>(b.shapeIndex[i]);
  return b.shape[i] == ShapeKind::PotentialBlock ? b.blocks[s].isBoundary : b.particles[s].isBoundary;
}

double boundingRadius(const Bodies& b, std::size_t i)
{
  const auto s = static_cast<std::size_t>(b.shapeIndex[i]);
  return b.shape[i] == ShapeKind::PotentialBlock ? b.blocks[s].boundingRadius : b.particles[s].boundingRadius;
}

double referenceLength(const Bodies& b, std::size_t i)
{
  const auto s = static_cast<std::size_t>(b.shapeIndex[i]);
  return b.shape[i] == ShapeKind::PotentialBlock ? b.blocks[s].R : b.particles[s].R;
}

/// Candidate pairs of Potential Blocks or Particles (Aabbs closer than the skin; two boundary
/// bodies never interact, nor a block with a particle, as in Yade) and of walls with them
/// (Aabb within the skin of the plane, on its side).
void convexPairs(const Bodies& b, const std::vector<BodyId>& convex, const std::vector<BodyId>& walls, double skin,
                 const Collider::PairFilter& filter, std::vector<Candidate>& out)
{
  const std::size_t n = convex.size();
  std::vector<Vec3> lo(n), hi(n);
  for (std::size_t k = 0; k < n; ++k)
  {
    const auto i = static_cast<std::size_t>(convex[k]);
    if (b.shape[i] == ShapeKind::PotentialBlock)
      potentialBlockAabb(b, i, lo[k], hi[k]);
    else
      potentialParticleAabb(b, i, lo[k], hi[k]);
  }
  // Sweep along x: blocks sorted by their lower bound.
  std::vector<std::size_t> order(n);
  for (std::size_t k = 0; k < n; ++k)
    order[k] = k;
  std::sort(order.begin(), order.end(), [&](std::size_t p, std::size_t q) { return lo[p][0] < lo[q][0]; });
  for (std::size_t s = 0; s < n; ++s)
    for (std::size_t t = s + 1; t < n && lo[order[t]][0] <= hi[order[s]][0] + skin; ++t)
    {
      const std::size_t p = order[s], q = order[t];
      if (((lo[p] - hi[q]).array() > skin).any() || ((lo[q] - hi[p]).array() > skin).any())
        continue;
      const BodyId i = convex[p], j = convex[q];
      if ((isBoundary(b, i) && isBoundary(b, j))
          || b.shape[static_cast<std::size_t>(i)] != b.shape[static_cast<std::size_t>(j)]
          || !filter(b, static_cast<std::size_t>(i), static_cast<std::size_t>(j)))
        continue;
      out.push_back({key(std::min(i, j), std::max(i, j)), Eigen::Vector3i::Zero()});
    }
  for (BodyId w : walls)
  {
    const auto wi = static_cast<std::size_t>(w);
    const WallShape& wall = b.walls[static_cast<std::size_t>(b.shapeIndex[wi])];
    const double x = b.pos[wi][wall.axis];
    for (std::size_t k = 0; k < n; ++k)
    {
      const double below = lo[k][wall.axis] - x, above = hi[k][wall.axis] - x;
      // the block's Aabb reaches the wall's solid side (within the skin)
      const bool reaches = wall.sense > 0   ? below < skin
                           : wall.sense < 0 ? above > -skin
                                            : below < skin && above > -skin;
      if (reaches && filter(b, wi, static_cast<std::size_t>(convex[k])))
        out.push_back({key(w, convex[k]), Eigen::Vector3i::Zero()});
    }
  }
}

/// A new candidate's contact record: ids and the geometry kind of its shapes.
Contact newContact(const Bodies& b, const Candidate& candidate)
{
  Contact c;
  c.cellDist = candidate.cellDist;
  c.id1 = static_cast<BodyId>(candidate.key >> 32);
  c.id2 = static_cast<BodyId>(candidate.key & 0xffffffffu);
  const ShapeKind second = b.shape[static_cast<std::size_t>(c.id2)];
  switch (b.shape[static_cast<std::size_t>(c.id1)])
  {
  case ShapeKind::Wall:
    c.kind = second == ShapeKind::PotentialBlock      ? ContactGeometryKind::WallBlock
             : second == ShapeKind::PotentialParticle ? ContactGeometryKind::WallParticle
                                                      : ContactGeometryKind::WallSphere;
    break;
  case ShapeKind::PotentialBlock: c.kind = ContactGeometryKind::BlockBlock; break;
  case ShapeKind::PotentialParticle: c.kind = ContactGeometryKind::ParticleParticle; break;
  case ShapeKind::Facet: c.kind = ContactGeometryKind::FacetSphere; break;
  case ShapeKind::Box: c.kind = ContactGeometryKind::BoxSphere; break;
  case ShapeKind::Sphere:
  case ShapeKind::Clump: c.kind = ContactGeometryKind::SphereSphere; break;
  }
  return c;
}

/// The contact list after a re-detection, into `merged` (and `mergedExtra`): the candidates in
/// key order, each keeping the record (and richer state) of the same pair through the same image
/// in the previous list `old` (sorted by key too), plus the previous list's contacts held by an
/// unbroken bond that are no longer candidates (the law decides when a bond breaks).
///
/// In parallel over runs of candidates, each with the share of the old list from its first key,
/// each writing its records at its offset, so the list is the same for every thread count. (Serial, this copy of the records was the largest serial
/// part of a re-detection.)
void mergeContacts(const Bodies& b, const std::vector<Candidate>& pairs, const ContactList& old,
                   const ContactExtraList& oldExtra, const Collider::PairFilter& filter, ContactList& merged,
                   ContactExtraList& mergedExtra)
{
  const bool withExtra = !oldExtra.empty();
  const std::size_t n = pairs.size();
  int runs = 1;
#ifdef _OPENMP
  if (static_cast<std::int64_t>(n) >= parallelLoopMinimum)
    runs = omp_get_max_threads();
#endif
  auto oldKey = [&](std::size_t i) { return key(old[i].id1, old[i].id2); };
  // Run r: candidates [pairStart[r], pairStart[r+1]), old records [oldStart[r], oldStart[r+1]);
  // a run never starts inside a group of equal keys (a pair seen through several images).
  std::vector<std::size_t> pairStart(static_cast<std::size_t>(runs) + 1, n), oldStart(pairStart.size(), old.size());
  for (std::size_t r = 0; r < static_cast<std::size_t>(runs); ++r)
  {
    std::size_t p = n * r / static_cast<std::size_t>(runs);
    while (p > 0 && p < n && pairs[p].key == pairs[p - 1].key)
      ++p;
    pairStart[r] = p;
    if (r == 0)
      oldStart[r] = 0;
    else if (p < n)
      oldStart[r] = static_cast<std::size_t>(
          std::lower_bound(old.begin(), old.end(), pairs[p].key,
                           [](const Contact& c, PairKey k) { return key(c.id1, c.id2) < k; })
          - old.begin());
  }
  // Kept when no longer a candidate: a contact held by a bond, or one the masks refuse now (a
  // mask changed during it): as in Yade, masks decide which contacts begin, not which end.
  auto kept = [&](std::size_t i) {
    return old[i].real
           && ((withExtra && !oldExtra[i].cohesionBroken)
               || (filter.masks
                   && !b.masksAllow(static_cast<std::size_t>(old[i].id1), static_cast<std::size_t>(old[i].id2),
                                    filter.avoidSelfInteractionMask)));
  };
  // The merge of run r: keep(o) for an old record that stays, fresh(p) for a new candidate.
  auto walk = [&](std::size_t r, auto&& keep, auto&& fresh) {
    std::size_t o = oldStart[r];
    const std::size_t oldEnd = oldStart[r + 1];
    for (std::size_t p = pairStart[r]; p < pairStart[r + 1]; ++p)
    {
      const PairKey k = pairs[p].key;
      for (; o < oldEnd && oldKey(o) < k; ++o)
        if (kept(o))
          keep(o);
      // The same pair through the same periodic image keeps its history.
      if (o < oldEnd && oldKey(o) == k && old[o].cellDist == pairs[p].cellDist)
        keep(o++);
      else
        fresh(p);
    }
    for (; o < oldEnd; ++o)
      if (kept(o))
        keep(o);
  };
  // Each run's record count: its candidates, plus, with bonds or masks, the records kept (the
  // counting pass reads every old record: without them it would cost as much as the merge).
  std::vector<std::size_t> offset(static_cast<std::size_t>(runs) + 1, 0);
  for (std::size_t r = 0; r < static_cast<std::size_t>(runs); ++r)
    offset[r + 1] = pairStart[r + 1] - pairStart[r];
  if (withExtra || filter.masks)
  {
#pragma omp parallel for schedule(static, 1) num_threads(runs) if (runs > 1)
    for (int r = 0; r < runs; ++r)
    {
      std::size_t count = 0;
      auto one = [&](std::size_t) { ++count; };
      walk(static_cast<std::size_t>(r), one, one);
      offset[static_cast<std::size_t>(r) + 1] = count;
    }
  }
  for (std::size_t r = 0; r < static_cast<std::size_t>(runs); ++r)
    offset[r + 1] += offset[r];
  const std::size_t total = offset.back();
  // The spare list's old records are dead: grow it with room to spare, every record of the new
  // storage constructed at once, so that its (huge, see HugePageAllocator) pages are faulted in
  // here and not a few at a time by the later re-detections that lengthen the list (each of
  // which would then pay page faults; docs/dem.md, "Measurements behind the code").
  auto reserveTouched = [total](auto& records) {
    if (records.capacity() >= total)
      return;
    records.clear();
    records.resize(total + total / 4);
  };
  reserveTouched(merged);
  merged.resize(total);
  if (withExtra)
    reserveTouched(mergedExtra);
  mergedExtra.resize(withExtra ? total : 0);
#pragma omp parallel for schedule(static, 1) num_threads(runs) if (runs > 1)
  for (int r = 0; r < runs; ++r)
  {
    std::size_t at = offset[static_cast<std::size_t>(r)];
    walk(
        static_cast<std::size_t>(r),
        [&](std::size_t o) {
          if (withExtra)
            mergedExtra[at] = oldExtra[o];
          merged[at++] = old[o];
        },
        [&](std::size_t p) {
          if (withExtra)
            mergedExtra[at] = ContactExtra{};
          merged[at++] = newContact(b, pairs[p]);
        });
  }
}
} // namespace

bool Collider::acrossProcesses(const Domain& domain, bool rebuild, Displacements& all)
{
  std::array<double, 11> v{rebuild ? -1.0 : 0.0, -all.sphere2, -all.sphereSpread2, -all.other2,
                           all.low[0], all.low[1], all.low[2], -all.high[0], -all.high[1], -all.high[2],
                           all.nonFinite ? -1.0 : 0.0};
  domain.min(v);
  all.sphere2 = -v[1];
  all.sphereSpread2 = -v[2];
  all.other2 = -v[3];
  all.low = Vec3(v[4], v[5], v[6]);
  all.high = -Vec3(v[7], v[8], v[9]);
  all.nonFinite = v[10] < 0;
  return v[0] < 0;
}

Collider::SkinCheck Collider::skinCheck(const Scene& scene) const
{
  SkinCheck check;
  if (scene.bodiesVersion != seenBodiesVersion_ || referencePos_.size() != scene.bodies.size())
  {
    check.rebuild = true;
    return check;
  }
  // A pair's distance changes by at most the two bodies' displacements beyond the cell's
  // homogeneous deformation A = H H_ref^-1, plus (A - I) applied to its old distance (at most
  // the interaction range): re-detect before that can exceed the skin.
  const Bodies& b = scene.bodies;
  check.affine = scene.periodic ? Mat3(scene.cell.hSize * referenceCellInverse_) : Mat3::Identity();
  const double strainReach = (check.affine - Mat3::Identity()).norm() * referenceRange_;
  if (strainReach >= skin_)
  {
    check.rebuild = true;
    return check;
  }
  const double limit = 0.5 * (skin_ - strainReach);
  check.limit2 = limit * limit;
  check.common = common_;
  check.otherPairs = !convex_.empty();
  check.deformed = scene.periodic && check.affine != Mat3::Identity();
  // A turning body's surface also moves by its rotation: at most its reach times the angle.
  for (std::size_t k = 0; k < turning_.size() && !check.rebuild; ++k)
  {
    const Turning& t = turning_[k];
    const auto i = static_cast<std::size_t>(t.id);
    check.rebuild = (b.pos[i] - referencePos_[i]).norm() + t.reach * b.ori[i].angularDistance(t.ori) > limit;
  }
  return check;
}

void Collider::Displacements::add(const Displacements& d)
{
  sphere2 = std::max(sphere2, d.sphere2);
  sphereSpread2 = std::max(sphereSpread2, d.sphereSpread2);
  other2 = std::max(other2, d.other2);
  low = low.cwiseMin(d.low);
  high = high.cwiseMax(d.high);
  nonFinite = nonFinite || d.nonFinite;
}

Collider::Displacements Collider::displacementsIn(const Scene& scene, const SkinCheck& check, std::int64_t first,
                                                  std::int64_t last) const
{
  const Bodies& b = scene.bodies;
  Displacements d;
  for (auto i = static_cast<std::size_t>(first); i < static_cast<std::size_t>(last); ++i)
  {
    if (!b.alive[i] || b.shape[i] == ShapeKind::Clump) // a clump's members have its surface
      continue;
    const Vec3 reference = check.deformed ? Vec3(check.affine * referencePos_[i]) : referencePos_[i];
    const Vec3 moved = b.pos[i] - reference;
    d.nonFinite = d.nonFinite || !std::isfinite(moved.squaredNorm());
    if (b.shape[i] == ShapeKind::Sphere)
    {
      d.sphere2 = std::max(d.sphere2, moved.squaredNorm());
      d.sphereSpread2 = std::max(d.sphereSpread2, (moved - check.common).squaredNorm());
      d.low = d.low.cwiseMin(moved);
      d.high = d.high.cwiseMax(moved);
    }
    else
      d.other2 = std::max(d.other2, moved.squaredNorm());
  }
  return d;
}

bool Collider::mustRebuild(const SkinCheck& check, const Displacements& all)
{
  const double limit2 = check.limit2;
  if (all.nonFinite)
    return true;
  // Pairs of two other bodies (blocks, a wall and a block): each within half the skin.
  if (check.otherPairs && all.other2 > limit2)
    return true;
  // A sphere and another body: the two displacements within the skin.
  if (all.other2 >= 0 && std::sqrt(all.sphere2) + std::sqrt(all.other2) > 2 * std::sqrt(limit2))
    return true;
  // Two spheres: each within half the skin of the common displacement, or of none.
  return all.sphereSpread2 > limit2 && all.sphere2 > limit2;
}

Vec3 Collider::commonOf(const Displacements& all)
{
  return (all.low.array() <= all.high.array()).all() ? Vec3(0.5 * (all.low + all.high)) : Vec3::Zero();
}

bool Collider::needsRebuild(const Scene& scene)
{
  const SkinCheck check = skinCheck(scene);
  if (check.rebuild && !scene.domain)
    return true;
  auto measure = [&](std::int64_t first, std::int64_t last) { return displacementsIn(scene, check, first, last); };
  Displacements all = check.rebuild ? Displacements{}
                                    : balancedFor(skinRanges_, static_cast<std::int64_t>(scene.bodies.size()),
                                                  Displacements{}, measure, [](Displacements a, const Displacements& c) {
                                                    a.add(c);
                                                    return a;
                                                  });
  // Split over processes: all decide from everyone's displacements, and re-detect together.
  if (scene.domain && acrossProcesses(*scene.domain, check.rebuild, all))
    return true;
  noteDisplacements(all);
  return mustRebuild(check, all);
}

void Collider::run(Scene& scene)
{
  timingDeltas.start(scene.timingEnabled);
  const bool rebuilding = needsRebuild(scene);
  timingDeltas.checkpoint("skin check");
  if (rebuilding)
  {
    // Split over processes: bodies that left this process's region move first, and the ghosts
    // are taken again (Domain::beforeDetection; the step's scheduler calls it on its own path).
    if (scene.domain)
      scene.domain->beforeDetection(scene);
    rebuild(scene);
  }
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
  boxes_.clear();
  convex_.clear();
  double blockRmin = std::numeric_limits<double>::infinity();
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
    else if (b.shape[i] == ShapeKind::Facet && b.facets[static_cast<std::size_t>(b.shapeIndex[i])].bounded)
      facets.push_back(static_cast<BodyId>(i));
    else if (b.shape[i] == ShapeKind::Box)
      boxes_.push_back(static_cast<BodyId>(i));
    else if (b.shape[i] == ShapeKind::PotentialBlock || b.shape[i] == ShapeKind::PotentialParticle)
    {
      convex_.push_back(static_cast<BodyId>(i));
      blockRmin = std::min(blockRmin, referenceLength(b, i));
    }
    // a clump has no surface: its members interact
  }
  if (scene.domain) // the skin and the cells from the radii of every process's spheres
  {
    rmin = scene.domain->min(rmin);
    rmax = -scene.domain->min(-rmax);
  }
  Collider::PairFilter filter{avoidSelfInteractionMask, (avoidSelfInteractionMask & 1) != 0};
  for (std::size_t i = 0; i < b.size() && !filter.masks; ++i)
    filter.masks = b.alive[i] && b.groupMask[i] != 1;
  // Without spheres, a negative verletDist is a fraction of the smallest block's or particle's R.
  // Split over processes, rmin is every process's: one left without spheres (a silo's top
  // emptied) keeps their skin, not none, which would have every process re-detect at every step.
  const double smallest = std::isfinite(rmin) ? rmin : blockRmin;
  skin_ = verletDist >= 0 ? verletDist : (std::isfinite(smallest) ? -verletDist * smallest : 0.0);

  // Not cleared for the open scene: its merge overwrites every entry, and resizing a cleared
  // list would first zero the whole of it, on one thread.
  std::vector<Candidate>& pairs = pairs_;
  if (scene.periodic)
  {
    pairs.clear();
    periodicSpherePairs(b, spheres, scene.cell, rmax, skin_, allowBiggerThanPeriod, filter, pairs);
  }
  else
  {
    grid_.build(b, spheres, 2 * rmax + skin_);
    timingDeltas.checkpoint("re-detection: binning");
    spherePairs(b, spheres, grid_, skin_, filter, perThread_);
  }
  timingDeltas.checkpoint("re-detection: sphere pairs");
  // The other shapes' pairs, few, sorted on their own and merged in.
  std::vector<Candidate>& others = boundaryPairs_;
  others.clear();
  if (scene.periodic)
    // Every sphere against each facet or box: periodic scenes with many of them are rare.
    for (const std::vector<BodyId>* kind : {&facets, &boxes_})
      for (BodyId k : *kind)
        periodicBoundaryPairs(b, k, spheres, scene.cell, rmax, skin_, allowBiggerThanPeriod, filter, others);
  else
  {
    for (BodyId f : facets)
      facetPairs(b, f, grid_, rmax, skin_, filter, others);
    for (BodyId k : boxes_)
      boxPairs(b, k, grid_, rmax, skin_, filter, others);
  }
  if (!convex_.empty())
    convexPairs(b, convex_, walls, skin_, filter, others);
  for (BodyId w : walls)
  {
    const auto wi = static_cast<std::size_t>(w);
    const WallShape& wall = b.walls[static_cast<std::size_t>(b.shapeIndex[wi])];
    for (BodyId s : spheres)
    {
      const auto si = static_cast<std::size_t>(s);
      const double d = b.pos[si][wall.axis] - b.pos[wi][wall.axis];
      const bool side = wall.sense == 0 || (wall.sense > 0 ? d > -b.radius[si] : d < b.radius[si]);
      if (side && std::abs(d) < b.radius[si] + skin_ && filter(b, wi, si))
        others.push_back({key(w, s), Eigen::Vector3i::Zero()});
    }
  }
  timingDeltas.checkpoint("re-detection: boundary pairs");
  if (scene.periodic)
  {
    // The periodic search finds pairs out of order (and a pair may come through two images).
    pairs.insert(pairs.end(), others.begin(), others.end());
    std::sort(pairs.begin(), pairs.end(), byKey);
  }
  else
  {
    std::sort(others.begin(), others.end(), byKey);
    mergeCandidates(perThread_, others, pairs);
  }
  if (scene.domain) // the pairs this process computes (Domain::computesPair)
    std::erase_if(pairs, [&](const Candidate& c) {
      return !scene.domain->computesPair(static_cast<std::size_t>(c.key >> 32), static_cast<std::size_t>(c.key & 0xffffffffu));
    });
  timingDeltas.checkpoint("re-detection: sort");

  ContactList& old = scene.contacts.list;
  ContactExtraList& oldExtra = scene.contacts.extra;
  const bool withExtra = scene.contacts.extraState() != nullptr;
  mergeContacts(b, pairs, old, oldExtra, filter, spare_, spareExtra_);
  old.swap(spare_);
  if (withExtra)
    oldExtra.swap(spareExtra_);
  timingDeltas.checkpoint("re-detection: merge");
  scene.contacts.index(b.size());
  timingDeltas.checkpoint("re-detection: index");
  referencePos_ = b.pos;
  turning_.clear();
  for (BodyId id : convex_)
    turning_.push_back({id, boundingRadius(b, static_cast<std::size_t>(id)), b.ori[static_cast<std::size_t>(id)]});
  for (const std::vector<BodyId>* kind : {&facets_, &boxes_})
    for (BodyId id : *kind)
    {
      const auto i = static_cast<std::size_t>(id);
      if (b.clumpId[i] < 0)
        continue;
      const auto s = static_cast<std::size_t>(b.shapeIndex[i]);
      const double reach = b.shape[i] == ShapeKind::Box ? b.boxes[s].extents.norm()
                                                        : std::max({b.facets[s].vertices[0].norm(), b.facets[s].vertices[1].norm(),
                                                                    b.facets[s].vertices[2].norm()});
      turning_.push_back({id, reach, b.ori[i]});
    }
  referenceCellInverse_ = scene.cell.hSize.inverse();
  referenceRange_ = 2 * rmax + skin_;
  seenBodiesVersion_ = scene.bodiesVersion;
  common_ = Vec3::Zero();
  ++rebuilds;
}
std::optional<Collider::Bound> Collider::boundOf(const Scene& scene, BodyId id) const
{
  const Bodies& b = scene.bodies;
  const auto i = static_cast<std::size_t>(id);
  if (id < 0 || i >= b.size() || i >= referencePos_.size() || seenBodiesVersion_ != scene.bodiesVersion || !b.alive[i]
      || b.shape[i] == ShapeKind::Clump)
    return std::nullopt;
  const Vec3 ref = referencePos_[i];
  const auto s = static_cast<std::size_t>(b.shapeIndex[i]);
  Vec3 lo = ref, hi = ref;
  switch (b.shape[i])
  {
  case ShapeKind::Sphere:
    lo -= Vec3::Constant(b.radius[i]);
    hi += Vec3::Constant(b.radius[i]);
    break;
  case ShapeKind::Wall:
  {
    const double inf = std::numeric_limits<double>::infinity();
    const int axis = b.walls[s].axis;
    lo = Vec3::Constant(-inf);
    hi = Vec3::Constant(inf);
    lo[axis] = hi[axis] = ref[axis];
    break;
  }
  case ShapeKind::Facet:
    for (const Vec3& v : b.facets[s].vertices)
    {
      const Vec3 corner = ref + b.ori[i] * v;
      lo = lo.cwiseMin(corner);
      hi = hi.cwiseMax(corner);
    }
    break;
  case ShapeKind::Box:
  {
    const Vec3 half = b.ori[i].toRotationMatrix().cwiseAbs() * b.boxes[s].extents;
    lo -= half;
    hi += half;
    break;
  }
  default: // Potential Blocks and Particles: their box now, moved back to the reference
    if (b.shape[i] == ShapeKind::PotentialBlock)
      potentialBlockAabb(b, i, lo, hi);
    else
      potentialParticleAabb(b, i, lo, hi);
    lo += ref - b.pos[i];
    hi += ref - b.pos[i];
  }
  return Bound{lo - Vec3::Constant(skin_), hi + Vec3::Constant(skin_), ref, skin_};
}
} // namespace talus::dem
