#include "dem/step/ContactShares.h"

#include "dem/core/Scene.h"
#include "dem/laws/ContactLaw.h"

#include <algorithm>

namespace talus::dem
{
std::pair<std::int64_t, std::int64_t> blockAligned(std::pair<std::int64_t, std::int64_t> share, std::int64_t n)
{
  auto align = [n](std::int64_t x) { return x >= n ? n : std::min(n, (x + energyBlock / 2) / energyBlock * energyBlock); };
  return {align(share.first), align(share.second)};
}

void ContactShares::update(const Contacts& contacts)
{
  if (runsVersion_ == contacts.version)
    return;
  runsVersion_ = contacts.version;
  const ContactList& list = contacts.list;
  boundaryRuns_.clear();
  boundaryContacts_ = 0;
  for (std::size_t k = 0; k < list.size();)
  {
    const ContactGeometryKind kind = list[k].kind;
    const bool boundary = kind == ContactGeometryKind::WallSphere || kind == ContactGeometryKind::FacetSphere
                          || kind == ContactGeometryKind::BoxSphere;
    std::size_t end = k + 1;
    while (end < list.size() && list[end].id1 == list[k].id1)
      ++end;
    if (boundary)
    {
      if (boundaryRuns_.size() == maxBoundaryRuns)
      {
        boundaryRuns_.clear(); // too many to split each one: contiguous ranges for all
        boundaryContacts_ = 0;
        break;
      }
      boundaryRuns_.emplace_back(static_cast<std::int64_t>(k), static_cast<std::int64_t>(end));
      boundaryContacts_ += static_cast<std::int64_t>(end - k);
    }
    k = end;
  }
}

std::int64_t ContactShares::compute(Scene& scene, ContactLaw& law, int thread, int threads,
                                    std::pair<std::int64_t, std::int64_t> myBodies, ContactEnergy* energy,
                                    ContactsProgress* progress) const
{
  const auto contacts = static_cast<std::int64_t>(scene.contacts.list.size());
  std::int64_t bad = contacts;
  auto compute = [&](std::int64_t first, std::int64_t last) {
    if (first < last)
      bad = std::min(bad, law.computeAllIn(scene, first, last, energy));
  };
  if (energy)
  {
    const auto [first, last] = blockAligned(ranges.range(contacts, thread, threads), contacts);
    compute(first, last);
    return bad;
  }
  // In chunks when someone follows: a chunk's records are still in the caches when the bodies
  // it completes are gathered.
  auto computeChunks = [&](std::int64_t first, std::int64_t last) {
    if (!progress)
      return compute(first, last);
    for (std::int64_t begin = first; begin < last; begin += progressChunk)
    {
      const std::int64_t end = std::min(last, begin + progressChunk);
      compute(begin, end);
      progress->reached(end);
    }
  };
  if (boundaryRuns_.empty())
  {
    const auto [first, last] = ranges.range(contacts, thread, threads);
    if (progress)
      progress->start(first, last);
    computeChunks(first, last);
    return bad;
  }
  // The runs first: a body's contacts with the boundary are then done before its others.
  computeRuns(scene, thread, threads, myBodies, compute);
  // This thread's share of the other contacts, counted over the gaps between the runs.
  const auto [from, to] = ranges.range(contacts - boundaryContacts_, thread, threads);
  if (progress)
    progress->start(listPosition(from, contacts), listPosition(to, contacts));
  std::int64_t gapStart = 0, counted = 0;
  auto gap = [&](std::int64_t gapEnd) {
    const std::int64_t length = gapEnd - gapStart;
    computeChunks(gapStart + std::clamp(from - counted, std::int64_t{0}, length),
                  gapStart + std::clamp(to - counted, std::int64_t{0}, length));
    counted += length;
  };
  for (const auto& [begin, end] : boundaryRuns_)
  {
    gap(begin);
    gapStart = end;
  }
  gap(contacts);
  return bad;
}

std::int64_t ContactShares::listPosition(std::int64_t counted, std::int64_t contacts) const
{
  std::int64_t position = counted;
  for (const auto& [begin, end] : boundaryRuns_)
    if (begin <= position)
      position += end - begin;
  return std::min(position, contacts);
}

void ContactShares::computeRuns(Scene& scene, int thread, int threads, std::pair<std::int64_t, std::int64_t> bodies,
                                const auto& compute) const
{
  // A run is sorted by the sphere's id.
  const ContactList& list = scene.contacts.list;
  auto firstOf = [&](std::int64_t begin, std::int64_t end, std::int64_t body) {
    return static_cast<std::int64_t>(
        std::lower_bound(list.begin() + begin, list.begin() + end, body,
                         [](const Contact& c, std::int64_t id) { return c.id2 < id; })
        - list.begin());
  };
  for (const auto& [begin, end] : boundaryRuns_)
    compute(thread == 0 ? begin : firstOf(begin, end, bodies.first),
            thread + 1 == threads ? end : firstOf(begin, end, bodies.second));
}
} // namespace talus::dem
