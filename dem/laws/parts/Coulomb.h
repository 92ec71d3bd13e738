#pragma once

// The tangential part every contact law shares: the Coulomb cap on the shear force, and the
// same cap on a plastic moment.
#include "dem/core/Contacts.h"
#include "dem/core/EnergyTracker.h"

namespace talus::dem::parts
{
/// Bring a force (or moment) back onto its cap along its own direction: `ratio` is the cap over
/// its trial magnitude (< 1). Returns the trial value.
/// @param value the force (N) or moment (N m), scaled in place
/// @param ratio the scale, cap / |value|
/// @return the value before scaling
inline Vec3 cap(Vec3& value, double ratio)
{
  const Vec3 trial = value;
  value *= ratio;
  return trial;
}

/// What the slip from `trial` to `capped` dissipates in a spring of that stiffness:
/// (trial - capped) . capped / stiffness, the work of the capped force over the spring's plastic
/// slip (0 without a spring).
/// @param trial, capped the force before and after the cap (N)
/// @param stiffness the spring's stiffness (N/m); <= 0: no spring
/// @return the work (J)
inline double plasticWork(const Vec3& trial, const Vec3& capped, double stiffness)
{
  return stiffness > 0 ? (trial - capped).dot(capped) / stiffness : 0.0;
}

/// The Coulomb cap of the shear force, its dissipation booked when Track: the laws whose shear
/// spring is incremental from its last capped value (all but the visco-elastic one, which books
/// the work of its own increment and calls cap()).
/// @param ratio the cap over the trial shear force's magnitude (< 1)
/// @param energy with Track, the slip's work added to plastDissip
template <bool Track>
inline void slide(Contact& c, double ratio, ContactEnergy& energy)
{
  const Vec3 trial = cap(c.shearForce, ratio);
  if constexpr (Track)
    energy.plastDissip += plasticWork(trial, c.shearForce, c.ks);
}

/// The shear force's magnitude against a strength maxFs: over it, the force slides at the cap
/// `exceeded(maxFs)` gives (a bond that breaks there lowers it). Returns whether it slid.
/// @param maxFs the strength (N)
/// @param exceeded exceeded(maxFs) returns the cap (N) once the force is over it (called only then)
/// @param energy with Track, the slip's work added to plastDissip
/// @return whether the force was over maxFs (and slid)
template <bool Track, class Exceeded>
inline bool slideOver(Contact& c, double maxFs, Exceeded&& exceeded, ContactEnergy& energy)
{
  const double fs = c.shearForce.norm();
  if (!(fs > maxFs))
    return false;
  slide<Track>(c, exceeded(maxFs) / fs, energy);
  return true;
}
} // namespace talus::dem::parts
