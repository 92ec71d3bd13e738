#pragma once

// The bond part (cohesion with breakage; its state is BondState in core/ContactExtra.h): the
// shear strength the Coulomb cap (Coulomb.h) caps a bonded contact at, a broken one's, and the
// normal spring of a bond (CohFrictPhys's: tension up to the bond's strength, then breakage or
// plastic yield).
#include "dem/core/Contacts.h"
#include "dem/core/EnergyTracker.h"

#include <algorithm>

namespace talus::dem::parts
{
/// Mohr-Coulomb with a tension cut-off: the bond's cohesion (a force) plus fn tan(phi), fn the
/// signed normal force, never below 0; `cohesionOnly` (Yade's cohesionDisablesFriction): the
/// cohesion alone while there is one.
/// @param cohesion the bond's shear strength (N); 0 without a bond
/// @param fn the signed normal force (N, negative when pulled)
/// @param tanPhi the contact's friction coefficient
/// @param cohesionOnly friction left out while the cohesion is not 0
/// @return the strength (N), >= 0
inline double bondedShearStrength(double cohesion, double fn, double tanPhi, bool cohesionOnly = false)
{
  double strength = cohesion;
  if (!cohesionOnly || cohesion == 0)
    strength += fn * tanPhi;
  return std::max(0.0, strength);
}

/// Friction alone (no bond, or a broken one): fn tan(phi) when pressed, 0 when pulled.
/// @param fn the signed normal force (N)
/// @param tanPhi the contact's friction coefficient
/// @return the strength (N), >= 0
inline double frictionStrength(double fn, double tanPhi) { return std::max(0.0, fn * tanPhi); }

/// The bond breaks: the bodies interact by contact only from now on.
/// @param x the contact's bond state: broken, its strengths zeroed
inline void breakBond(BondState& x)
{
  x.cohesionBroken = 1;
  x.normalAdhesion = x.shearAdhesion = 0;
}

/// The contact ends (Yade erases the interaction): forces, bond and moments are dropped.
/// @param x the contact's state: bond broken, moments zeroed
inline void endContact(Contact& c, ContactExtra& x)
{
  c.reset();
  breakBond(x);
  x.momentBending.setZero();
  x.momentTwist.setZero();
}

/// Normal part of a bond (Yade's CohFrictPhys): a linear spring from the plastic normal
/// displacement unp, F_n = kn (u - unp); a pull beyond the bond's normal strength ends the
/// contact (fragile bond) or yields (unp follows, until -unp passes unpMax when that is >= 0).
struct BondedSpring
{
  static constexpr bool usesExtra = true;
  static constexpr bool mayEnd = true; ///< the contact may end here (c.real false)
  /// @param x the contact's BondState (unp, normalAdhesion, fragile, unpMax), updated on yield
  ///        or breakage
  /// @return the signed normal force (N; negative: tension), 0 if the contact ended
  template <bool Track>
  static double force(Contact& c, ContactExtra* x, ContactEnergy& /*energy*/)
  {
    double fn = c.kn * (c.penetration - x->unp);
    if (-fn > x->normalAdhesion)
    {
      if (x->fragile)
      {
        endContact(c, *x);
        return 0;
      }
      fn = -x->normalAdhesion;
      x->unp = c.penetration + x->normalAdhesion / c.kn;
      if (x->unpMax >= 0 && -x->unp > x->unpMax)
      {
        endContact(c, *x);
        return 0;
      }
    }
    return fn;
  }
  /// 1/2 kn (u - unp)^2.
  /// @param x the contact's state (null: unp taken as 0)
  /// @return the energy (J)
  static double elastic(const Contact& c, const ContactExtra* x)
  {
    const double v = c.penetration - (x ? x->unp : 0.0);
    return 0.5 * c.kn * v * v;
  }
};
} // namespace talus::dem::parts
