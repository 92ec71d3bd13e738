#pragma once

// Damping parts of the contact laws: a dashpot on the normal force and the shear dashpot's
// coefficient (which the tangential part applies while the contact sticks). Each:
//   static constexpr bool usesExtra;
//   template <bool Track, class Motion> static double normal(Contact&, const ContactExtra*,
//       const StepContext&, const Motion&, double elastic, ContactEnergy&);
//       // sets c.normalForce (and c.cn, c.cs) from the elastic force; returns the signed normal
//       // force the tangential part's strength is taken from
#include "dem/laws/ContactLaw.h"

#include <algorithm>
#include <cmath>

namespace talus::dem::parts
{
/// No dashpot: the normal force is the spring's.
struct NoDamping
{
  static constexpr bool usesExtra = false;
  /// @param elastic the normal part's force (N)
  /// @return elastic: the normal force (N)
  template <bool Track, class Motion>
  static double normal(Contact& c, const ContactExtra* /*x*/, const StepContext& /*step*/, const Motion& /*motion*/,
                       double elastic, ContactEnergy& /*energy*/)
  {
    c.normalForce = elastic * c.normal;
    return elastic;
  }
};

/// Thornton's viscous damping of a Hertz contact (HertzState's betan, betas: fractions of the
/// critical damping): cn = 2 betan sqrt(m kn), cs = 2 betas sqrt(m ks), m the reduced mass (or the
/// dynamic body's mass against one forces do not move); F_n = elastic - cn v_n, never
/// attractive (the dashpot at most cancels the spring). v_n: the normal velocity of the bodies'
/// centres (Yade's incident velocity at the contact point, whose rotational part has no normal
/// component between spheres).
struct ThorntonDamping
{
  static constexpr bool usesExtra = true;
  static constexpr bool stateForForcesOnly = true; ///< betan, betas: read by its force alone
  /// @param x the contact's state (HertzState's betan, betas)
  /// @param step the bodies' masses and velocities, the cell, dt
  /// @param elastic the normal part's force (N)
  /// @param energy with Track, the dashpot's dissipation added to viscDamp
  /// @return the damped normal force (N), >= 0
  template <bool Track, class Motion>
  static double normal(Contact& c, const ContactExtra* x, const StepContext& step, const Motion& /*motion*/,
                       double elastic, ContactEnergy& energy)
  {
    // Without a dashpot (Yade's default: neither en nor betan given) the normal force is the
    // spring's and the dashpot dissipates nothing: no incident velocity to compute.
    double fn = elastic;
    if (x->betan != 0 || x->betas != 0)
    {
      const Bodies& b = step.bodies;
      const double vn = c.normal.dot(incidentVelocity(c, b, step.cell));
      const auto i1 = static_cast<std::size_t>(c.id1), i2 = static_cast<std::size_t>(c.id2);
      const double mass = !b.dynamic[i1] && b.dynamic[i2]   ? b.mass[i2]
                          : !b.dynamic[i2] && b.dynamic[i1] ? b.mass[i1]
                                                            : b.mass[i1] * b.mass[i2] / (b.mass[i1] + b.mass[i2]);
      c.cn = 2 * std::sqrt(mass * c.kn) * x->betan;
      c.cs = 2 * std::sqrt(mass * c.ks) * x->betas;
      fn = std::max(0.0, elastic - c.cn * vn);
      if constexpr (Track) // the normal dashpot's force is elastic - fn
        energy.viscDamp += (elastic - fn) * vn * step.dt;
    }
    c.normalForce = fn * c.normal;
    return fn;
  }
};
} // namespace talus::dem::parts
