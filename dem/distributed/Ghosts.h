#pragma once

#include "dem/distributed/Partition.h"

#include <mpi.h>

#include <functional>
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
/// the farthest a centre can be from a body it may touch before the next re-detection. Rows of
/// one group (a clump and its members) are sent together when any of them is within reach.
/// @param comm the ranks exchanging (collective)
/// @param local this rank's own bodies
/// @param boxes every rank's region (index = rank), from the partition's plan
/// @param distance the ghost layer's width (m)
/// @param groupOf per row of `local`, its group (0 .. groups - 1); empty: each row alone
/// @return the ghosts received and the lists of rows sent
/// @throws std::invalid_argument on every rank if `distance` is negative or not a number, or
///         `boxes` does not hold one box per rank
[[nodiscard]] Ghosts exchangeGhosts(MPI_Comm comm, const RankBodies& local, std::span<const Box> boxes,
                                    double distance, std::span<const std::int64_t> groupOf = {});

/// Whether a body at a position may touch the bodies of a region (a rank's box).
using Reach = std::function<bool(const Vec3& position, const Box& region)>;

/// exchangeGhosts with the test of who is a ghost where given: each body of `local` goes to
/// every other rank r for which reaches(its position, boxes[r]) (a periodic cell's test, through
/// the cell's images: periodic/Regions.h), groups sent whole as above.
/// @throws std::invalid_argument on every rank if `boxes` does not hold one box per rank
[[nodiscard]] Ghosts exchangeGhosts(MPI_Comm comm, const RankBodies& local, std::span<const Box> boxes,
                                    const Reach& reaches, std::span<const std::int64_t> groupOf = {});
} // namespace talus::dem::distributed
