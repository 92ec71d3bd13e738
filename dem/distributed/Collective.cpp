#include "dem/distributed/Collective.h"

#include <chrono>
#include <cmath>
#include <cstdio>
#include <stdexcept>
#include <thread>

namespace talus::dem::distributed
{
std::string lowestRankError(MPI_Comm comm, const std::string& localError, double patience)
{
  int rank = 0, ranks = 1;
  MPI_Comm_rank(comm, &rank);
  MPI_Comm_size(comm, &ranks);
  int first = localError.empty() ? ranks : rank;
  MPI_Request request = MPI_REQUEST_NULL;
  MPI_Iallreduce(MPI_IN_PLACE, &first, 1, MPI_INT, MPI_MIN, comm, &request);
  if (localError.empty() || !std::isfinite(patience))
    MPI_Wait(&request, MPI_STATUS_IGNORE);
  else
    for (const double deadline = MPI_Wtime() + patience;;)
    {
      int done = 0;
      MPI_Test(&request, &done, MPI_STATUS_IGNORE);
      if (done)
        break;
      if (MPI_Wtime() > deadline)
      {
        std::fprintf(stderr, "%s (process %d of %d; the others did not come to check with it: ending the run)\n",
                     localError.c_str(), rank, ranks);
        std::fflush(stderr);
        MPI_Abort(comm, 1);
      }
      std::this_thread::sleep_for(std::chrono::microseconds(50));
    }
  if (first == ranks)
    return {};
  std::string message = localError;
  int length = static_cast<int>(message.size());
  MPI_Bcast(&length, 1, MPI_INT, first, comm);
  message.resize(static_cast<std::size_t>(length));
  MPI_Bcast(message.data(), length, MPI_CHAR, first, comm);
  return message;
}

void throwIfAnyRank(MPI_Comm comm, const std::string& localError)
{
  if (std::string message = lowestRankError(comm, localError); !message.empty())
    throw std::invalid_argument(message);
}

void raiseOnEveryRank(MPI_Comm comm, const std::string& localError)
{
  try
  {
    throwIfAnyRank(comm, localError);
  }
  catch (const std::invalid_argument& e)
  {
    throw CollectiveError(e.what());
  }
}

std::vector<int> sendRows(MPI_Comm comm, const RankBodies& from, std::span<const std::int64_t> rows,
                          std::span<const int> to, RankBodies& into)
{
  int ranks = 1;
  MPI_Comm_size(comm, &ranks);
  if (rows.size() != to.size())
    throw std::invalid_argument("sendRows: " + std::to_string(rows.size()) + " rows for " + std::to_string(to.size())
                                + " destinations");
  const auto P = static_cast<std::size_t>(ranks);
  // Group the rows by destination (stable: each destination gets them in the caller's order).
  std::vector<int> sendCounts(P, 0), sendStart(P + 1, 0);
  for (std::size_t k = 0; k < rows.size(); ++k)
  {
    if (to[k] < 0 || to[k] >= ranks || rows[k] < 0 || static_cast<std::size_t>(rows[k]) >= from.size())
      throw std::invalid_argument("sendRows: row " + std::to_string(rows[k]) + " to rank " + std::to_string(to[k])
                                  + " (rows: " + std::to_string(from.size()) + ", ranks: " + std::to_string(ranks) + ")");
    ++sendCounts[static_cast<std::size_t>(to[k])];
  }
  for (std::size_t r = 0; r < P; ++r)
    sendStart[r + 1] = sendStart[r] + sendCounts[r];
  std::vector<std::int64_t> grouped(rows.size());
  std::vector<int> next(sendStart.begin(), sendStart.end() - 1);
  for (std::size_t k = 0; k < rows.size(); ++k)
    grouped[static_cast<std::size_t>(next[static_cast<std::size_t>(to[k])]++)] = rows[k];
  std::vector<std::byte> sendBuffer;
  packRows(from, grouped, sendBuffer);

  std::vector<int> recvCounts(P, 0), recvStart(P + 1, 0);
  MPI_Alltoall(sendCounts.data(), 1, MPI_INT, recvCounts.data(), 1, MPI_INT, comm);
  for (std::size_t r = 0; r < P; ++r)
    recvStart[r + 1] = recvStart[r] + recvCounts[r];
  std::vector<std::byte> recvBuffer(static_cast<std::size_t>(recvStart[P]) * rowBytes());

  // Counts in rows, not bytes: a row type keeps them far from int's limit.
  MPI_Datatype row = MPI_DATATYPE_NULL;
  MPI_Type_contiguous(static_cast<int>(rowBytes()), MPI_BYTE, &row);
  MPI_Type_commit(&row);
  MPI_Alltoallv(sendBuffer.data(), sendCounts.data(), sendStart.data(), row, recvBuffer.data(), recvCounts.data(),
                recvStart.data(), row, comm);
  MPI_Type_free(&row);

  unpackRows(recvBuffer, into);
  std::vector<int> source;
  source.reserve(static_cast<std::size_t>(recvStart[P]));
  for (int r = 0; r < ranks; ++r)
    source.insert(source.end(), static_cast<std::size_t>(recvCounts[static_cast<std::size_t>(r)]), r);
  return source;
}

// GCC 12 cannot see that out.size() (the rank count) is small and warns that the count vectors
// might exceed the largest object.
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Walloc-size-larger-than="
std::vector<std::byte> sendBytes(MPI_Comm comm, const std::vector<std::vector<std::byte>>& out)
{
  const std::size_t P = out.size();
  if (P == 0)
    return {};
  std::vector<int> sendCounts(P), sendStart(P + 1, 0), recvCounts(P), recvStart(P + 1, 0);
  for (std::size_t r = 0; r < P; ++r)
  {
    sendCounts[r] = static_cast<int>(out[r].size());
    sendStart[r + 1] = sendStart[r] + sendCounts[r];
  }
  MPI_Alltoall(sendCounts.data(), 1, MPI_INT, recvCounts.data(), 1, MPI_INT, comm);
  for (std::size_t r = 0; r < P; ++r)
    recvStart[r + 1] = recvStart[r] + recvCounts[r];
  std::vector<std::byte> sendBuffer(static_cast<std::size_t>(sendStart[P])), in(static_cast<std::size_t>(recvStart[P]));
  for (std::size_t r = 0; r < P; ++r)
    std::copy(out[r].begin(), out[r].end(), sendBuffer.begin() + sendStart[r]);
  MPI_Alltoallv(sendBuffer.data(), sendCounts.data(), sendStart.data(), MPI_BYTE, in.data(), recvCounts.data(),
                recvStart.data(), MPI_BYTE, comm);
  return in;
}
#pragma GCC diagnostic pop
} // namespace talus::dem::distributed
