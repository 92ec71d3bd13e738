#include "dem/distributed/Ghosts.h"

#include "dem/distributed/Collective.h"

#include <string>

namespace talus::dem::distributed
{
Ghosts exchangeGhosts(MPI_Comm comm, const RankBodies& local, std::span<const Box> boxes, double distance)
{
  int rank = 0, ranks = 1;
  MPI_Comm_rank(comm, &rank);
  MPI_Comm_size(comm, &ranks);
  std::string error;
  if (!(distance >= 0.0))
    error = "exchangeGhosts: the ghost distance " + std::to_string(distance) + " is not zero or positive";
  else if (boxes.size() != static_cast<std::size_t>(ranks))
    error = "exchangeGhosts: rank " + std::to_string(rank) + " passed " + std::to_string(boxes.size())
            + " boxes for " + std::to_string(ranks) + " ranks";
  throwIfAnyRank(comm, error);

  Ghosts ghosts;
  ghosts.sentStart.assign(static_cast<std::size_t>(ranks) + 1, 0);
  std::vector<int> to;
  for (int r = 0; r < ranks; ++r)
  {
    if (r != rank)
      for (std::size_t i = 0; i < local.size(); ++i)
        if (distanceToBox(local.bodies.pos[i], boxes[static_cast<std::size_t>(r)]) <= distance)
        {
          ghosts.sentRows.push_back(static_cast<std::int64_t>(i));
          to.push_back(r);
        }
    ghosts.sentStart[static_cast<std::size_t>(r) + 1] = static_cast<std::int64_t>(ghosts.sentRows.size());
  }
  ghosts.owner = sendRows(comm, local, ghosts.sentRows, to, ghosts.copies);
  return ghosts;
}
} // namespace talus::dem::distributed
