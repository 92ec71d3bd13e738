#include "dem/distributed/Migration.h"

#include "dem/distributed/Collective.h"

#include <algorithm>
#include <stdexcept>

namespace talus::dem::distributed
{
void migrate(MPI_Comm comm, RankBodies& local, const Plan& plan)
{
  const std::size_t before = local.size();
  (void)sendRows(comm, local, plan.exportRows, plan.exportTo, local);

  std::vector<GlobalId> expected = plan.importIds;
  std::vector<GlobalId> got(local.globalId.begin() + static_cast<std::ptrdiff_t>(before), local.globalId.end());
  std::sort(expected.begin(), expected.end());
  std::sort(got.begin(), got.end());
  std::string error;
  if (got != expected)
  {
    int rank = 0;
    MPI_Comm_rank(comm, &rank);
    error = "migrate: rank " + std::to_string(rank) + " received " + std::to_string(got.size())
            + " bodies where the plan announced " + std::to_string(expected.size()) + " (or other ids)";
  }
  try
  {
    throwIfAnyRank(comm, error);
  }
  catch (const std::invalid_argument& e)
  {
    throw std::runtime_error(e.what());
  }

  // The arrivals were appended after the rows that were there; drop the rows that left.
  std::vector<std::uint8_t> keep(local.size(), 1);
  for (const std::int64_t row : plan.exportRows)
    keep[static_cast<std::size_t>(row)] = 0;
  keepRows(local, keep);
}
} // namespace talus::dem::distributed
