#pragma once

#ifdef _OPENMP
#include <omp.h>
#endif

#include <algorithm>
#include <array>
#include <atomic>
#include <cstdint>
#include <utility>
#include <vector>

namespace talus::dem
{
/// Loops over fewer items than this run on one thread: a parallel region
/// costs microseconds even on idle cores, and on an oversubscribed machine its barrier waits for
/// descheduled threads, which made small scenes up to 100 times slower. Results do not depend on
/// the thread count, so the threshold changes speed only.
inline constexpr std::int64_t parallelLoopMinimum = 1024;

/// Number of OpenMP threads the DEM loops use (1 without OpenMP).
inline int threadCount()
{
#ifdef _OPENMP
  return omp_get_max_threads();
#else
  return 1;
#endif
}

/// Set the number of OpenMP threads for the following steps. Needed because OMP_NUM_THREADS is
/// read once, when the OpenMP runtime starts (at `import talus`), so changing the environment
/// afterwards (`talus run -j N`) has no effect by itself.
inline void setThreadCount(int threads)
{
#ifdef _OPENMP
  omp_set_num_threads(threads);
#else
  (void)threads;
#endif
}

/// Contiguous ranges of a loop's items per thread, one instance per loop (kept by its engine
/// from step to step), whose boundaries follow where balancedFor's threads had to steal work.
/// On this project's 2-vCPU machine the second half of the quick-performance scene's bodies
/// took 1.3-1.7 times longer per item than the first in every loop, whichever thread ran it,
/// and the host takes a vCPU away for a while at random, so fixed equal halves left one thread
/// waiting at every barrier. After each run every boundary moves by 1/512 of the items away
/// from the thread that lost items to a thief: the ranges stay nearly the same from step to
/// step, so each thread keeps its bodies' data in its own cache, which dynamic scheduling lost
/// (measured twice). Items must be independent: the ranges change the speed only, never a
/// result.
class BalancedRanges
{
public:
  static constexpr int maxThreads = 64;

  /// The items [first, second) of thread `thread` of `threads` in a loop over n items.
  [[nodiscard]] std::pair<std::int64_t, std::int64_t> range(std::int64_t n, int thread, int threads) const
  {
    if (threads != static_cast<int>(bounds_.size()) - 1)
      return {n * thread / threads, n * (thread + 1) / threads}; // not yet balanced for this count
    return {static_cast<std::int64_t>(bounds_[static_cast<std::size_t>(thread)] * static_cast<double>(n)),
            thread + 1 == threads ? n : static_cast<std::int64_t>(bounds_[static_cast<std::size_t>(thread + 1)] * static_cast<double>(n))};
  }
  /// Called after the loop by one thread with each thread's items lost to thieves minus those
  /// it stole (positive: the thread was late): move the boundaries towards no stealing.
  void rebalance(int threads, const std::array<std::int64_t, maxThreads>& late)
  {
    if (threads < 2 || threads > maxThreads)
      return;
    if (static_cast<int>(bounds_.size()) != threads + 1)
    {
      bounds_.resize(static_cast<std::size_t>(threads) + 1);
      for (int t = 0; t <= threads; ++t)
        bounds_[static_cast<std::size_t>(t)] = static_cast<double>(t) / threads;
      return; // the run was on equal ranges of another count
    }
    constexpr double step = 1.0 / 512, least = 0.25; // of the items; of an equal share
    const double gap = least / threads;
    for (int t = 1; t < threads; ++t)
    {
      const auto k = static_cast<std::size_t>(t);
      const double moved = bounds_[k] + (late[k - 1] > late[k] ? -step : late[k - 1] < late[k] ? step : 0.0);
      bounds_[k] = std::clamp(moved, bounds_[k - 1] + gap, 1.0 - (threads - t) * gap);
    }
  }

private:
  std::vector<double> bounds_; ///< fractions of the items where each thread's range starts, and 1
};

namespace detail
{
/// The items [front, back) of one thread's range not yet claimed, in one word so that its owner
/// (claiming chunks at the front) and a thief (taking half of the rest from the back) each claim
/// with one compare-and-swap; on a cache line of its own, which only thieves read besides it.
/// Front only grows and back only shrinks, so a stale word never matches again (no ABA).
struct alignas(64) UnclaimedItems
{
  std::atomic<std::uint64_t> span{0};

