#pragma once

#include "dem/distributed/BodyRows.h"

#include <mpi.h>

#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace talus::dem
{
struct Contacts;
}

namespace talus::dem::distributed
{
/// Zoltan's geometric partitioners the DEM uses.
enum class Method
{
  RCB,  ///< recursive coordinate bisection: each rank owns a box, cut planes normal to the axes
  HSFC, ///< Hilbert space-filling curve: each rank owns a stretch of the curve
};

/// The method of a name ("RCB", "HSFC", as Zoltan's LB_METHOD).
/// @param name "RCB" or "HSFC" (case-sensitive)
/// @return the method
/// @throws std::invalid_argument naming `name` and the valid names
[[nodiscard]] Method methodNamed(std::string_view name);

/// An axis-aligned box; RCB's boxes reach infinity (±DBL_MAX) on the sides of the domain.
struct Box
{
  Vec3 min, max;
};

/// Distance from `x` to the box (0 inside it): the test that decides which bodies are ghosts.
/// @param x a point (m)
/// @return the Euclidean distance (m)
[[nodiscard]] double distanceToBox(const Vec3& x, const Box& box);

/// How the bodies of every rank are to be spread: what leaves this rank, what arrives, and
/// the region each rank owns afterwards.
struct Plan
{
  std::vector<std::int64_t> exportRows; ///< local rows leaving this rank, ascending
  std::vector<int> exportTo;            ///< the rank each of them goes to
  std::vector<GlobalId> importIds;      ///< global ids of the bodies arriving
  std::vector<int> importFrom;          ///< the rank each of them comes from
  /// The region of each rank (index = rank) after the move: its RCB box, or with HSFC the
  /// bounding box of the centres of the bodies it will own (empty, min > max, if none).
  std::vector<Box> boxes;
};

/// Settings of a partition; every rank must pass the same.
struct PartitionSettings
{
  std::string method = "RCB"; ///< a name methodNamed knows
  /// Largest ratio of a rank's weight to the average Zoltan may leave (its IMBALANCE_TOL).
  double imbalanceTolerance = 1.1;
  /// Measured imbalance (the slowest rank's compute time over the mean between two
  /// re-detections) above which the domain partitions again with the measured costs (>= 1;
  /// infinity: never). Not read by partition() itself.
  double rebalanceThreshold = 1.1;
};

/// Partition the bodies of all ranks (collective over `comm`), weighted by `weights` (one per
/// local row, for instance contactWeights'; empty: 1 each). The bodies stay where they are:
/// migrate() moves them.
/// @param comm the ranks partitioned (collective)
/// @param local this rank's bodies
/// @param weights one weight per row (>= 0), or empty
/// @param settings the method and tolerance, the same on every rank
/// @return this rank's part of the plan and every rank's region
/// @throws std::invalid_argument on every rank, before any other communication, for an
///         unknown method, a tolerance below 1, a wrong number of weights or a negative one,
///         or a body the partition cannot place (not a sphere or clump, or a clump member), naming
///         the body's global id and shape
/// @throws std::runtime_error if Zoltan fails
[[nodiscard]] Plan partition(MPI_Comm comm, const RankBodies& local, std::span<const double> weights,
                             const PartitionSettings& settings = {});

/// Per-body cost from the contact list: the number of contacts of each body, plus one (the
/// body's own integration), for the first `bodyCount` bodies.
/// @param bodyCount the rows weighted (contacts of other rows are ignored)
/// @return one weight per row
[[nodiscard]] std::vector<double> contactWeights(const Contacts& contacts, std::size_t bodyCount);
} // namespace talus::dem::distributed
