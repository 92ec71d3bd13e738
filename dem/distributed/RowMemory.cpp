#include "dem/distributed/RowMemory.h"

#include <algorithm>
#include <limits>
#include <vector>

namespace talus::dem::distributed
{
namespace
{
/// `values` (one per row of `before`) moved to the rows of `after`; `fresh` for an id not in `before`.
template <class Value>
void follow(std::vector<Value>& values, std::span<const GlobalId> before, std::span<const GlobalId> after,
            const Value& fresh)
{
  if (values.empty())
    return;
  std::vector<Value> moved(after.size(), fresh);
  // Both lists ascend: one walk along them.
  std::size_t k = 0;
  for (std::size_t row = 0; row < after.size(); ++row)
  {
    while (k < before.size() && before[k] < after[row])
      ++k;
    if (k < before.size() && before[k] == after[row] && k < values.size())
      moved[row] = values[k];
  }
  values = std::move(moved);
}
} // namespace

void followRows(EnergyTracker& energy, std::span<const GlobalId> before, std::span<const GlobalId> after)
{
  const Vec3 unknown = Vec3::Constant(std::numeric_limits<double>::quiet_NaN());
  follow(energy.previousDisplacement, before, after, unknown);
  follow(energy.previousRotation, before, after, unknown);
  follow(energy.grownBy, before, after, 0.0);
}

PendingGrowth ownGrowth(const EnergyTracker& energy, std::span<const GlobalId> globalId,
                        std::span<const std::int64_t> ownedRows)
{
  PendingGrowth own;
  for (const std::int64_t row : ownedRows)
    if (const auto i = static_cast<std::size_t>(row); i < energy.grownBy.size() && energy.grownBy[i] != 0)
      own.emplace_back(globalId[i], energy.grownBy[i]);
  return own;
}

void shareGrowth(MPI_Comm comm, EnergyTracker& energy, const PendingGrowth& own, std::span<const GlobalId> rows,
                 std::span<const std::uint8_t> replicated)
{
  int ranks = 1;
  MPI_Comm_size(comm, &ranks);
  const int mine = static_cast<int>(own.size() * sizeof(PendingGrowth::value_type));
  std::vector<int> bytes(static_cast<std::size_t>(ranks)), offsets(static_cast<std::size_t>(ranks) + 1, 0);
  MPI_Allgather(&mine, 1, MPI_INT, bytes.data(), 1, MPI_INT, comm);
  for (std::size_t r = 0; r < bytes.size(); ++r)
    offsets[r + 1] = offsets[r] + bytes[r];
  PendingGrowth all(static_cast<std::size_t>(offsets.back()) / sizeof(PendingGrowth::value_type));
  MPI_Allgatherv(own.data(), mine, MPI_BYTE, all.data(), bytes.data(), offsets.data(), MPI_BYTE, comm);
  std::sort(all.begin(), all.end());
  energy.grownBy.resize(rows.size(), 0.0);
  for (std::size_t row = 0; row < rows.size(); ++row)
  {
    if (replicated[row])
      continue;
    const auto at = std::lower_bound(all.begin(), all.end(), std::pair(rows[row], -std::numeric_limits<double>::infinity()));
    energy.grownBy[row] = at != all.end() && at->first == rows[row] ? at->second : 0.0;
  }
}
} // namespace talus::dem::distributed
