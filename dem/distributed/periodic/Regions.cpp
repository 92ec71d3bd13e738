#include "dem/distributed/periodic/Regions.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace talus::dem::distributed
{
Regions::Regions(const Cell& cell) : periodic_(true), inverse_(cell.hSize.inverse()) {}

Vec3 Regions::coordinates(const Vec3& x) const
{
  if (!periodic_)
    return x;
  const Vec3 f = inverse_ * x;
  return f - f.array().floor().matrix();
}

Vec3 Regions::coordinatesBeside(const Vec3& x, const Vec3& beside) const
{
  if (!periodic_)
    return x;
  return inverse_ * x - (inverse_ * beside).array().floor().matrix();
}

Box Regions::withinCell(const Box& box) const
{
  if (!periodic_)
    return box;
  return {box.min.cwiseMax(Vec3::Zero()), box.max.cwiseMin(Vec3::Ones())};
}

bool Regions::reaches(const Vec3& x, const Box& box, double distance) const
{
  if (!periodic_)
    return distanceToBox(x, box) <= distance;
  const Vec3 f = coordinates(x);
  for (int d = 0; d < 3; ++d)
  {
    // Lattice planes of constant reduced coordinate d lie 1 / |row d of H^-1| apart: a point
    // within `distance` of another differs from it by at most this much in that coordinate.
    const double margin = distance * inverse_.row(d).norm();
    // RCB's outer boxes reach infinity: the bodies' coordinates lie in [0, 1]; a grown region's
    // finite bounds may lie beyond.
    // (Zoltan gives an outer box's bounds as the largest finite doubles.)
    const double far = std::numeric_limits<double>::max();
    const double low = (box.min[d] <= -far ? 0.0 : box.min[d]) - margin, high = (box.max[d] >= far ? 1.0 : box.max[d]) + margin;
    // The margin stays below one cell (the collider keeps the reach below the cell's width):
    // the images one cell either side are the only ones that can fall within.
    bool near = false;
    for (const double image : {f[d] - 1, f[d], f[d] + 1})
      near = near || (image >= low && image <= high);
    if (!near)
      return false;
  }
  return true;
}
} // namespace talus::dem::distributed
