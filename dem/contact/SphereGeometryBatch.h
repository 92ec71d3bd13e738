#pragma once

// The geometry of sphere pairs that stay in contact, four at a time in the lanes of AVX2 where
// the processor has it: contactGeometry's sphere path, the same operations in the same order
// lane by lane, so the same bits.
#include "dem/core/Bodies.h"
#include "dem/core/Cell.h"
#include "dem/core/Contacts.h"

namespace talus::dem
{
/// How many contacts sphereGeometryBatch takes at once.
inline constexpr int sphereBatchWidth = 4;

/// What a law's own lanes did with four contacts (PartsLaw::sphereLanes): bit i of `geometry`
/// for contact i's geometry made, of `forces` for its forces too, and of `deep` for forces made
/// at an overlap beyond StepContext::maxOverlapRatio of the smaller reference radius (the first
/// tests of overlapsTooMuch, which the contact loop then makes for those lanes alone).
struct SphereLanes
{
  unsigned geometry = 0, forces = 0, deep = 0;
};

/// Whether this processor runs sphereGeometryBatch (AVX2), asked once.
bool sphereBatchAvailable();

/// contactGeometry<true> of four contacts that were real at the last step, between two spheres
/// (in a periodic cell, inside it or across its boundary): a contact whose spheres still overlap
/// gets its normal, overlap, contact point, reference radii, turned shear force and shear
/// increment (and is no longer fresh); one whose spheres came apart is left untouched, for
/// contactGeometry to reset.
/// Only where sphereBatchAvailable().
/// @param contacts the four contacts (distinct)
/// @param dt the time step (s)
/// @param cell the periodic cell, or null (the pairs' shift zero: inside the cell, or open space)
/// @return the lanes updated: bit i for contacts[i]
unsigned sphereGeometryBatch(Contact* const* contacts, const Bodies& b, double dt, const Cell* cell = nullptr);
} // namespace talus::dem
