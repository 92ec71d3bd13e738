#pragma once

#include "dem/base/Threads.h"
#include "dem/core/Scene.h"
#include "dem/engines/InteractionLoop.h"
#include "dem/step/ContactShares.h"

#include <algorithm>
#include <array>
#include <chrono>
#include <cstdint>
#include <limits>
#include <vector>

namespace talus::dem
{
/// The gather of forces per body run while the contacts stage goes on: a thread sums a body's
/// forces as soon as it has computed all the body's contacts, while their records are still in
/// the caches. Run after the stage, the gather read every record again from memory once the
/// contact list outgrew the caches, which made a large bed's particle-step dearer than a small
/// one's (docs/dem.md, Speed).
///
/// Each body's sum is the gather's own (InteractionLoop::gatherIn: its contacts in list order),
/// so the results are the same bits whichever thread gathers a body and when. A body whose
/// contacts another thread computes (at the ends of the threads' shares), or which owns a
/// boundary run (a wall, whose contacts the threads split by sphere), waits for the barrier
/// that ends the stage.
class GatherAhead
{
public:
  /// Find each body's first and last contact outside the boundary runs; does nothing until
  /// Contacts::version changes. Call after shares.update() on the same list.
  void update(const Contacts& contacts, const ContactShares& shares);

  /// One thread's gather of its bodies, told by its contacts stage where it stands.
  class Thread final : public ContactsProgress
  {
  public:
    /// @param thread the thread's number (its list of bodies left for finish())
    /// @param first, last the bodies [first, last) the thread gathers
    /// @param reset the gather also resets the bodies' forces (InteractionLoop::gatherIn)
    Thread(GatherAhead& ahead, Scene& scene, const InteractionLoop& loop, int thread, std::int64_t first,
           std::int64_t last, bool reset);
    void start(std::int64_t first, std::int64_t last) override;
    void reached(std::int64_t position) override;
    /// After the barrier that ends the contacts stage: the bodies not gathered yet.
    void finish();
    /// Wall seconds spent gathering inside the contacts stage.
    [[nodiscard]] double seconds() const { return seconds_; }

  private:
    /// Gather the bodies [first, last).
    void gather(std::int64_t first, std::int64_t last);

    const GatherAhead& ahead_;
    Scene& scene_;
    const InteractionLoop& loop_;
    std::vector<std::int64_t>& later_; ///< bodies left for finish()
    std::int64_t next_, end_;          ///< the next body to consider, the end of the thread's bodies
    std::int64_t last_;                ///< the end of those the contact list's index covers
    bool reset_;
    std::int64_t spanFirst_ = 0, spanLast_ = 0; ///< the list span of the thread's contacts
    double seconds_ = 0;
  };

private:
  /// Per body: the first and last list position of its contacts outside the boundary runs
  /// (none: the largest number and -1); the first is -1 for a body that owns a run.
  std::vector<std::int64_t> firstContact_, lastContact_;
  struct alignas(64) Later
  {
    std::vector<std::int64_t> bodies;
  };
  std::array<Later, BalancedRanges::maxThreads> later_{};
  std::uint64_t version_ = 0; ///< the Contacts::version the spans were found for
};

inline void GatherAhead::update(const Contacts& contacts, const ContactShares& shares)
{
  if (version_ == contacts.version)
    return;
  version_ = contacts.version;
  const auto bodies = static_cast<std::size_t>(contacts.indexedBodies());
  firstContact_.assign(bodies, std::numeric_limits<std::int64_t>::max());
  lastContact_.assign(bodies, -1);
  auto note = [&](BodyId id, std::int64_t k) {
    const auto b = static_cast<std::size_t>(id);
    firstContact_[b] = std::min(firstContact_[b], k);
    lastContact_[b] = std::max(lastContact_[b], k);
  };
  const ContactList& list = contacts.list;
  std::int64_t k = 0;
  auto outsideRuns = [&](std::int64_t end) {
    for (; k < end; ++k)
    {
      note(list[static_cast<std::size_t>(k)].id1, k);
      note(list[static_cast<std::size_t>(k)].id2, k);
    }
  };
  for (const auto& [begin, end] : shares.boundaryRuns())
  {
    outsideRuns(begin);
    firstContact_[static_cast<std::size_t>(list[static_cast<std::size_t>(begin)].id1)] = -1;
    k = end;
  }
  outsideRuns(static_cast<std::int64_t>(list.size()));
}

inline GatherAhead::Thread::Thread(GatherAhead& ahead, Scene& scene, const InteractionLoop& loop, int thread,
                            std::int64_t first, std::int64_t last, bool reset)
  : ahead_(ahead), scene_(scene), loop_(loop), later_(ahead.later_[static_cast<std::size_t>(thread)].bodies),
    next_(first), end_(last), last_(std::min(last, static_cast<std::int64_t>(ahead.firstContact_.size()))),
    reset_(reset)
{
  later_.clear();
}

inline void GatherAhead::Thread::start(std::int64_t first, std::int64_t last)
{
  spanFirst_ = first;
  spanLast_ = last;
}

inline void GatherAhead::Thread::reached(std::int64_t position)
{
  const auto t0 = std::chrono::steady_clock::now();
  std::int64_t run = next_;
  for (; next_ < last_; ++next_)
  {
    const auto b = static_cast<std::size_t>(next_);
    if (ahead_.firstContact_[b] < spanFirst_ || ahead_.lastContact_[b] >= spanLast_)
    {
      gather(run, next_); // the ready bodies before it
      later_.push_back(next_);
      run = next_ + 1;
    }
    else if (ahead_.lastContact_[b] >= position)
      break;
  }
  gather(run, next_);
  seconds_ += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

inline void GatherAhead::Thread::finish()
{
  gather(next_, end_);
  next_ = end_;
  for (const std::int64_t b : later_)
    gather(b, b + 1);
  later_.clear();
}

inline void GatherAhead::Thread::gather(std::int64_t first, std::int64_t last)
{
  if (first < last)
    loop_.gatherIn(scene_, first, last, reset_);
}
} // namespace talus::dem
