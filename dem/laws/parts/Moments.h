#pragma once

// The rolling and twisting part: bending and twisting moments from the relative rotation of
// the two bodies (RotationState, MomentState in core/ContactExtra.h), elastic springs capped
// by a plastic moment proportional to the normal force.
#include "dem/core/Bodies.h"
#include "dem/core/Contacts.h"
#include "dem/core/EnergyTracker.h"
#include "dem/laws/ContactLaw.h"
#include "dem/laws/parts/Coulomb.h"
#include "dem/laws/parts/Parameters.h"

#include <cmath>

namespace talus::dem::parts
{
/// Rotation vector (angle times unit axis, angle in [0, pi]) of a unit quaternion: the vector
/// part times angle / sin(angle / 2) = 2 atan(t) / (t w), t = tan(angle / 2) = |vec| / w. Below
/// a few degrees (t^2 <= 1/1024, the relative rotations of most bonds) atan(t) / t is its
/// series to t^10 (the next term is below 1e-19 of it): a polynomial in t^2 = |vec|^2 / w^2,
/// without the square root, atan2 and division of the general case, which cost the cohesive
/// law a quarter of its step. The two agree to round-off.
/// @return the vector (rad); zero for the identity
inline Vec3 rotationVector(Quat q)
{
  if (q.w() < 0)
    q.coeffs() = -q.coeffs();
  const double s2 = q.vec().squaredNorm();
  if (s2 == 0)
    return Vec3::Zero();
  const double w = q.w();
  if (s2 <= (1.0 / 1024) * (w * w))
  {
    const double t2 = s2 / (w * w);
    const double atanOverT
        = 1 - t2 * (1.0 / 3 - t2 * (1.0 / 5 - t2 * (1.0 / 7 - t2 * (1.0 / 9 - t2 * (1.0 / 11)))));
    return (2 * atanOverT / w) * q.vec();
  }
  const double s = std::sqrt(s2);
  return (2 * std::atan2(s, w) / s) * q.vec();
}

/// Rotations count from now (ScGeom6D's reference orientations).
/// @param x the contact's state: reference orientations set, twist and bending zeroed
inline void startRotations(const Contact& c, RotationState& x, const Bodies& b)
{
  x.initialOrientation1 = b.ori[static_cast<std::size_t>(c.id1)];
  x.initialOrientation2 = b.ori[static_cast<std::size_t>(c.id2)];
  x.twist = 0;
  x.bending.setZero();
}

/// Moments of springs kr, ktw on the rotation of body 1 relative to body 2 since the start
/// (ScGeom6D's twist and bending): ktw twist n and kr bending.
/// @param x the contact's state: twist, bending and both moments (N m) set
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
/// @param x the contact's state: both moments (N m) updated
/// @param dt the time step (s)
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
/// @param moment the moment (N m), capped in place
/// @param plastic the limit per unit normal force (m); < 0: none
/// @param normal the normal force's magnitude (N)
/// @param stiffness the moment spring's stiffness (N m/rad), for the dissipated work
/// @param dissipates book the excess's work (the incremental form only)
/// @param energy with Track and dissipates, the work added to plastDissip
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

// Moments parts of a law (PartsLaw's last part), objects with the Law2's parameters
// (parts/Parameters.h):
//   template <bool Track, class Motion> void force(Contact&, ContactExtra*, double fn,
//       const StepContext&, const Motion&, ContactEnergy&) const;   // fn: the damping part's
//   double addElastic(double elastic, const ContactExtra*) const;   // plus what its springs store
//   bool carriesMoments() const;   // its moments carry over to the next step (the geometry then
//                                  // turns them with the contact frame)

/// No moments.
struct NoMoments
{
  static constexpr bool usesExtra = false;
  /// Nothing to do.
  template <bool Track, class Motion>
  void force(Contact& /*c*/, ContactExtra* /*x*/, double /*fn*/, const StepContext& /*step*/,
             const Motion& /*motion*/, ContactEnergy& /*energy*/) const
  {
  }
  /// @param elastic the other parts' energy (J)
  /// @return elastic unchanged
  [[nodiscard]] double addElastic(double elastic, const ContactExtra* /*x*/) const { return elastic; }
  /// @return false: no moment
  [[nodiscard]] bool carriesMoments() const { return false; }
};

/// Bending and twisting springs kr, ktw on the relative rotation (Yade's CohFrictPhys moments)
/// of a contact with momentRotationLaw while it is bonded (always_use_moment_law: also after),
/// capped at maxRollPl |F_n| and maxTwistPl |F_n| when those are >= 0 (|F_n| of the normal
/// force vector, which a sliding bond in tension has dropped); no moment otherwise.
struct RotationMoments
{
  static constexpr bool usesExtra = true;
  // Law2 parameters: moments from incremental rotations (plastic limits are then exact) rather
  // than from the total rotation since the bond; keep moments after the bond broke.
  bool useIncrementalForm = false, alwaysUseMomentLaw = false;
  /// @return the part's declared parameters (Yade's names), see parts/Parameters.h
  static constexpr auto parameters()
  {
    return std::tuple{parameter("useIncrementalForm", &RotationMoments::useIncrementalForm),
                      parameter("always_use_moment_law", &RotationMoments::alwaysUseMomentLaw)};
  }

  /// Sets x's momentBending and momentTwist (the moments on body 2, N m; body 1 takes the
  /// opposite), capped by the normal force c.normalForce.
  /// @param x the contact's MomentState and RotationState
  /// @param step the bodies' orientations or angular velocities, dt
  /// @param energy with Track and the incremental form, the caps' work added to plastDissip
  template <bool Track, class Motion>
  void force(Contact& c, ContactExtra* x, double /*fn*/, const StepContext& step, const Motion& /*motion*/,
             ContactEnergy& energy) const
  {
    if (!x->momentRotationLaw || (x->cohesionBroken && !alwaysUseMomentLaw))
    {
      x->momentBending.setZero();
      x->momentTwist.setZero();
      return;
    }
    if (useIncrementalForm)
      incrementalRotationMoments(c, *x, step.bodies, step.dt);
    else
      totalRotationMoments(c, *x, step.bodies);
    const double normal = c.normalForce.norm();
    capMoment<Track>(x->momentBending, x->maxRollPl, normal, x->kr, useIncrementalForm, energy);
    capMoment<Track>(x->momentTwist, x->maxTwistPl, normal, x->ktw, useIncrementalForm, energy);
  }
  /// Plus 1/2 M^2 / k of each spring.
  /// @param elastic the other parts' energy (J)
  /// @param x the contact's state (null: nothing added)
  /// @return the sum (J)
  [[nodiscard]] double addElastic(double elastic, const ContactExtra* x) const
  {
    if (x && x->kr > 0)
      elastic += 0.5 * x->momentBending.squaredNorm() / x->kr;
    if (x && x->ktw > 0)
      elastic += 0.5 * x->momentTwist.squaredNorm() / x->ktw;
    return elastic;
  }
  /// @return whether the moments carry over to the next step: the incremental form adds to
  /// them, the total form sets them afresh from the rotations since the bond
  [[nodiscard]] bool carriesMoments() const { return useIncrementalForm; }
};
} // namespace talus::dem::parts
