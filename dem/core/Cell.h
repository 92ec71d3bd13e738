#pragma once

#include "dem/base/types.h"

#include <algorithm>
#include <stdexcept>
#include <string>

namespace talus::dem
{
/// Rotation rate (axial vector) of the antisymmetric part of a velocity gradient: the spin that
/// homoDeform adds to the bodies' angular velocities.
/// @param L the velocity gradient (1/s)
/// @return the rotation rate (rad/s)
inline Vec3 spin(const Mat3& L) { return 0.5 * Vec3(L(2, 1) - L(1, 2), L(0, 2) - L(2, 0), L(1, 0) - L(0, 1)); }

/// The periodic cell (Yade's Cell): a parallelepiped whose edges are the columns of `hSize`,
/// repeated to fill space. Particles keep unwrapped positions; contacts across the boundary
/// carry the integer cell offset of their second body.
///
/// The cell deforms with the homogeneous velocity gradient `velGrad`: each step
/// H <- (I + L dt) H and trsf <- (I + L dt) trsf (seed 3.6.1). With `homoDeform` the particles
/// follow the same field: their velocity holds the affine part L x plus their fluctuation.
struct Cell
{
  Mat3 hSize = Mat3::Identity();      ///< cell edges as columns
  Mat3 velGrad = Mat3::Zero();        ///< velocity gradient L
  Mat3 prevVelGrad = Mat3::Zero();    ///< L of the previous step (to recover fluctuations)
  Mat3 trsf = Mat3::Identity();       ///< deformation gradient accumulated since the reference
  bool homoDeform = true;

  /// The cell's volume (m^3), positive for a right-handed cell.
  [[nodiscard]] double volume() const { return hSize.determinant(); }
  /// Shift of the periodic image with integer offset c.
  /// @param c the image's cell offset along each edge
  /// @return the image's displacement from the original (m)
  [[nodiscard]] Vec3 shift(const Eigen::Vector3i& c) const { return hSize * c.cast<double>(); }
  /// Velocity of that image relative to the original (the affine field over the shift).
  /// @param c the image's cell offset along each edge
  /// @return the velocity difference (m/s)
  [[nodiscard]] Vec3 shiftVelocity(const Eigen::Vector3i& c) const { return velGrad * shift(c); }

  /// Advance the cell by one step of the current velocity gradient.
  /// @param dt the time step (s)
  /// @throws std::runtime_error (the cell unchanged) if the step would invert the cell
  void integrate(double dt)
  {
    const Mat3 step = Mat3::Identity() + velGrad * dt;
    // The cell's volume is multiplied by det(I + L dt): at or below zero it is flattened or
    // turned inside out, which no strain rate means.
    if (!(step.determinant() > 0))
      throw std::runtime_error("the periodic cell's velGrad inverts the cell in one step: det(I + velGrad*O.dt) = "
                               + std::to_string(step.determinant())
                               + " <= 0 (O.dt " + std::to_string(dt)
                               + "); velGrad times O.dt must stay well below 1 in magnitude");
    hSize = step * hSize;
    trsf = step * trsf;
    prevVelGrad = velGrad;
  }
};

// The periodic cell's near images (one cell away or less each way: nearly every pair across its
// boundary) as a table, made once for the kernels that would otherwise compute an image's shift
// per contact (the gather's and the laws' AVX2 lanes, docs/dem.md "Speed").
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
