#include "dem/Contacts.h"

#include <algorithm>

namespace talus::dem
{
void Contacts::index(std::size_t bodyCount)
{
  start.assign(bodyCount + 1, 0);
  for (const Contact& c : list)
  {
    ++start[static_cast<std::size_t>(c.id1) + 1];
    ++start[static_cast<std::size_t>(c.id2) + 1];
  }
  for (std::size_t b = 0; b < bodyCount; ++b)
    start[b + 1] += start[b];
  entries.resize(2 * list.size());
  std::vector<std::int64_t> fill(start.begin(), start.end() - 1);
  for (std::size_t k = 0; k < list.size(); ++k)
  {
    const auto ck = static_cast<std::int64_t>(k);
    entries[static_cast<std::size_t>(fill[static_cast<std::size_t>(list[k].id1)]++)] = ck << 1;
    entries[static_cast<std::size_t>(fill[static_cast<std::size_t>(list[k].id2)]++)] = (ck << 1) | 1;
  }
}

std::size_t Contacts::countReal() const
{
  return static_cast<std::size_t>(std::count_if(list.begin(), list.end(), [](const Contact& c) { return c.real; }));
}
} // namespace talus::dem
