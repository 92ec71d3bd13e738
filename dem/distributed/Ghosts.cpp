#include "dem/distributed/Ghosts.h"

#include "dem/distributed/Collective.h"

#include <algorithm>
#include <string>

namespace talus::dem::distributed
{
Ghosts exchangeGhosts(MPI_Comm comm, const RankBodies& local, std::span<const Box> boxes, double distance,
                      std::span<const std::int64_t> groupOf)
{
  std::string error;
  if (!(distance >= 0.0))
    error = "exchangeGhosts: the ghost distance " + std::to_string(distance) + " is not zero or positive";
  throwIfAnyRank(comm, error);
  return exchangeGhosts(comm, local, boxes,
                        [distance](const Vec3& x, const Box& box) { return distanceToBox(x, box) <= distance; },
                        groupOf);
}

Ghosts exchangeGhosts(MPI_Comm comm, const RankBodies& local, std::span<const Box> boxes, const Reach& reaches,
                      std::span<const std::int64_t> groupOf)
{
  int rank = 0, ranks = 1;
  MPI_Comm_rank(comm, &rank);
  MPI_Comm_size(comm, &ranks);
  std::string error;
  if (boxes.size() != static_cast<std::size_t>(ranks))
    error = "exchangeGhosts: rank " + std::to_string(rank) + " passed " + std::to_string(boxes.size())
            + " boxes for " + std::to_string(ranks) + " ranks";
  throwIfAnyRank(comm, error);

  Ghosts ghosts;
  ghosts.sentStart.assign(static_cast<std::size_t>(ranks) + 1, 0);
  std::vector<int> to;
  std::vector<std::uint8_t> near(groupOf.empty() ? 0 : local.size());
  for (int r = 0; r < ranks; ++r)
  {
    auto within = [&](std::size_t i) { return reaches(local.bodies.pos[i], boxes[static_cast<std::size_t>(r)]); };
    if (!groupOf.empty() && r != rank) // a group goes whole when one of its rows is within reach
    {
      std::fill(near.begin(), near.end(), std::uint8_t{0});
      for (std::size_t i = 0; i < local.size(); ++i)
        if (within(i))
          near[static_cast<std::size_t>(groupOf[i])] = 1;
    }
    if (r != rank)
      for (std::size_t i = 0; i < local.size(); ++i)
        if (groupOf.empty() ? within(i) : near[static_cast<std::size_t>(groupOf[i])] != 0)
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
