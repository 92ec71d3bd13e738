#pragma once

#include "dem/base/Threads.h"
#include "dem/core/EnergyTracker.h"

#include <cstddef>
#include <cstdint>
#include <utility>
#include <vector>

namespace talus::dem
{
class Scene;
class ContactLaw;
struct Contacts;

/// Where a thread's contacts stage stands (ContactShares::compute): what it says lets work on
/// the bodies whose contacts are all computed start while their records are still in the caches.
class ContactsProgress
{
public:
  virtual ~ContactsProgress() = default;
  /// The thread has computed its part of the boundary runs; its other contacts lie in the
  /// list's [first, last) (the runs inside that span excluded).
  virtual void start(std::int64_t first, std::int64_t last) = 0;
  /// The thread has computed all its contacts before list position `position`.
  virtual void reached(std::int64_t position) = 0;
};

/// A thread's share [first, last) of n items with its ends moved to multiples of energyBlock
/// (n stays n): the shares of the threads still tile the items, and each block of energy sums
/// lies in one of them.
/// @param share the thread's [first, last) before alignment
/// @param n the item count (an end at or past n stays n)
/// @return the aligned [first, last)
std::pair<std::int64_t, std::int64_t> blockAligned(std::pair<std::int64_t, std::int64_t> share, std::int64_t n);

/// How the contacts stage splits the contact list among the threads of a region.
///
/// The contacts of each wall, facet or box (runs of the list, each sorted by the sphere's id)
/// are computed by the threads that integrate their spheres, not by whichever thread's range of
/// the list they fall in: they lie at the list's end when the boundary was created last, and the
/// last thread then read the state of the other threads' spheres along the boundary, whose next
/// integration had to wait for those cache lines. Beyond maxBoundaryRuns runs (a large mesh)
/// every thread takes one contiguous range of the list.
class ContactShares
{
public:
  /// Find the boundary runs of the current contact list; does nothing until Contacts::version
  /// changes (once per re-detection).
  void update(const Contacts& contacts);
  /// Compute the contacts of thread `thread` of `threads` with `law`; `myBodies` are the bodies
  /// the thread integrates. With `energy` (blocks of energyBlock contacts) the shares are block-aligned
  /// ranges instead. Called by every thread of the region after update() on the current list.
  /// @param law the region's single contact law
  /// @param thread this thread's number, 0 to threads - 1
  /// @param threads the region's thread count
  /// @param myBodies the body ids [first, last) this thread integrates (its boundary contacts)
  /// @param energy null without energy tracking, else the per-block dissipation sums
  /// @param progress null, or told where the thread stands (chunk by chunk; not with `energy`,
  ///        whose shares take the runs in list order)
  /// @return the index of the first contact of this share overlapping too much, or the contact
  ///         count if none does
  std::int64_t compute(Scene& scene, ContactLaw& law, int thread, int threads,
                       std::pair<std::int64_t, std::int64_t> myBodies, ContactEnergy* energy,
                       ContactsProgress* progress = nullptr) const;
  /// The boundary runs [begin, end) of the current list, each computed by the threads that
  /// integrate its spheres; empty when every thread takes one contiguous range of the list.
  [[nodiscard]] const std::vector<std::pair<std::int64_t, std::int64_t>>& boundaryRuns() const { return boundaryRuns_; }

  BalancedRanges ranges; ///< contacts per thread

private:
  /// Thread `thread`'s part of the boundary runs: the contacts of the bodies it integrates.
  void computeRuns(Scene& scene, int thread, int threads, std::pair<std::int64_t, std::int64_t> bodies,
                   const auto& compute) const;

  /// The list position of the `counted`-th contact outside the runs (`contacts` past the last).
  [[nodiscard]] std::int64_t listPosition(std::int64_t counted, std::int64_t contacts) const;

  std::vector<std::pair<std::int64_t, std::int64_t>> boundaryRuns_;
  std::int64_t boundaryContacts_ = 0; ///< contacts in boundaryRuns_
  std::uint64_t runsVersion_ = 0;     ///< the Contacts::version boundaryRuns_ was found for
  static constexpr std::size_t maxBoundaryRuns = 64;
  /// Contacts between two reports to a ContactsProgress: their records (a quarter of a MiB)
  /// stay in a core's cache until the bodies they complete are gathered.
  static constexpr std::int64_t progressChunk = 1024;
};
} // namespace talus::dem
