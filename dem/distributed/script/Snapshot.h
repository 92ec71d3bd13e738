#pragma once

#include "dem/distributed/MpiDomain.h"

#include <cstddef>
#include <string>
#include <vector>

namespace talus::dem::distributed
{
/// What a snapshot of a body holds, in this order (talus.dem.split.bodies reads these columns):
/// global id, position, velocity, angular velocity (3 each), orientation (w, x, y, z), mass,
/// inertia (3, principal), radius, dynamic, material, group mask, clump (global id, -1 if
/// none), whether it is a clump, blocked DOFs (bits), owning rank, damped.
inline constexpr std::size_t snapshotDoubles = 27;

/// The snapshot of row `row` of a split scene.
/// @param out snapshotDoubles numbers written
void snapshotOf(const MpiDomain& domain, const Scene& scene, std::size_t row, double* out);

/// O.bodies[id] of a scene split over the ranks, as every rank of the script reads it (talus.dem.split.by_id).
struct ScriptRead
{
  bool local = false;       ///< held as every rank holds it (a wall, facet or box): no exchange was made
  std::int64_t row = -1;    ///< its row here when owned here or local (alive), else -1
  bool agreed = true;       ///< every rank read the same id (false: some were elsewhere in the script)
  std::vector<double> rows; ///< per rank: place, id, whether it sent the snapshot, then the snapshot
};

/// Where a rank is in the script, as the first entry of each rank's row on the script channel:
/// a read of O.bodies[id]; other places are talus.dem.split.by_id's.
inline constexpr double readPlace = 1;
/// Entries ahead of the snapshot in each rank's row: place, id, sent.
inline constexpr std::size_t placeDoubles = 3;

/// Read body `id`: a wall, facet or box (every rank holds it) here alone, another body with every
/// rank over the script channel (gatherOnScriptChannel), its owner sending its snapshot.
/// @param patience seconds to wait for the other ranks before ending the run
/// @param rule the rule the message names when they do not come
ScriptRead readById(const MpiDomain& domain, const Scene& scene, GlobalId id, double patience, const std::string& rule);
} // namespace talus::dem::distributed
