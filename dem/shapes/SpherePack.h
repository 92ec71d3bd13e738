#pragma once

#include "dem/base/types.h"

#include <vector>

namespace talus::dem
{
/// A list of spheres (centres and radii) that is not a simulation yet: Yade's SpherePack.
/// `hSize` is the cell of a periodic packing (edges as columns, as Cell::hSize; diagonal for
/// an axis-aligned one, Yade's cellSize) and zero for a packing that is not periodic.
struct SpherePack
{
  std::vector<Vec3> centers;
  std::vector<double> radii;
  Mat3 hSize = Mat3::Zero();
  /// The most spheres a packing generator makes: beyond it a generator refuses before
  /// allocating (a radius too small for the box, a count mistyped), as no scene could hold them.
  static constexpr long maxSpheres = 100'000'000;
  /// Factor by which makeCloud scaled a size distribution down to fit `num` spheres (1: none).
  double appliedPsdScaling = 1;

  /// Yade's makeCloud: random non-overlapping spheres in the box [minCorner, maxCorner] (a flat
  /// box, one size 0, gives a 2D packing). Radii: uniform rMean (1 +- rRelFuzz); or, with
  /// rMean < 0 and num > 0, rMean from `porosity`; or a size distribution (psdSizes are
  /// diameters, psdCumm their cumulative fractions, by number or, with distributeMass, by
  /// mass). With num > 0 radii are deterministic and decreasing; if they do not fit, the
  /// distribution is scaled down (porosity raised) and the cloud redone. Each sphere gets up to
  /// 1000 random tries. The random numbers are std::mt19937(seed) with
  /// std::uniform_real_distribution (random_device if seed < 0), drawn in Yade's order, so a
  /// seeded cloud is the same as Yade's.
  ///
  /// Periodic clouds fill the cell [minCorner, maxCorner), or, with a non-zero `cell`, the
  /// parallelepiped minCorner + cell u, u in [0, 1)^3, of a sheared cell (Yade's hSize argument;
  /// maxCorner is then unused). No sphere overlaps another or its own images: every image within
  /// reach is tested, whatever the shear and the sizes (Yade's test for a sheared cell looks at
  /// the nearest image in fractional coordinates only, which is exact while two radii stay below
  /// half the distance between the cell's faces, and checks no sphere against its own image).
  /// @param minCorner, maxCorner the box's corners (m)
  /// @param rMean, rRelFuzz the mean radius (m; < 0 with num > 0: from porosity) and the radii's
  ///        relative spread
  /// @param num the number of spheres; < 0: as many as the tries place
  /// @param periodic fill a periodic cell (images tested for overlaps)
  /// @param porosity the porosity that sets rMean when rMean < 0
  /// @param psdSizes, psdCumm a size distribution (diameters in m, cumulative fractions from 0
  ///        to 1); empty: none
  /// @param distributeMass psdCumm counts mass, not number
  /// @param seed the random seed (< 0: random_device)
  /// @param cell the sheared cell's edges as columns (m); zero: the box
  /// @return the number of spheres created (may be below num when rMean is given)
  /// @throws std::invalid_argument naming the inconsistent parameter, when the largest
  /// sphere asked for does not fit in the cell (its diameter reaches the shortest period), or
  /// when num, or the spheres of rMean the box could hold, exceed maxSpheres
  long makeCloud(const Vec3& minCorner, const Vec3& maxCorner, double rMean, double rRelFuzz, int num, bool periodic,
                 double porosity, const std::vector<double>& psdSizes, const std::vector<double>& psdCumm,
                 bool distributeMass, int seed, const Mat3& cell = Mat3::Zero());
};
} // namespace talus::dem
