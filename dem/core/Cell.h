#pragma once

#include "dem/base/types.h"

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
} // namespace talus::dem
