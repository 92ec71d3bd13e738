#pragma once

#include <cstdint>
#include <vector>

namespace talus::dem
{
class Scene;

/// Yade's energy tracker (O.trackEnergy, O.energy): the energies that must be accumulated step
/// by step. Kinetic and elastic energies are state functions, computed on demand
/// (kineticEnergy, elasticPotential).
///
/// With the leap-frog scheme the change of kinetic energy over a step is exactly the work of the
/// step's forces over the mean of the old and new velocities times dt, so gravity's work and the
/// non-viscous damping are accumulated with that mean velocity and close the balance to
/// round-off; contact energies close it to O(dt^2) (elastic energy is taken at the step's
/// contact state).
///
/// Sign convention as Yade's: dissipated energies are positive, gravWork is minus the work done
/// by gravity, so that total() = kinetic + elastPotential + gravWork + dissipations stays
/// constant in a closed system. Sums are taken per block of bodies or contacts, then over the
/// blocks in order: the result does not depend on the number of threads. When off (the
/// default), the step has no energy code in its loops (separate instantiations).
struct EnergyTracker
{
  bool enabled = false;
  double gravWork = 0;    ///< minus the work of gravity
  double nonviscDamp = 0; ///< dissipated by Cundall's non-viscous damping (NewtonIntegrator)
  double plastDissip = 0; ///< dissipated by friction sliding and plastic moments of contacts
  double viscDamp = 0;    ///< dissipated by contact dashpots (visco-elastic, Hertz damping)

  /// Set every accumulated energy to zero (Yade's O.energy.clear()).
  void clear() { gravWork = nonviscDamp = plastDissip = viscDamp = 0; }
};

/// Energies dissipated by contacts, accumulated over a block of contacts.
struct ContactEnergy
{
  double plastDissip = 0, viscDamp = 0;
  ContactEnergy& operator+=(const ContactEnergy& o)
  {
    plastDissip += o.plastDissip;
    viscDamp += o.viscDamp;
    return *this;
  }
};

/// Number of contacts or bodies summed together before the per-block sums are added in order.
inline constexpr std::int64_t energyBlock = 256;

/// Sum of 1/2 m v^2 + 1/2 w.I w over dynamic bodies (fluctuating velocities in a homogeneously
/// deforming periodic cell).
double kineticEnergy(const Scene& scene);
/// Elastic energy stored in the contacts of the scene's InteractionLoop(s), as each law defines
/// it (1/2 Fn^2/kn + 1/2 Fs^2/ks for linear springs, 2/5 Fn u for Hertz, moments as springs).
double elasticPotential(const Scene& scene);
} // namespace talus::dem
