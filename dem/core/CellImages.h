#pragma once

// The periodic cell's near images (one cell away or less each way: nearly every pair across its
// boundary) as a table, made once for the kernels that would otherwise compute an image's shift
// per contact (the gather's and the laws' AVX2 lanes, docs/dem.md "Speed").
#include "dem/core/Cell.h"

#include <algorithm>

namespace talus::dem
{
/// A vector per near image: lanes 0 to 2 the value, lane 3 zero, aligned for whole vector loads.
/// Left unset until filled (fillNearImages).
struct alignas(32) NearImageRows
{
  double row[27][4];
};

/// The row of the image with cell offset d (Contact::cellDist) in NearImageRows,
/// 9 (d0 + 1) + 3 (d1 + 1) + (d2 + 1), or -1 if it lies more than one cell away along some edge.
[[nodiscard]] inline int nearImage(const Eigen::Vector3i& d)
{
  const unsigned a = static_cast<unsigned>(d[0]) + 1U, b = static_cast<unsigned>(d[1]) + 1U,
                 c = static_cast<unsigned>(d[2]) + 1U;
  return std::max(std::max(a, b), c) < 3U ? static_cast<int>(9U * a + 3U * b + c) : -1;
}

/// Fill `rows` with value(d) (a Vec3) of each near image d, the row of no image (d = 0) with +0:
/// what a pair inside the cell adds, where Cell::shift(0) may hold -0.
template <class Value>
void fillNearImages(NearImageRows& rows, const Value& value)
{
  double* row = rows.row[0];
  for (int a = -1; a <= 1; ++a)
    for (int b = -1; b <= 1; ++b)
      for (int c = -1; c <= 1; ++c, row += 4)
      {
        const Vec3 v = value(Eigen::Vector3i(a, b, c));
        row[0] = v[0];
        row[1] = v[1];
        row[2] = v[2];
        row[3] = 0;
      }
  for (double& v : rows.row[13])
    v = 0;
}

/// The shifts of a cell's near images and their velocities, as contactGeometry takes them for
/// a pair across the boundary (zero for one inside), or nothing without a cell.
struct CellImages
{
  NearImageRows shift, velocity;
  /// @param cell the periodic cell, or null (nothing made)
  explicit CellImages(const Cell* cell)
  {
    if (cell == nullptr)
      return;
    fillNearImages(shift, [cell](const Eigen::Vector3i& d) { return cell->shift(d); });
    fillNearImages(velocity, [cell](const Eigen::Vector3i& d) { return cell->shiftVelocity(d); });
  }
};
} // namespace talus::dem
