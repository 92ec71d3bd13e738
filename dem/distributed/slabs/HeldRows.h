#pragma once

#include "dem/distributed/BodyRows.h"

#include <mpi.h>

#include <cstdint>
#include <vector>

namespace talus::dem::distributed
{
/// The rows of a scene each rank built in part before its split: every rank holds the bodies the
/// script appended one by one (walls, facets, single spheres), but only its own slab of a packing
/// read in slabs (ymport.text under mpirun), so that no rank ever holds all the bodies.
struct HeldRows
{
  std::vector<GlobalId> globalId; ///< per row of the scene as this rank built it, ascending
  std::vector<std::uint8_t> own;  ///< per row: 1 for a sphere of this rank's slab, which no other rank holds
  std::int64_t count = 0;         ///< bodies of the whole scene (global ids 0 .. count - 1)
};

/// The spheres this rank offers to the first partition: its share (the r-th of P slices) of the
/// spheres every rank holds, and, with `held`, every sphere of its own slab.
/// @param spheres the rows of the live spheres this rank holds, ascending
/// @param held the scene's rows when it was built in slabs, null when every rank built it whole
/// @return rows, ascending
[[nodiscard]] std::vector<std::int64_t> offeredRows(const std::vector<std::int64_t>& spheres, const HeldRows* held,
                                                    int rank, int ranks);

/// The spheres of the whole scene (collective when `held` is given: the slabs are summed).
[[nodiscard]] std::int64_t sceneSpheres(MPI_Comm comm, const std::vector<std::int64_t>& spheres, const HeldRows* held);
} // namespace talus::dem::distributed
