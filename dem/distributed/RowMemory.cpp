#include "dem/distributed/RowMemory.h"

#include <limits>
#include <vector>

namespace talus::dem::distributed
{
namespace
{
/// `values` (one per row of `before`) moved to the rows of `after`; NaN for an id not in `before`.
void follow(std::vector<Vec3>& values, std::span<const GlobalId> before, std::span<const GlobalId> after)
{
  if (values.empty())
    return;
  std::vector<Vec3> moved(after.size(), Vec3::Constant(std::numeric_limits<double>::quiet_NaN()));
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
  follow(energy.previousDisplacement, before, after);
  follow(energy.previousRotation, before, after);
}
} // namespace talus::dem::distributed
