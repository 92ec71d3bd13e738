#pragma once

// The geometry of facet-sphere candidate pairs, four at a time in the lanes of AVX2 where the
// processor has it: contactGeometry's facet path, the same operations in the same order lane by
// lane, so the same bits.
#include "dem/core/Bodies.h"
#include "dem/core/Contacts.h"

namespace talus::dem
{
/// What facetGeometryBatch did with four contacts: bit i of `geometry` for contact i's geometry
/// made (it was real and still touches), of `apart` for a contact that was not real and does
/// not touch (nothing to write). The other lanes are left untouched, for contactGeometry
/// (contacts beginning or ending).
struct FacetLanes
{
  unsigned geometry = 0, apart = 0;
};

/// contactGeometry<false> without a bond (no contact state) of four facet-sphere contacts (body
/// 1 the facet) not across a periodic boundary (cellDist zero).
/// Only where sphereBatchAvailable() (AVX2).
/// @param contacts the four contacts (distinct)
/// @param dt the time step (s)
/// @return the lanes done, as said of FacetLanes
FacetLanes facetGeometryBatch(Contact* const* contacts, const Bodies& b, double dt);
} // namespace talus::dem
