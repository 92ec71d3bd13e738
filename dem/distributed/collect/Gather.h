#pragma once

#include "dem/distributed/MpiDomain.h"

#include <span>
#include <vector>

namespace talus::dem::distributed
{
/// What gatherBodies reads of each body, in this order: position, velocity, angular velocity
/// (3 each), orientation (w, x, y, z), mass, inertia (3, principal), radius (0 for shapes
/// without one), dynamic (1 or 0).
inline constexpr std::size_t gatheredDoubles = 19;

/// The state of the bodies `ids` (global ids) of a scene split over the ranks, on every rank
/// (collective: O.bodies.gather). Each body's entries come from the rank that counts it (its
/// owner; rank 0 for a wall, which every rank holds), the ranks' tables are summed: an exchange of
/// gatheredDoubles per id, whatever the scene's size.
/// @param ids the bodies, the same list on every rank (any order, repeats allowed)
/// @return gatheredDoubles per id, in the order of `ids`
/// @throws CollectiveError on every rank if the ranks passed different lists, or an id is out of
///         range or names an erased body
std::vector<double> gatherBodies(const MpiDomain& domain, const Scene& scene, std::span<const GlobalId> ids);
} // namespace talus::dem::distributed
