#pragma once

#include "dem/distributed/Partition.h"

#include <mpi.h>

namespace talus::dem::distributed
{
/// Move the bodies `plan` exports to their new ranks, every per-body field and the global id
/// with them, and take in the ones it imports (collective). Afterwards `local` holds the bodies
/// this rank owns: those that stayed, in their order, then the arrivals by source rank.
/// @param comm the ranks exchanging (collective)
/// @param local this rank's bodies, replaced by those it owns after the move
/// @param plan the partition's plan, made for `local` as it is
/// @throws std::invalid_argument if `plan` names a row or rank that does not exist (on this
///         rank only: a plan made for other bodies)
/// @throws std::runtime_error on every rank if the bodies arriving anywhere are not the ones the
///         plan announced there
void migrate(MPI_Comm comm, RankBodies& local, const Plan& plan);
} // namespace talus::dem::distributed
