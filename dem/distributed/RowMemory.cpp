#include "dem/distributed/RowMemory.h"

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
} // namespace talus::dem::distributed
