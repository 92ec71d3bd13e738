#pragma once

#include "dem/base/types.h"

#include <cstdint>
#include <limits>
#include <vector>

namespace talus::dem
{
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
  /// Minus the work of the periodic cell's deformation on the bodies (Yade's PeriTriaxController
  /// key; booked here for any deforming cell, whoever sets velGrad).
  double velGradWork = 0;
  /// Minus the work of imposed motions: non-dynamic bodies moving with their velocity (walls
  /// of a TriaxialStressController, bodies of kinematic engines) and blocked DOFs of dynamic
  /// bodies. Not a Yade key: Yade does not book these.
  double kinematicWork = 0;
  /// Minus the energy that changing radii at fixed positions puts in (growParticles: the contacts'
  /// compressions and stiffnesses, the bodies' masses at their velocities change). Not a Yade key:
  /// Yade's growParticles books nothing, so its balance does not close under internal compaction.
  double growthWork = 0;
  /// Per body id, how much growParticles increased its radius since the last contact pass (empty:
  /// no growth since): the contacts that pass finds new overlap by it (addGrownContactsEnergy).
  std::vector<double> grownBy;
  /// Per body id, the imposed displacement and rotation (velocity times the step) it made in
  /// the previous tracked step (NaN: none yet), so that kinematicWork is taken over the mean of
  /// the previous and the current displacement, as gravity's work is over the mean velocity (a
  /// servo-controlled wall changes its velocity every step, and an adaptive step changes dt:
  /// the work over the current displacement alone is off by a few percent there).
  std::vector<Vec3> previousDisplacement, previousRotation;
  /// total() when the growth check first ran since tracking started or was cleared (NaN: not yet).
  double growthReference = std::numeric_limits<double>::quiet_NaN();

  /// Set every accumulated energy to zero (Yade's O.energy.clear()).
  void clear()
  {
    gravWork = nonviscDamp = plastDissip = viscDamp = velGradWork = kinematicWork = growthWork = 0;
    growthReference = std::numeric_limits<double>::quiet_NaN();
  }
};

/// Energies dissipated by contacts, accumulated over a block of contacts.
struct ContactEnergy
{
  double plastDissip = 0, viscDamp = 0;
  /// Add another block's sums (the blocks are added in block order: the same sums whatever
  /// the threads).
  /// @param o the other block's energies (J)
  /// @return this
  ContactEnergy& operator+=(const ContactEnergy& o)
  {
    plastDissip += o.plastDissip;
    viscDamp += o.viscDamp;
    return *this;
  }
};

/// Gravity's work, the damping's dissipation and the work of imposed motions (kinematicWork,
/// and cellPower: the power of a deforming cell's field, booked times dt), summed over a block
/// of bodies by NewtonIntegrator.
struct BodyEnergy
{
  double gravWork = 0, damp = 0, kinematicWork = 0, cellPower = 0;
};

/// Number of contacts or bodies summed together before the per-block sums are added in order.
inline constexpr std::int64_t energyBlock = 256;
} // namespace talus::dem
