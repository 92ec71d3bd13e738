#include "dem/Contacts.h"

#include "dem/CountingSort.h"

#include <algorithm>
#include <atomic>

namespace talus::dem
{
namespace
{
std::atomic<std::uint64_t> lastVersion{0}; ///< the last Contacts::version handed out
} // namespace

void Contacts::index(std::size_t bodyCount)
{
  version = lastVersion.fetch_add(1) + 1;
  entries.resize(2 * list.size());
  stableCountingSort(
      static_cast<std::int64_t>(list.size()), static_cast<std::int64_t>(bodyCount), start,
      [this](std::int64_t k, auto&& emit) {
        emit(list[static_cast<std::size_t>(k)].id1, 0);
        emit(list[static_cast<std::size_t>(k)].id2, 1);
      },
      [this](std::int64_t k, int side, std::int64_t slot) { entries[static_cast<std::size_t>(slot)] = (k << 1) | side; });
}

std::size_t Contacts::countReal() const
{
  return static_cast<std::size_t>(std::count_if(list.begin(), list.end(), [](const Contact& c) { return c.real; }));
}
} // namespace talus::dem
