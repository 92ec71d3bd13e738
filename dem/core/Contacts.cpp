#include "dem/core/Contacts.h"

#include "dem/base/CountingSort.h"

#include <algorithm>
#include <atomic>
#include <stdexcept>
#include <string>

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

void Contacts::removeIf(const std::function<bool(const Contact&)>& doomed, std::size_t bodyCount)
{
  const bool withExtra = extraState() != nullptr;
  std::size_t kept = 0;
  for (std::size_t k = 0; k < list.size(); ++k)
  {
    if (doomed(list[k]))
      continue;
    if (kept != k)
    {
      list[kept] = list[k];
      if (withExtra)
        extra[kept] = extra[k];
    }
    ++kept;
  }
  list.resize(kept);
  if (withExtra)
    extra.resize(kept);
  index(bodyCount);
}

const ContactExtra* Contacts::extraState() const
{
  if (extra.empty())
    return nullptr;
  if (extra.size() != list.size())
    throw std::logic_error("contact state (Contacts::extra) has " + std::to_string(extra.size()) + " entries for "
                           + std::to_string(list.size()) + " contacts");
  return extra.data();
}

ContactExtra* Contacts::extraState() { return const_cast<ContactExtra*>(std::as_const(*this).extraState()); }

std::size_t Contacts::countReal() const
{
  return static_cast<std::size_t>(std::count_if(list.begin(), list.end(), [](const Contact& c) { return c.real; }));
}
} // namespace talus::dem
