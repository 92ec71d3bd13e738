#pragma once

// Normal parts of the contact laws: the elastic normal force from the overlap, with the
// stiffnesses it implies (a bond's is in Bond.h). Each is a struct of inline static functions (no virtual call):
//   static constexpr bool usesExtra;   // keeps state in ContactExtra (its part state)
//   static constexpr bool mayEnd;      // may end the contact (c.real false: no force this step)
//   template <bool Track> static double force(Contact&, ContactExtra*, ContactEnergy&);
//       // the elastic normal force's magnitude (>= 0 pushes), stiffnesses updated
//   static double elastic(const Contact&, const ContactExtra*);   // the energy it stores
#include "dem/core/Contacts.h"
#include "dem/core/EnergyTracker.h"

#include <algorithm>
#include <cmath>

namespace talus::dem::parts
{
/// A linear spring: F_n = kn u, kn and ks fixed by the physics when the contact was made.
struct LinearSpring
{
  static constexpr bool usesExtra = false;
  static constexpr bool mayEnd = false;
  /// @return kn u (N), negative when the bodies are apart within the skin (the contact is kept)
  template <bool Track>
  static double force(Contact& c, ContactExtra* /*x*/, ContactEnergy& /*energy*/)
  {
    return c.kn * c.penetration;
  }
  /// 1/2 kn u^2.
  /// @return the energy (J)
  static double elastic(const Contact& c, const ContactExtra* /*x*/) { return 0.5 * c.kn * c.penetration * c.penetration; }
};

/// Hertz's spring with Mindlin's shear (HertzState): F_n = kno u^1.5, tangent stiffnesses
/// kn = 3/2 kno u^0.5 and ks = kso u^0.5.
struct HertzSpring
{
  static constexpr bool usesExtra = true;
  static constexpr bool stateForForcesOnly = true; ///< kno, kso: read by its force alone
  static constexpr bool mayEnd = false;
  /// Sets c.kn and c.ks to the tangent stiffnesses of the current overlap.
  /// @param x the contact's state (its HertzState's kno, kso)
  /// @param energy with Track, the change of the shear spring's energy as its stiffness changes
  ///        is added to plastDissip
  /// @return kno u^1.5 (N), 0 when apart
  template <bool Track>
  static double force(Contact& c, ContactExtra* x, ContactEnergy& energy)
  {
    const double u = std::max(c.penetration, 0.0);
    const double sqrtU = std::sqrt(u);
    const double ksOld = c.ks;
    c.kn = 1.5 * x->kno * sqrtU;
    c.ks = x->kso * sqrtU;
    // The incremental shear spring is not conservative when its stiffness changes with the
    // overlap: the energy 1/2 Fs^2 / ks it holds changes by 1/2 Fs^2 (1/ks_new - 1/ks_old)
    // without work. That difference is counted with the dissipation (it is negative while the
    // contact unloads), so that the balance of the energy tracker closes.
    if constexpr (Track)
      if (ksOld > 0 && c.ks > 0)
        energy.plastDissip += 0.5 * c.shearForce.squaredNorm() * (1 / ksOld - 1 / c.ks);
    return x->kno * u * sqrtU;
  }
  /// 2/5 kno u^2.5.
  /// @param x the contact's state (null: 0)
  /// @return the energy (J)
  static double elastic(const Contact& c, const ContactExtra* x)
  {
    const double u = std::max(c.penetration, 0.0);
    return x ? 0.4 * x->kno * u * u * std::sqrt(u) : 0.0;
  }
};
} // namespace talus::dem::parts
