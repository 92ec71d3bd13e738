#pragma once

// The sphere pairs in the contact list that are candidates only (not real at the last step),
// four at a time in the lanes of AVX2 where the processor has it: Ig2_Sphere_Sphere_ScGeom's
// test to begin a contact (spheresBegin on yadeSquaredNorm), the same operations in the same
// order lane by lane, so the same answer as contactGeometry's. In a rotating drum two in three
// sphere candidates are such pairs, and their test one by one waited on the two spheres'
// positions between the contact loop's branches.
#include "dem/core/Bodies.h"
#include "dem/core/Contacts.h"

namespace talus::dem
{
/// Of four sphere-sphere contacts that were not real at the last step and are not across a
/// periodic boundary (cellDist zero, or open space): the lanes whose spheres do not begin a
/// contact, those contactGeometry returns false for without writing anything. The other lanes
/// (beginning contacts, a NaN distance) are for contactGeometry.
/// Only where sphereBatchAvailable() (AVX2).
/// @param contacts the four contacts
/// @return the lanes apart: bit i for contacts[i]
unsigned spheresApart(const Contact* const* contacts, const Bodies& b);
} // namespace talus::dem
