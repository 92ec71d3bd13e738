#pragma once

#include <cstddef>
#include <span>
#include <string>
#include <vector>

namespace talus::dem::distributed
{
/// Open the channel of the script's own collective calls (a duplicate of MPI_COMM_WORLD, so that
/// they never meet the step's messages): every rank calls it once, when MPI starts.
void openScriptChannel();

/// Every rank's `mine` (the same length on every rank), one after the other in rank order, on
/// every rank (collective over the script channel): what a script's by-id access and its
/// agreement points exchange, each rank saying where in the script it is. A rank that made the
/// call alone (the others are in another collective, from code some processes ran and others
/// did not) would wait forever: after `patience` seconds without every rank, it prints
/// `waiting` to the standard error and ends the run (MPI_Abort).
/// @param mine this rank's numbers
/// @param patience seconds to wait for the other ranks (infinity: as long as it takes)
/// @param waiting the message printed when they do not come
/// @return ranks × mine.size() numbers
std::vector<double> gatherOnScriptChannel(std::span<const double> mine, double patience, const std::string& waiting);
} // namespace talus::dem::distributed
