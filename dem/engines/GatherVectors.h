#pragma once

// The gather of contact forces per body with each body's three components in one AVX2 vector,
// where the processor has it: a body's contacts in index order with the operations of
// InteractionLoop's scalar gather component by component, so each body gets the same bits.
#include "dem/core/Bodies.h"
#include "dem/core/Cell.h"
#include "dem/core/Contacts.h"

#include <cstdint>

namespace talus::dem
{
/// Whether this processor runs gatherVectors (AVX2), asked once.
bool gatherVectorsAvailable();

/// The forces and torques of the contacts of bodies [first, last) (all in the index), each
/// body's contacts in index order, of laws that leave no moments: the force on the body and its
/// moment about the centre, applied at the contact point (body 2 of a pair across a periodic
/// cell's boundary at its image). Only where gatherVectorsAvailable().
/// @param cell the periodic cell, or null outside one
/// @param reset each body's force and torque become its permanent ones plus the sums, instead
///        of the sums being added to them
void gatherVectors(const Contacts& contacts, Bodies& b, const Cell* cell, std::int64_t first, std::int64_t last,
                   bool reset);
} // namespace talus::dem
