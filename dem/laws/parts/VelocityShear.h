#pragma once

// The tangential part of Yade's visco-elastic law: a shear spring driven by the velocity at the
// contact point, capped by the Coulomb cap (Coulomb.h), with the shear dashpot while it sticks.
#include "dem/laws/ContactLaw.h"
#include "dem/laws/parts/Coulomb.h"
#include "dem/laws/parts/Tangential.h"

#include <cmath>

namespace talus::dem::parts
{
/// F_s += ks v_s dt (v_s the Motion's tangential velocity), capped at fn tan(phi) (fn >= 0, the
/// damped normal force), plus the shear dashpot cs v_s only while not sliding. Sliding
/// dissipates the work of the capped force over this step's increment less the change of the
/// spring's energy; the dashpot its power cs v_s . v_s.
struct VelocityShear
{
  static constexpr bool usesExtra = false;
  /// Sets c.shearForce and c.force.
  /// @param fn the damping part's normal force (N), >= 0
  /// @param step dt
  /// @param energy with Track, the slip's work to plastDissip, the dashpot's to viscDamp
  template <bool Track, class Motion>
  static void force(Contact& c, ContactExtra* /*x*/, double fn, const StepContext& step, const Motion& motion,
                    ContactEnergy& energy)
  {
    const Vec3 before = c.shearForce;
    c.shearForce += c.ks * step.dt * motion.vs;
    const double maxFs2 = fn * fn * c.tanPhi * c.tanPhi;
    Vec3 viscous = Vec3::Zero();
    if (c.shearForce.squaredNorm() > maxFs2)
    {
      const Vec3 trial = cap(c.shearForce, std::sqrt(maxFs2) / c.shearForce.norm());
      if constexpr (Track)
        if (c.ks > 0)
          energy.plastDissip += (c.shearForce.dot(trial - before)
                                 - 0.5 * (c.shearForce.squaredNorm() - before.squaredNorm()))
                                / c.ks;
    }
    else
      viscous = c.cs * motion.vs;
    c.force = c.normalForce + c.shearForce + viscous;
    if constexpr (Track)
      energy.viscDamp += viscous.dot(motion.vs) * step.dt;
  }
  /// @return the shear spring's energy (J)
  static double elastic(const Contact& c) { return shearSpringEnergy(c); }
};
} // namespace talus::dem::parts
