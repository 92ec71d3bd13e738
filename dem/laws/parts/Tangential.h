#pragma once

// Tangential parts of the contact laws: the shear force, capped by the one Coulomb cap
// (Coulomb.h). Each:
//   static constexpr bool usesExtra;
//   template <bool Track, class Motion> static void force(Contact&, ContactExtra*, double fn,
//       const StepContext&, const Motion&, ContactEnergy&);
//       // c.shearForce and c.force (= c.normalForce + the shear force), fn the normal force's
//       // signed magnitude
//   static double elastic(const Contact&);   // the energy the shear spring stores
#include "dem/laws/ContactLaw.h"
#include "dem/laws/parts/Bond.h"
#include "dem/laws/parts/Coulomb.h"

#include <cmath>

namespace talus::dem::parts
{
/// What an elastic shear spring stores, 1/2 Fs^2 / ks.
/// @return the energy (J), 0 without a shear stiffness
inline double shearSpringEnergy(const Contact& c) { return c.ks > 0 ? 0.5 * c.shearForce.squaredNorm() / c.ks : 0.0; }

/// How the Coulomb limit tan(phi) F_n is compared with the shear force: from the normal force
/// vector's squared length (the linear law's rounding) or from its magnitude fn (the others').
enum class CoulombLimit
{
  FromNormalForce,
  FromMagnitude
};

/// An incremental elastic shear spring, F_s -= ks du_s, capped at tan(phi) F_n (sliding
/// dissipates its slip); with Dashpot, the shear dashpot cs v_s (v_s = du_s / dt) adds to it
/// while the contact sticks.
template <CoulombLimit Limit, bool Dashpot>
struct IncrementalCoulomb
{
  static constexpr bool usesExtra = false;
  /// @param fn the damping part's signed normal force (N)
  /// @param step dt, for the shear dashpot's velocity
  /// @param energy with Track, the slip's work to plastDissip, the dashpot's to viscDamp
  template <bool Track, class Motion>
  static void force(Contact& c, ContactExtra* /*x*/, double fn, const StepContext& step, const Motion& /*motion*/,
                    ContactEnergy& energy)
  {
    c.shearForce -= c.ks * c.shearIncrement;
    bool sliding = false;
    if constexpr (Limit == CoulombLimit::FromNormalForce)
    {
      const double maxFs2 = c.normalForce.squaredNorm() * c.tanPhi * c.tanPhi;
      const double fs2 = c.shearForce.squaredNorm();
      if (fs2 > maxFs2)
      {
        slide<Track>(c, std::sqrt(maxFs2 / fs2), energy);
        sliding = true;
      }
    }
    else
    {
      const double maxFs = fn * c.tanPhi;
      if (c.shearForce.squaredNorm() > maxFs * maxFs)
      {
        slide<Track>(c, maxFs / c.shearForce.norm(), energy);
        sliding = true;
      }
    }
    Vec3 shear = c.shearForce;
    if constexpr (Dashpot)
      if (!sliding && c.cs != 0)
      {
        const Vec3 vs = c.shearIncrement / step.dt;
        shear -= c.cs * vs;
        if constexpr (Track)
          energy.viscDamp += c.cs * vs.squaredNorm() * step.dt;
      }
    c.force = c.normalForce + shear;
  }
  /// @return the shear spring's energy (J)
  static double elastic(const Contact& c) { return shearSpringEnergy(c); }
};
/// An incremental elastic shear spring capped at the bond's strength (bondedShearStrength, with
/// BondState's cohesion); exceeding it breaks a fragile bond, the cap then being friction alone.
/// A pulled contact that slides keeps no normal force.
struct BondedCoulomb
{
  static constexpr bool usesExtra = true;
  /// @param x the contact's BondState (shearAdhesion, fragile, cohesionDisablesFriction); the
  ///        bond breaks here when a fragile one is exceeded
  /// @param fn the damping part's signed normal force (N)
  /// @param energy with Track, the slip's work added to plastDissip
  template <bool Track, class Motion>
  static void force(Contact& c, ContactExtra* x, double fn, const StepContext& /*step*/, const Motion& /*motion*/,
                    ContactEnergy& energy)
  {
    c.shearForce -= c.ks * c.shearIncrement;
    const double strength = bondedShearStrength(x->shearAdhesion, fn, c.tanPhi, x->cohesionDisablesFriction);
    const bool slid = slideOver<Track>(c, strength, [&](double maxFs) {
      if (!x->fragile || x->cohesionBroken)
        return maxFs;
      breakBond(*x);
      return frictionStrength(fn, c.tanPhi);
    }, energy);
    if (slid && fn < 0)
      c.normalForce.setZero();
    c.force = c.normalForce + c.shearForce;
  }
  /// @return the shear spring's energy (J)
  static double elastic(const Contact& c) { return shearSpringEnergy(c); }
};
} // namespace talus::dem::parts
