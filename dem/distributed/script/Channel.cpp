#include "dem/distributed/script/Channel.h"

#include <mpi.h>

#include <chrono>
#include <cstdio>
#include <stdexcept>
#include <thread>

namespace talus::dem::distributed
{
namespace
{
MPI_Comm channel = MPI_COMM_NULL;
} // namespace

void openScriptChannel()
{
  if (channel == MPI_COMM_NULL)
    MPI_Comm_dup(MPI_COMM_WORLD, &channel);
}

std::vector<double> gatherOnScriptChannel(std::span<const double> mine, double patience, const std::string& waiting)
{
  if (channel == MPI_COMM_NULL)
    throw std::logic_error("gatherOnScriptChannel: the script channel is not open (openScriptChannel at MPI's start)");
  int rank = 0, ranks = 1;
  MPI_Comm_rank(channel, &rank);
  MPI_Comm_size(channel, &ranks);
  std::vector<double> all(mine.size() * static_cast<std::size_t>(ranks));
  const int count = static_cast<int>(mine.size());
  MPI_Request request = MPI_REQUEST_NULL;
  MPI_Iallgather(mine.data(), count, MPI_DOUBLE, all.data(), count, MPI_DOUBLE, channel, &request);
  // Polled, not waited for: a rank left alone here must be able to give up. The first polls
  // are back to back (the partners usually arrive within microseconds, the script being the
  // same), then each after a short sleep, leaving the core to the others on a shared machine.
  const double deadline = MPI_Wtime() + patience;
  for (int polls = 0;; ++polls)
  {
    int done = 0;
    MPI_Test(&request, &done, MPI_STATUS_IGNORE);
    if (done)
      return all;
    if (MPI_Wtime() > deadline)
    {
      std::fprintf(stderr, "%s (process %d of %d waited %g s for the others: ending the run)\n", waiting.c_str(), rank,
                   ranks, patience);
      std::fflush(stderr);
      MPI_Abort(MPI_COMM_WORLD, 1);
    }
    if (polls > 200)
      std::this_thread::sleep_for(std::chrono::microseconds(20));
  }
}
} // namespace talus::dem::distributed
