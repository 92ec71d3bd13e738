#pragma once

#include "dem/core/Bodies.h"
#include "dem/base/CountingSort.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

namespace talus::dem
{
/// Spheres binned into cubic cells at least as wide as the largest interaction range
/// (linked cells, stored as a counting sort). Rebuilt in place: its arrays keep their capacity,
/// so re-detection allocates nothing once the scene has settled in size.
class CellGrid
{
public:
  using Cell = std::array<int, 3>;

  /// Bin `spheres` (ids into `b`); `range` is the largest centre distance that can interact.
  /// @param b the scene's bodies (positions and radii are copied into the grid)
  /// @param spheres the ids binned; kept by reference nowhere
  /// @param range the smallest cell width (m); cells grow by 1.5 until there are at most about
  ///        8 per sphere
  /// @throws std::runtime_error naming a body whose centre is not finite, or the two extreme
  ///         bodies when the centres' extent overflows
  void build(const Bodies& b, const std::vector<BodyId>& spheres, double range)
  {
    const auto n = static_cast<std::int64_t>(spheres.size());
    const Extremes ends = extremes(b, spheres);
    lo_ = ends.lo;
    const Vec3 hi = ends.hi;
    // Coarser cells if the box is sparse, whatever its shape (a flat or a long box too), so
    // that the cell count, hence memory, stays proportional to the sphere count.
    h_ = std::max(range, 1e-300);
    const Vec3 extent = (hi - lo_).cwiseMax(Vec3::Constant(1e-300));
    const double cellBudget = 8.0 * static_cast<double>(spheres.size()) + 27;
    while (((extent / h_).array().floor() + 1).prod() > cellBudget)
      h_ *= 1.5;
    for (int d = 0; d < 3; ++d)
      dims_[static_cast<std::size_t>(d)] = static_cast<int>(std::floor(extent[d] / h_)) + 1;

    cellOfSphere_.resize(spheres.size());
#pragma omp parallel for schedule(static) if (n >= parallelLoopMinimum)
    for (std::int64_t s = 0; s < n; ++s)
      cellOfSphere_[static_cast<std::size_t>(s)] = flat(cellOf(b.pos[static_cast<std::size_t>(spheres[static_cast<std::size_t>(s)])]));
    sorted_.resize(spheres.size());
    packed_.resize(spheres.size());
    stableCountingSort(
        n, static_cast<std::int64_t>(dims_[0]) * dims_[1] * dims_[2], start_,
        [this](std::int64_t s, auto&& emit) { emit(cellOfSphere_[static_cast<std::size_t>(s)], 0); },
        [&](std::int64_t s, int, std::int64_t slot) {
          const BodyId id = spheres[static_cast<std::size_t>(s)];
          const auto i = static_cast<std::size_t>(id), e = static_cast<std::size_t>(slot);
          sorted_[e] = id;
          packed_[e] = {b.pos[i][0], b.pos[i][1], b.pos[i][2], b.radius[i]};
        });
  }

  /// A binned sphere's centre and radius, stored in cell order next to its cell's neighbours, so
  /// that a neighbour search reads them in runs instead of one body at a time.
  struct Packed
  {
    double x, y, z, radius;
  };

  /// Call f(first, last) for each run [first, last) of binned entries (see entry(), packed())
  /// in the 3x3x3 cells around the cell of the s-th sphere given to build(): one run per row of
  /// three cells along x, which lie next to each other in cell order. Runs come in the order
  /// of forEachInBox over the same cells.
  /// @param s the sphere's index in the list given to build() (not its body id)
  /// @param f f(first, last) for each run of entries
  template <class F>
  void forEachRunAround(std::size_t s, F&& f) const
  {
    const std::int64_t k = cellOfSphere_[s];
    const int cx = static_cast<int>(k % dims_[0]);
    const int cy = static_cast<int>((k / dims_[0]) % dims_[1]);
    const int cz = static_cast<int>(k / (static_cast<std::int64_t>(dims_[0]) * dims_[1]));
    const int x0 = std::max(cx - 1, 0), x1 = std::min(cx + 1, dims_[0] - 1);
    for (int z = std::max(cz - 1, 0); z <= std::min(cz + 1, dims_[2] - 1); ++z)
      for (int y = std::max(cy - 1, 0); y <= std::min(cy + 1, dims_[1] - 1); ++y)
        f(start_[static_cast<std::size_t>(flat({x0, y, z}))], start_[static_cast<std::size_t>(flat({x1, y, z})) + 1]);
  }
  /// @param e a binned entry, from a run of forEachRunAround
  /// @return the entry's body id
  [[nodiscard]] BodyId entry(std::int64_t e) const { return sorted_[static_cast<std::size_t>(e)]; }
  /// @param e a binned entry, from a run of forEachRunAround
  /// @return the entry's centre and radius as they were at build()
  [[nodiscard]] const Packed& packed(std::int64_t e) const { return packed_[static_cast<std::size_t>(e)]; }

  /// Cell width.
  [[nodiscard]] double width() const { return h_; }

