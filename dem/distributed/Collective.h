#pragma once

#include "dem/distributed/BodyRows.h"

#include <mpi.h>

#include <cstring>
#include <limits>
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

/// The lowest failing rank's error message, on every rank, or "" when no rank has one
/// (collective). A rank with an error whose partners do not all join the check within
/// `patience` seconds (they are held elsewhere, in a collective call it left by failing) prints
/// its message to the standard error and ends the run (MPI_Abort) instead of waiting forever.
/// @param comm the ranks that check together (every one of them calls it)
/// @param localError this rank's error message, empty if none
/// @param patience seconds a failing rank waits for the others (infinity: as long as it takes)
/// @return the message, the same on every rank
std::string lowestRankError(MPI_Comm comm, const std::string& localError,
                            double patience = std::numeric_limits<double>::infinity());

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

/// Append the bytes of `x` to a message: a value that holds no pointers (Eigen's fixed-size
/// vectors are not trivially copyable to the compiler, but their bytes are their value).
/// @param out the message, grown by sizeof(T)
/// @param x the value
template <class T>
void appendBytes(std::vector<std::byte>& out, const T& x)
{
  const std::size_t at = out.size();
  out.resize(at + sizeof(T));
  std::memcpy(out.data() + at, static_cast<const void*>(&x), sizeof(T));
}

/// Read a value appended by appendBytes.
/// @param in where it starts in a message
/// @param x the value, read
/// @return where the next value starts
template <class T>
const std::byte* readBytes(const std::byte* in, T& x)
{
  std::memcpy(static_cast<void*>(&x), in, sizeof(T));
  return in + sizeof(T);
}

/// Send the bytes `out[r]` to each rank r (collective, every rank calls it with one entry per
/// rank, empty or not).
/// @param comm the ranks exchanging
/// @param out what goes to each rank
/// @return what each rank sent here, concatenated by source rank
std::vector<std::byte> sendBytes(MPI_Comm comm, const std::vector<std::vector<std::byte>>& out);
} // namespace talus::dem::distributed
