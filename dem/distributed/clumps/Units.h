#pragma once

#include "dem/distributed/Partition.h"

#include <mpi.h>

#include <cstdint>
#include <span>
#include <vector>

namespace talus::dem::distributed
{
/// A rank's own bodies grouped into what the partition places and what travels together: a free
/// sphere alone, or a clump with all its members. A clump is placed by its centre of mass (the
/// clump body's position) and weighs as many rows as it holds; its members go wherever it goes,
/// as the rank's own bodies or as ghosts, so a clump and its members are always on one rank and
/// every rank holding a member holds the whole clump (its integration sums every member's force).
///
/// Rows here are those of a RankBodies whose clumpId holds the clump's global id (not a row).
struct Units
{
  std::vector<std::int64_t> head;  ///< per unit: the row of the sphere or clump body placed, ascending
  std::vector<std::int64_t> start; ///< unit u's rows are rows[start[u] .. start[u+1])
  std::vector<std::int64_t> rows;  ///< the rows of every unit, each unit's ascending
  std::vector<std::int64_t> unitOf; ///< per row of the RankBodies: its unit

  /// The number of units.
  [[nodiscard]] std::size_t size() const { return head.size(); }
};

/// Group the rows of `local` into units (its clumpId entries being global ids).
/// @param local a rank's own bodies: free spheres, clumps and the members of those clumps
/// @return the units, in the order of their heads
/// @throws std::invalid_argument if a member's clump is not among the rows (a clump split over
///         ranks: a bug, not bad input)
[[nodiscard]] Units unitsOf(const RankBodies& local);

/// The heads of `units`, as rows of their own (what Zoltan partitions).
/// @param local the rows the units were made of
/// @return the head rows, in unit order
[[nodiscard]] RankBodies unitHeads(const RankBodies& local, const Units& units);

/// The weight of each unit: the sum of its rows' weights (a clump weighs as its members and
/// itself).
/// @param rowWeights one weight per row of the RankBodies the units were made of; empty: 1 each
/// @return one weight per unit
[[nodiscard]] std::vector<double> unitWeights(const Units& units, std::span<const double> rowWeights);

/// The plan moving whole units from the plan `unitPlan` made for their heads (exportRows naming
/// units): every row of an exported unit leaves with it, and each rank learns the global ids
/// arriving (collective).
/// @param comm the ranks exchanging (collective)
/// @param local the rows the units were made of
/// @param unitPlan exportRows: unit indices; exportTo: their ranks; boxes: every rank's region
/// @return the plan over the rows of `local` (importFrom left empty)
[[nodiscard]] Plan unitPlanRows(MPI_Comm comm, const RankBodies& local, const Units& units, const Plan& unitPlan);

/// Every rank's region grown to hold the rows it owns (collective): a clump belongs to the rank
/// of its centre, and its members may reach out of that rank's box, where another rank's bodies
/// within the ghost distance of them must still be its ghosts.
/// @param comm the ranks (collective)
/// @param boxes every rank's region (index = rank), finite
/// @param where where each of this rank's own bodies lies in the regions' space (a periodic
///        cell's members beside their clumps: periodic/Regions.h)
/// @return every rank's region holding its rows
[[nodiscard]] std::vector<Box> reachingBoxes(MPI_Comm comm, std::span<const Box> boxes, std::span<const Vec3> where);
/// Make the clump references of `bodies` (clumpId, each held clump's member list) the rows they
/// are now, from the global ids they are kept as while rows travel.
/// @param bodies a rank's rows, their clumpId entries global ids (rewritten as rows)
/// @param globalIdOfRow the global id of each row, ascending
/// @param members per clump (by shape index), its members' global ids
/// @throws std::logic_error if a clump is held without one of its members, or a member without its clump
void linkClumps(Bodies& bodies, std::span<const GlobalId> globalIdOfRow, const std::vector<std::vector<GlobalId>>& members);
} // namespace talus::dem::distributed
