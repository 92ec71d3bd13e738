#pragma once

// The rolling and twisting part: bending and twisting moments from the relative rotation of
// the two bodies (RotationState, MomentState in core/ContactExtra.h), elastic springs capped
// by a plastic moment proportional to the normal force.
#include "dem/core/Bodies.h"
#include "dem/core/Contacts.h"
#include "dem/core/EnergyTracker.h"
#include "dem/laws/parts/Coulomb.h"

#include <cmath>

namespace talus::dem::parts
{
/// Rotation vector (angle times unit axis, angle in [0, pi]) of a unit quaternion.
inline Vec3 rotationVector(Quat q)
{
  if (q.w() < 0)
    q.coeffs() = -q.coeffs();
  const double s = q.vec().norm();
  if (s == 0)
    return Vec3::Zero();
  return (2 * std::atan2(s, q.w()) / s) * q.vec();
}

/// Rotations count from now (ScGeom6D's reference orientations).
inline void startRotations(const Contact& c, RotationState& x, const Bodies& b)
{
  x.initialOrientation1 = b.ori[static_cast<std::size_t>(c.id1)];
  x.initialOrientation2 = b.ori[static_cast<std::size_t>(c.id2)];
  x.twist = 0;
  x.bending.setZero();
}

/// Moments of springs kr, ktw on the rotation of body 1 relative to body 2 since the start
/// (ScGeom6D's twist and bending): ktw twist n and kr bending.
inline void totalRotationMoments(const Contact& c, ContactExtra& x, const Bodies& b)
{
  const auto i1 = static_cast<std::size_t>(c.id1), i2 = static_cast<std::size_t>(c.id2);
  const Vec3 rotation
      = rotationVector((b.ori[i1] * x.initialOrientation1.conjugate()) * (x.initialOrientation2 * b.ori[i2].conjugate()));
  x.twist = rotation.dot(c.normal);
  x.bending = rotation - x.twist * c.normal;
  x.momentTwist = (x.twist * x.ktw) * c.normal;
  x.momentBending = x.bending * x.kr;
}

/// The same springs incrementally: the moments lose kr, ktw times this step's relative
/// rotation (w2 - w1) dt, split into its bending and twisting parts.
inline void incrementalRotationMoments(const Contact& c, MomentState& x, const Bodies& b, double dt)
{
  const Vec3 relativeRotation
      = (b.angVel[static_cast<std::size_t>(c.id2)] - b.angVel[static_cast<std::size_t>(c.id1)]) * dt;
  const Vec3 twist = c.normal.dot(relativeRotation) * c.normal;
  x.momentBending -= x.kr * (relativeRotation - twist);
  x.momentTwist -= x.ktw * twist;
}

/// Cap a moment at plastic * normal (plastic < 0: no cap); with `dissipates`, the excess is a
/// plastic slip of the moment's spring (the incremental form) whose work is booked when Track.
template <bool Track>
inline void capMoment(Vec3& moment, double plastic, double normal, double stiffness, bool dissipates,
                      ContactEnergy& energy)
{
  if (plastic < 0)
    return;
  const double max = plastic * normal, m = moment.norm();
  if (m <= max)
    return;
  const Vec3 trial = cap(moment, max / m);
  if constexpr (Track)
    if (dissipates)
      energy.plastDissip += plasticWork(trial, moment, stiffness);
}
} // namespace talus::dem::parts
