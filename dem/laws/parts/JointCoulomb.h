#pragma once

// The tangential part of the Potential Blocks' and Particles' laws (Yade's KnKsPBLaw, KnKsLaw):
// the incremental shear spring capped by the Coulomb cap (Coulomb.h); with RockJoints (blocks),
// the cohesion of a joint's bond (RockJoint.h).
#include "dem/laws/ContactLaw.h"
#include "dem/laws/parts/Bond.h"
#include "dem/laws/parts/Coulomb.h"
#include "dem/laws/parts/Parameters.h"
#include "dem/laws/parts/Tangential.h"

#include <tuple>

namespace talus::dem::parts
{
/// F_s -= ks du_s, capped at tan(phi) |F_n|, F_n the spring's force fn (blocks) or the damped
/// one (particles, as Yade's). With RockJoints, a bond with its cohesion adds it to the strength,
/// which then takes the signed fn (bondedShearStrength: Mohr-Coulomb with a tension cut-off);
/// exceeding it breaks the bond with allowBreakage (the cap is then friction alone), else the
/// joint yields at its strength, as Yade's.
template <bool RockJoints>
struct JointCoulomb
{
  static constexpr bool usesExtra = RockJoints;
  bool allowBreakage = false; ///< Law2's, RockJoints only
  /// @return the part's declared parameters (Yade's names), see parts/Parameters.h
  static constexpr auto parameters()
  {
    if constexpr (RockJoints)
      return std::tuple{parameter("allowBreakage", &JointCoulomb::allowBreakage)};
    else
      return std::tuple{};
  }

  /// Sets c.shearForce and c.force.
  /// @param x the contact's BondState and AreaState (RockJoints; the bond may break here)
  /// @param fn the damping part's signed normal force (N)
  /// @param energy with Track, the slip's work added to plastDissip
  template <bool Track, class Motion>
  void force(Contact& c, ContactExtra* x, double fn, const StepContext& /*step*/, const Motion& /*motion*/,
             ContactEnergy& energy) const
  {
    c.shearForce -= c.ks * c.shearIncrement;
    if constexpr (RockJoints)
    {
      const bool cohesive = x->intactRock && !x->cohesionBroken;
      const double strength
          = cohesive ? bondedShearStrength(x->shearAdhesion, fn, c.tanPhi) : (fn * c.normal).norm() * c.tanPhi;
      slideOver<Track>(c, strength, [&](double maxFs) {
        if (!cohesive || !allowBreakage)
          return maxFs;
        x->cohesionBroken = x->tensionBroken = 1;
        return frictionStrength(fn, c.tanPhi);
      }, energy);
    }
    else
      slideOver<Track>(c, c.normalForce.norm() * c.tanPhi, [](double maxFs) { return maxFs; }, energy);
    c.force = c.normalForce + c.shearForce;
  }
  /// @return the shear spring's energy (J)
  static double elastic(const Contact& c) { return shearSpringEnergy(c); }
};
} // namespace talus::dem::parts
