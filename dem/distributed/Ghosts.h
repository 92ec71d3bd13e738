#pragma once

#include "dem/distributed/Partition.h"

#include <mpi.h>

#include <span>
#include <vector>

namespace talus::dem::distributed
{
/// Read-only copies of other ranks' bodies near this rank's region, and the lists of what this
/// rank sent as ghosts to the others (what later updates of the halo send again).
struct Ghosts
{
  RankBodies copies;      ///< the ghosts received, by owner rank, each owner's in its row order
  std::vector<int> owner; ///< the rank owning each copy
  /// Rows of this rank's bodies sent to rank r as ghosts: entries [sentStart[r], sentStart[r+1])
  /// of sentRows, ascending.
  std::vector<std::int64_t> sentRows;
  std::vector<std::int64_t> sentStart;
};

/// Send each body of `local` whose centre lies within `distance` of another rank's box
/// (distanceToBox <= distance) to that rank as a ghost, every per-body field with it
/// (collective). For spheres, `distance` is twice the largest radius plus the collider's skin:
/// the farthest a centre can be from a body it may touch before the next re-detection.
/// @param comm the ranks exchanging (collective)
/// @param local this rank's own bodies
/// @param boxes every rank's region (index = rank), from the partition's plan
/// @param distance the ghost layer's width (m)
/// @return the ghosts received and the lists of rows sent
/// @throws std::invalid_argument on every rank if `distance` is negative or not a number, or
///         `boxes` does not hold one box per rank
[[nodiscard]] Ghosts exchangeGhosts(MPI_Comm comm, const RankBodies& local, std::span<const Box> boxes,
                                    double distance);
} // namespace talus::dem::distributed
