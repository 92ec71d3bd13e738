#pragma once

// When two spheres touch, to the last bit as in Yade 2023.02a. Its Eigen is built without
// vectorisation, so a squared norm sums x^2 + (y^2 + z^2) (Eigen's unrolled halves), where
// Talus's vectorised Eigen sums (x^2 + y^2) + z^2. Ig2_Sphere_Sphere_ScGeom begins a contact
// while (r1 + r2)^2 - d^2 >= 0 and the law ends a real one when its penetration
// r1 + r2 - sqrt(d^2), taken after the square root, is negative: a real contact outlives the
// squared test by up to a rounding of sqrt. In a lattice packed with no gap (regularHexa), where
// pairs touch exactly, either difference changes which contacts exist, and with them the step
// GlobalStiffnessTimeStepper sets.
#include "dem/base/types.h"

namespace talus::dem
{
/// |d|^2 in Yade's order: x^2 + (y^2 + z^2).
/// @param x, y, z the components of d
/// @return the squared norm
inline double yadeSquaredNorm(double x, double y, double z) { return x * x + (y * y + z * z); }
/// |d|^2 in Yade's order: x^2 + (y^2 + z^2).
/// @param d the centre-to-centre vector
/// @return the squared norm
inline double yadeSquaredNorm(const Vec3& d) { return yadeSquaredNorm(d[0], d[1], d[2]); }

/// Whether two spheres at squared distance dist2 begin a contact (Ig2_Sphere_Sphere_ScGeom's
/// test: not when dist2 exceeds reach^2; a NaN goes on, as in Yade).
/// @param dist2 the squared centre distance (yadeSquaredNorm)
/// @param reach the sum of the radii
/// @return whether they touch
inline bool spheresBegin(double dist2, double reach) { return !(dist2 > reach * reach); }

/// Whether a real sphere contact of this penetration (r1 + r2 - sqrt(dist2)) holds on: Yade's
/// laws erase it only below zero (a NaN holds).
/// @param penetration the overlap (m)
/// @return whether the contact stays real
inline bool spheresHold(double penetration) { return !(penetration < 0); }
} // namespace talus::dem
