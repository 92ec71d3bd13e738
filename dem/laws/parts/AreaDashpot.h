#pragma once

// The damping part of the Potential Blocks' and Particles' laws (Yade's KnKsPBPhys, KnKsPhys):
// a dashpot of a fraction of the critical damping of the normal spring.
#include "dem/laws/ContactLaw.h"
#include "dem/laws/parts/Parameters.h"

#include <cmath>
#include <tuple>

namespace talus::dem::parts
{
/// cn = viscousDamping 2 sqrt(m kn) (m the reduced mass, a body that forces do not move counting
/// as infinitely heavy), F_n = elastic n - cn v_n n (v_n the incident velocity); the dashpot
/// never turns the spring's force around (no pull from a pressed contact unless
/// allowViscousAttraction, no push from a bond that pulls) and dissipates cn v_n^2 dt. Returns
/// the spring's force: a joint's shear strength is taken from it.
struct AreaDashpot
{
  static constexpr bool usesExtra = false;
  // Ip2's viscousDamping (set mid-run, it applies to every contact from the next step); Law2's
  // allowViscousAttraction.
  double viscousDamping = 0;
  bool allowViscousAttraction = false;
  /// @return the part's declared parameters (Yade's names), see parts/Parameters.h
  static constexpr auto parameters()
  {
    return std::tuple{parameter("viscousDamping", &AreaDashpot::viscousDamping),
                      parameter("allowViscousAttraction", &AreaDashpot::allowViscousAttraction)};
  }

  /// Sets c.normalForce and c.cn.
  /// @param step the bodies' masses and velocities, dt
  /// @param elastic the normal part's signed force (N)
  /// @param energy with Track, the dashpot's dissipation added to viscDamp
  /// @return elastic (the spring's force, undamped)
  template <bool Track, class Motion>
  double normal(Contact& c, const ContactExtra* /*x*/, const StepContext& step, const Motion& /*motion*/,
                double elastic, ContactEnergy& energy) const
  {
    c.normalForce = elastic * c.normal;
    if (!(viscousDamping > 0))
      return elastic;
    const Bodies& b = step.bodies;
    c.cn = viscousDamping * 2 * std::sqrt(reducedMass(b, static_cast<std::size_t>(c.id1), static_cast<std::size_t>(c.id2))
                                          * c.kn);
    const double vn = incidentVelocity(c, b, nullptr).dot(c.normal);
    c.normalForce -= c.cn * vn * c.normal;
    if constexpr (Track)
      energy.viscDamp += c.cn * vn * vn * step.dt;
    const double total = c.normalForce.dot(c.normal);
    if (!allowViscousAttraction && (elastic >= 0 ? total < 0 : total > 0))
      c.normalForce.setZero();
    return elastic;
  }

private:
  static double reducedMass(const Bodies& b, std::size_t i1, std::size_t i2)
  {
    const bool d1 = b.dynamic[i1] && b.mass[i1] > 0, d2 = b.dynamic[i2] && b.mass[i2] > 0;
    if (d1 && d2)
      return b.mass[i1] * b.mass[i2] / (b.mass[i1] + b.mass[i2]);
    return d1 ? b.mass[i1] : d2 ? b.mass[i2] : 0.0;
  }
};
} // namespace talus::dem::parts
