#pragma once

// The damping part of Yade's visco-elastic law: a linear dashpot beside the normal spring,
// which cannot pull.
#include "dem/laws/ContactLaw.h"

#include <algorithm>

namespace talus::dem::parts
{
/// F_n = elastic + cn v_n along the normal, never attractive (cn fixed by the physics; v_n the
/// Motion's normal velocity, > 0 approaching). Its work: what the force does beyond the
/// spring's, (F_n - elastic) v_n dt (the dashpot's, and while it would pull the spring's
/// release). The shear dashpot c.cs is the tangential part's.
struct NormalDashpot
{
  static constexpr bool usesExtra = false;
  /// Sets c.normalForce.
  /// @param step dt, for the dissipated work
  /// @param motion vn, the normal velocity (m/s, > 0 approaching)
  /// @param elastic the normal spring's force (N)
  /// @param energy with Track, the dashpot's work added to viscDamp
  /// @return the normal force (N), >= 0
  template <bool Track, class Motion>
  static double normal(Contact& c, const ContactExtra* /*x*/, const StepContext& step, const Motion& motion,
                       double elastic, ContactEnergy& energy)
  {
    const double fn = elastic + c.cn * motion.vn;
    c.normalForce = fn < 0 ? Vec3::Zero() : Vec3(fn * c.normal);
    const double pressing = std::max(fn, 0.0);
    if constexpr (Track)
      energy.viscDamp += (pressing - elastic) * motion.vn * step.dt;
    return pressing;
  }
};
} // namespace talus::dem::parts