  /// Call f(sphere id) for every sphere binned in cells overlapping the box [a, b].
  /// @param a, b the box's low and high corners (m); parts outside the grid fall in its edge cells
  /// @param f f(id), in cell order
  template <class F>
  void forEachInBox(const Vec3& a, const Vec3& b, F&& f) const
  {
    const Cell c0 = cellOf(a), c1 = cellOf(b);
    for (int z = c0[2]; z <= c1[2]; ++z)
      for (int y = c0[1]; y <= c1[1]; ++y)
        for (int x = c0[0]; x <= c1[0]; ++x)
        {
          const auto k = static_cast<std::size_t>(flat({x, y, z}));
          for (std::int64_t e = start_[k]; e < start_[k + 1]; ++e)
            f(sorted_[static_cast<std::size_t>(e)]);
        }
  }

private:
  /// The box of the sphere centres (zero without spheres).
  struct Extremes
  {
    Vec3 lo = Vec3::Zero(), hi = Vec3::Zero();
  };
  /// @throws std::runtime_error naming the body whose centre is not finite, or the two
  /// extreme bodies when the box is too large for doubles (its extent overflows): both come of
  /// a step that moved a body absurdly far (a huge velocity or time step).
  static Extremes extremes(const Bodies& b, const std::vector<BodyId>& spheres)
  {
    if (spheres.empty())
      return {};
    Extremes e{Vec3::Constant(std::numeric_limits<double>::infinity()),
               Vec3::Constant(-std::numeric_limits<double>::infinity())};
    // min and max pass a NaN by: 0 x each coordinate catches it (and an infinity).
    double nonFinite = 0;
    for (BodyId id : spheres)
    {
      const Vec3& p = b.pos[static_cast<std::size_t>(id)];
      e.lo = e.lo.cwiseMin(p);
      e.hi = e.hi.cwiseMax(p);
      nonFinite += 0 * p.sum();
    }
    if (nonFinite == 0 && (e.hi - e.lo).allFinite())
      return e;
    // Rare: a second pass finds whom to name.
    for (BodyId id : spheres)
      if (!b.pos[static_cast<std::size_t>(id)].allFinite())
        throw lostBody(b, id, "has a non-finite position");
    if ((e.hi - e.lo).allFinite())
      return e; // (finite coordinates whose sum overflowed)
    int d = 0;
    while (std::isfinite(e.hi[d] - e.lo[d]))
      ++d;
    auto at = [&](double x) {
      return *std::find_if(spheres.begin(), spheres.end(),
                           [&](BodyId id) { return b.pos[static_cast<std::size_t>(id)][d] == x; });
    };
    const BodyId low = at(e.lo[d]), high = at(e.hi[d]);
    throw std::runtime_error("bodies " + std::to_string(low) + " and " + std::to_string(high)
                             + " are too far apart along axis " + std::to_string(d) + " (at "
                             + describe(b.pos[static_cast<std::size_t>(low)]) + " and "
                             + describe(b.pos[static_cast<std::size_t>(high)])
                             + "): the scene's extent overflows; a velocity or O.dt too large moved them");
  }

public:
  /// The error for body `id`, whose position (`what`) a step made absurd.
  /// @param b the scene's bodies (the message gives the body's position and velocity)
  /// @param id the body
  /// @param what what is wrong with its position ("has a non-finite position", ...)
  /// @return the exception, for the caller to throw
  static std::runtime_error lostBody(const Bodies& b, BodyId id, const std::string& what)
  {
    const auto i = static_cast<std::size_t>(id);
    return std::runtime_error("body " + std::to_string(id) + " " + what + " " + describe(b.pos[i]) + " (velocity "
                              + describe(b.vel[i])
                              + "): a velocity or O.dt so large that a step moved it absurdly far, or a position "
                              + "set so from Python (O.positions(), state.pos)");
  }

private:
  static std::string describe(const Vec3& v)
  {
    std::ostringstream text;
    text << "(" << v[0] << ", " << v[1] << ", " << v[2] << ")";
    return text.str();
  }

  [[nodiscard]] int coord(double x, int d) const
  {
    return std::clamp(static_cast<int>(std::floor((x - lo_[d]) / h_)), 0, dims_[static_cast<std::size_t>(d)] - 1);
  }
  [[nodiscard]] Cell cellOf(const Vec3& p) const { return {coord(p[0], 0), coord(p[1], 1), coord(p[2], 2)}; }
  [[nodiscard]] std::int64_t flat(const Cell& c) const
  {
    return (static_cast<std::int64_t>(c[2]) * dims_[1] + c[1]) * dims_[0] + c[0];
  }

  Vec3 lo_ = Vec3::Zero();
  double h_ = 1;
  Cell dims_{1, 1, 1};
  std::vector<std::int64_t> start_; ///< spheres of cell k: sorted_[start_[k] .. start_[k+1])
  std::vector<BodyId> sorted_;
  std::vector<Packed> packed_; ///< centre and radius of sorted_[e]
  std::vector<std::int64_t> cellOfSphere_;
};
} // namespace talus::dem
