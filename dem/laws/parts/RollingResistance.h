#pragma once

// The moments part of Yade's visco-elastic law: rolling resistance, a moment against the
// bodies' relative rotation proportional to the normal force (RollingResistanceState in
// core/ContactExtra.h; the moment is MomentState's momentBending, set afresh at every step).
#include "dem/core/Scene.h"
#include "dem/laws/ContactLaw.h"

namespace talus::dem::parts
{
/// With mR > 0: a moment on body 1 of -mR fn (w1 - w2) (mRtype 1), times also
/// |c1x x w1 - c2x x w2| (mRtype 2; c1x, c2x the Motion's arms), the opposite on body 2; it
/// dissipates its power and stores nothing.
struct RollingResistance
{
  static constexpr bool usesExtra = true;
  /// mR: twice the harmonic mean of the materials' mR > 0 (one alone: twice it), as Yade.
  /// @param x the new contact's state: mR, mRtype set (mRtype: body 1's material's)
  void initialize(Contact& c, ContactExtra* x, const Scene& scene) const
  {
    const Material& m1 = scene.materials[static_cast<std::size_t>(scene.bodies.material[static_cast<std::size_t>(c.id1)])];
    const Material& m2 = scene.materials[static_cast<std::size_t>(scene.bodies.material[static_cast<std::size_t>(c.id2)])];
    x->mR = m1.mR > 0 || m2.mR > 0 ? 2.0 / ((m1.mR > 0 ? 1 / m1.mR : 0) + (m2.mR > 0 ? 1 / m2.mR : 0)) : 0;
    x->mRtype = static_cast<std::uint8_t>(m1.mRtype);
  }
  /// Sets x's momentBending (N m, the moment on body 2).
  /// @param x the contact's RollingResistanceState and MomentState
  /// @param fn the damping part's normal force (N)
  /// @param step the bodies' angular velocities, dt
  /// @param energy with Track, the moment's work added to viscDamp
  template <bool Track, class Motion>
  void force(Contact& c, ContactExtra* x, double fn, const StepContext& step, const Motion& motion,
             ContactEnergy& energy) const
  {
    x->momentBending.setZero();
    if (!(x->mR > 0))
      return;
    const Bodies& b = step.bodies;
    const Vec3& w1 = b.angVel[static_cast<std::size_t>(c.id1)];
    const Vec3& w2 = b.angVel[static_cast<std::size_t>(c.id2)];
    const Vec3 relAngVel = w1 - w2;
    double scale = x->mR * fn;
    if (x->mRtype == 2)
      scale *= (motion.c1x.cross(w1) - motion.c2x.cross(w2)).norm();
    x->momentBending = scale * relAngVel; // the moment on body 2 (body 1 gets the opposite)
    if constexpr (Track)
      energy.viscDamp += x->momentBending.dot(relAngVel) * step.dt;
  }
  /// @param elastic the other parts' energy (J)
  /// @return elastic unchanged: the resistance stores nothing
  [[nodiscard]] double addElastic(double elastic, const ContactExtra* /*x*/) const { return elastic; }
  /// @return false: the moment is set afresh at every step
  [[nodiscard]] bool carriesMoments() const { return false; }
};
} // namespace talus::dem::parts
