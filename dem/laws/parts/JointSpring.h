#pragma once

// The normal part of the Potential Blocks' and Particles' laws (Yade's KnKsPBLaw, KnKsLaw): a
// linear spring of the stiffness the physics sets from the contact's area at every step, which
// pulls only across a rock joint's bond (RockJoints, blocks: RockJoint.h).
#include "dem/core/Contacts.h"
#include "dem/core/EnergyTracker.h"
#include "dem/laws/parts/Normal.h"
#include "dem/laws/parts/Parameters.h"

#include <algorithm>
#include <tuple>

namespace talus::dem::parts
{
/// F_n = kn u_n, never pulling; with RockJoints, u_n is the overlap less initialOverlapDistance
/// (blocks generated overlapping by it carry tension across a bond until they separate), and a
/// bond that holds tension pulls down to -normalAdhesion (beyond, it breaks altogether, as Yade
/// erases the contact, and the force is 0). Stores 1/2 kn u^2 of the whole overlap u.
template <bool RockJoints>
struct JointSpring
{
  static constexpr bool usesExtra = RockJoints;
  static constexpr bool mayEnd = false;
  double initialOverlapDistance = 0; ///< Law2's, RockJoints only
  /// @return the part's declared parameters (Yade's names), see parts/Parameters.h
  static constexpr auto parameters()
  {
    if constexpr (RockJoints)
      return std::tuple{parameter("initialOverlapDistance", &JointSpring::initialOverlapDistance)};
    else
      return std::tuple{};
  }

  /// @param x the contact's BondState and AreaState (RockJoints: the bond may break here)
  /// @return the signed normal force (N; negative only across a bond holding tension)
  template <bool Track>
  double force(Contact& c, ContactExtra* x, ContactEnergy& /*energy*/) const
  {
    if constexpr (!RockJoints)
      return c.kn * std::max(c.penetration, 0.0);
    else
    {
      const double un = c.penetration - initialOverlapDistance;
      const bool tension = x->intactRock && !x->tensionBroken;
      double fn = c.kn * (tension ? un : std::max(un, 0.0));
      if (tension && fn < -x->normalAdhesion)
      {
        x->tensionBroken = x->cohesionBroken = 1;
        fn = 0;
      }
      return fn;
    }
  }
  /// @return 1/2 kn u^2 (J)
  static double elastic(const Contact& c, const ContactExtra* x) { return LinearSpring::elastic(c, x); }
};
} // namespace talus::dem::parts
