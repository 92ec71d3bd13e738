#include "dem/distributed/RowMemory.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <stdexcept>
#include <string>
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

std::vector<Remembered> ownMemory(const EnergyTracker& energy, const Bodies& bodies,
                                 std::span<const GlobalId> globalId, std::span<const std::int64_t> ownedRows,
                                 bool imposed)
{
  constexpr double none = std::numeric_limits<double>::quiet_NaN();
  auto plain = [](const Vec3& v) { return std::array<double, 3>{v[0], v[1], v[2]}; };
  std::vector<Remembered> own;
  for (const std::int64_t row : ownedRows)
  {
    const auto i = static_cast<std::size_t>(row);
    Remembered r{globalId[i], i < energy.grownBy.size() ? energy.grownBy[i] : 0.0, {none, none, none}, {none, none, none}};
    if (imposed && (!bodies.dynamic[i] || bodies.blockedDofs[i] != 0) && i < energy.previousDisplacement.size())
    {
      r.displacement = plain(energy.previousDisplacement[i]);
      r.rotation = plain(energy.previousRotation[i]);
    }
    if (r.grownBy != 0 || !std::isnan(r.displacement[0]) || !std::isnan(r.rotation[0]))
      own.push_back(r);
  }
  return own;
}

void shareMemory(MPI_Comm comm, EnergyTracker& energy, const std::vector<Remembered>& own,
                 std::span<const GlobalId> rows, std::span<const std::uint8_t> replicated)
{
  int ranks = 1;
  MPI_Comm_size(comm, &ranks);
  // Every rank learns every rank's count, so all refuse alike a gather past MPI's int counts.
  const auto records = static_cast<std::int64_t>(own.size());
  std::vector<std::int64_t> counts(static_cast<std::size_t>(ranks));
  MPI_Allgather(&records, 1, MPI_INT64_T, counts.data(), 1, MPI_INT64_T, comm);
  std::int64_t total = 0;
  for (const std::int64_t n : counts)
    total += n;
  if (total > std::numeric_limits<int>::max() / static_cast<std::int64_t>(sizeof(Remembered)))
    throw std::overflow_error("re-detection: the energy memory of " + std::to_string(total) +
                              " bodies (a growth or imposed motions to hand over) is more than one MPI gather carries "
                              "(2 GiB); track no energy (O.trackEnergy = False) for runs of this size");
  const int mine = static_cast<int>(records * static_cast<std::int64_t>(sizeof(Remembered)));
  std::vector<int> bytes(static_cast<std::size_t>(ranks)), offsets(static_cast<std::size_t>(ranks) + 1, 0);
  for (std::size_t r = 0; r < bytes.size(); ++r)
  {
    bytes[r] = static_cast<int>(counts[r] * static_cast<std::int64_t>(sizeof(Remembered)));
    offsets[r + 1] = offsets[r] + bytes[r];
  }
  std::vector<Remembered> all(static_cast<std::size_t>(offsets.back()) / sizeof(Remembered));
  MPI_Allgatherv(own.data(), mine, MPI_BYTE, all.data(), bytes.data(), offsets.data(), MPI_BYTE, comm);
  auto byId = [](const Remembered& a, const Remembered& b) { return a.id < b.id; };
  std::sort(all.begin(), all.end(), byId);
  // a growth pending here or at any owner (records of imposed motions alone leave grownBy empty,
  // sparing the next contacts pass its growth check)
  const bool growing =
      !energy.grownBy.empty() || std::any_of(all.begin(), all.end(), [](const Remembered& r) { return r.grownBy != 0; });
  if (growing)
    energy.grownBy.resize(rows.size(), 0.0);
  for (std::size_t row = 0; row < rows.size(); ++row)
  {
    if (replicated[row])
      continue;
    const auto at = std::lower_bound(all.begin(), all.end(), Remembered{rows[row], 0, {}, {}}, byId);
    const bool found = at != all.end() && at->id == rows[row];
    if (growing)
      energy.grownBy[row] = found ? at->grownBy : 0.0;
    if (found && row < energy.previousDisplacement.size() && !std::isnan(at->displacement[0]))
    {
      energy.previousDisplacement[row] = Vec3(at->displacement.data());
      energy.previousRotation[row] = Vec3(at->rotation.data());
    }
  }
}
} // namespace talus::dem::distributed
