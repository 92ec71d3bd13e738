#pragma once

#include "dem/distributed/BodyRows.h"

#include <mpi.h>

#include <span>
#include <stdexcept>
#include <string>
#include <vector>

namespace talus::dem::distributed
{
/// An error raised on every rank alike (by raiseOnEveryRank): each rank may report it and stop
/// on its own, none is left waiting for the others.
struct CollectiveError : std::runtime_error
{
  using std::runtime_error::runtime_error;
};

/// throwIfAnyRank's check, raising a CollectiveError on every rank.
/// @param comm the ranks that check together (every one of them calls it)
/// @param localError this rank's error message, empty if none
/// @throws CollectiveError with the lowest failing rank's message
void raiseOnEveryRank(MPI_Comm comm, const std::string& localError);

/// Raise one error on every rank of `comm` when any rank has one (collective): the ranks pass
/// what they found wrong (empty: nothing), and all throw the lowest failing rank's message, so
/// no rank goes on into a collective the others have left.
/// @param comm the ranks that check together (every one of them calls it)
/// @param localError this rank's error message, empty if none
/// @throws std::invalid_argument with that message
void throwIfAnyRank(MPI_Comm comm, const std::string& localError);

/// Send rows `rows` of `from` to the ranks `to` (one entry per row; collective, every rank
/// calls it, with nothing to send or not) and append the rows received to `into`, by source
/// rank, each source's rows in the order it listed them.
/// @param comm the ranks exchanging
/// @param from this rank's bodies
/// @param rows the rows sent
/// @param to the destination rank of each row
/// @param into the received rows are appended to it
/// @return the source rank of each row appended
/// @throws std::invalid_argument if `rows` and `to` differ in length or name a row or rank
///         that does not exist (on this rank only: a caller's bug, not bad input)
std::vector<int> sendRows(MPI_Comm comm, const RankBodies& from, std::span<const std::int64_t> rows,
                          std::span<const int> to, RankBodies& into);
} // namespace talus::dem::distributed