  static std::uint64_t pack(std::uint64_t front, std::uint64_t back) { return front << 32 | back; }
  static std::uint64_t front(std::uint64_t word) { return word >> 32; }
  static std::uint64_t back(std::uint64_t word) { return word & 0xffffffffu; }
};
} // namespace detail

/// Run body(first, last) on ranges of [0, n) in parallel (one thread below parallelLoopMinimum
/// items) and return the ranges' results combined with `combine`, which must be associative and
/// commutative (a minimum, a logical or): which thread runs which items changes from run to run.
/// Each thread starts on its range of `ranges` in chunks from the front; a thread done with
/// its own range takes half of the unclaimed rest of the fullest other range, from its back,
/// so neither an uneven cost per item nor a descheduled thread leaves the other waiting for
/// more than one chunk. The thefts move the ranges' boundaries for the next run.
template <class Result, class Body, class Combine>
Result balancedFor(BalancedRanges& ranges, std::int64_t n, Result init, Body&& body, Combine&& combine)
{
#ifdef _OPENMP
  const int planned = std::min(omp_get_max_threads(), BalancedRanges::maxThreads);
  if (n < parallelLoopMinimum || planned < 2 || n >= (std::int64_t{1} << 32))
    return n > 0 ? combine(init, body(std::int64_t{0}, n)) : init;
  // Claimed in chunks of an eighth of what is left, at least 16 items: a few dozen claims per
  // range, and at the end a thief waits for at most 16 items of another thread.
  constexpr std::uint64_t leastChunk = 16;
  std::array<detail::UnclaimedItems, BalancedRanges::maxThreads> unclaimed;
  for (int t = 0; t < planned; ++t)
  {
    const auto [first, last] = ranges.range(n, t, planned);
    unclaimed[static_cast<std::size_t>(t)].span.store(detail::UnclaimedItems::pack(static_cast<std::uint64_t>(first), static_cast<std::uint64_t>(last)), std::memory_order_relaxed);
  }
  std::array<Result, BalancedRanges::maxThreads> results;
  results.fill(init);
  std::array<std::atomic<std::int64_t>, BalancedRanges::maxThreads> lost{};
  std::array<std::int64_t, BalancedRanges::maxThreads> late{};
  int used = planned;
#pragma omp parallel num_threads(planned)
  {
    const int thread = omp_get_thread_num();
    if (thread == 0)
      used = omp_get_num_threads();
    Result& mine = results[static_cast<std::size_t>(thread)];
    // The whole of the loop if the runtime gave fewer threads than planned (nested, limited).
    if (omp_get_num_threads() != planned)
    {
#pragma omp single
      mine = combine(mine, body(std::int64_t{0}, n));
    }
    else
    {
      std::atomic<std::uint64_t>& own = unclaimed[static_cast<std::size_t>(thread)].span;
      for (std::uint64_t word = own.load(std::memory_order_acquire);;)
      {
        const std::uint64_t front = detail::UnclaimedItems::front(word), back = detail::UnclaimedItems::back(word);
        if (front >= back)
          break;
        const std::uint64_t end = std::min(back, front + std::max(leastChunk, (back - front) / 8));
        if (own.compare_exchange_weak(word, detail::UnclaimedItems::pack(end, back), std::memory_order_acq_rel))
        {
          mine = combine(mine, body(static_cast<std::int64_t>(front), static_cast<std::int64_t>(end)));
          word = own.load(std::memory_order_acquire);
        }
      }
      std::int64_t stolen = 0;
      for (;;)
      {
        int victim = -1;
        std::uint64_t word = 0, rest = 0;
        for (int t = 0; t < planned; ++t)
        {
          const std::uint64_t w = unclaimed[static_cast<std::size_t>(t)].span.load(std::memory_order_acquire);
          const std::uint64_t left = detail::UnclaimedItems::back(w) > detail::UnclaimedItems::front(w) ? detail::UnclaimedItems::back(w) - detail::UnclaimedItems::front(w) : 0;
          if (t != thread && left > rest)
          {
            victim = t;
            word = w;
            rest = left;
          }
        }
        if (rest < 2 * leastChunk)
          break; // what is left, its owners finish sooner than a theft would
        const std::uint64_t back = detail::UnclaimedItems::back(word), take = rest / 2;
        if (unclaimed[static_cast<std::size_t>(victim)].span.compare_exchange_strong(word, detail::UnclaimedItems::pack(detail::UnclaimedItems::front(word), back - take), std::memory_order_acq_rel))
        {
          mine = combine(mine, body(static_cast<std::int64_t>(back - take), static_cast<std::int64_t>(back)));
          stolen += static_cast<std::int64_t>(take);
          lost[static_cast<std::size_t>(victim)].fetch_add(static_cast<std::int64_t>(take), std::memory_order_relaxed);
        }
      }
      late[static_cast<std::size_t>(thread)] = -stolen;
    }
  }
  if (used == planned)
  {
    for (int t = 0; t < used; ++t)
      late[static_cast<std::size_t>(t)] += lost[static_cast<std::size_t>(t)].load(std::memory_order_relaxed);
    ranges.rebalance(used, late);
  }
  Result total = init;
  for (int t = 0; t < used; ++t)
    total = combine(total, results[static_cast<std::size_t>(t)]);
  return total;
#else
  (void)ranges;
  return n > 0 ? combine(init, body(std::int64_t{0}, n)) : init;
#endif
}

/// balancedFor for a body with no result.
template <class Body>
void balancedFor(BalancedRanges& ranges, std::int64_t n, Body&& body)
{
  balancedFor(
      ranges, n, 0,
      [&](std::int64_t first, std::int64_t last) {
        body(first, last);
        return 0;
      },
      [](int, int) { return 0; });
}
} // namespace talus::dem
