#include "dem/distributed/slabs/HeldRows.h"

#include <algorithm>

namespace talus::dem::distributed
{
std::vector<std::int64_t> offeredRows(const std::vector<std::int64_t>& spheres, const HeldRows* held, int rank,
                                      int ranks)
{
  std::vector<std::int64_t> everyones, offered;
  for (const std::int64_t row : spheres)
    (held && held->own[static_cast<std::size_t>(row)] ? offered : everyones).push_back(row);
  const auto P = static_cast<std::size_t>(ranks), me = static_cast<std::size_t>(rank);
  offered.insert(offered.end(), everyones.begin() + static_cast<std::ptrdiff_t>(everyones.size() * me / P),
                 everyones.begin() + static_cast<std::ptrdiff_t>(everyones.size() * (me + 1) / P));
  std::sort(offered.begin(), offered.end());
  return offered;
}

std::int64_t sceneSpheres(MPI_Comm comm, const std::vector<std::int64_t>& spheres, const HeldRows* held)
{
  if (!held)
    return static_cast<std::int64_t>(spheres.size());
  std::int64_t own = 0;
  for (const std::int64_t row : spheres)
    own += held->own[static_cast<std::size_t>(row)];
  std::int64_t slabs = own;
  MPI_Allreduce(MPI_IN_PLACE, &slabs, 1, MPI_INT64_T, MPI_SUM, comm);
  return static_cast<std::int64_t>(spheres.size()) - own + slabs;
}
} // namespace talus::dem::distributed
