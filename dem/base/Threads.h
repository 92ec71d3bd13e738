#pragma once

#ifdef _OPENMP
#include <omp.h>
#endif

#include <algorithm>
#include <array>
#include <cstdint>
#include <utility>
#include <vector>

namespace talus::dem
{
/// Loops over fewer items than this run on one thread (OpenMP `if` clause): a parallel region
/// costs microseconds even on idle cores, and on an oversubscribed machine its barrier waits for
/// descheduled threads, which made small scenes many times slower (docs/dem.md, "Measurements
/// behind the code"). Results do not depend on the thread count, so the threshold changes speed
/// only.
inline constexpr std::int64_t parallelLoopMinimum = 1024;

/// Number of OpenMP threads the DEM loops use (1 without OpenMP).
/// @return omp_get_max_threads(), at least 1
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
/// @param threads the count, >= 1 (OpenMP's own rules for other values); ignored without OpenMP
inline void setThreadCount(int threads)
{
#ifdef _OPENMP
  omp_set_num_threads(threads);
#else
  (void)threads;
#endif
}

/// Contiguous ranges of a loop's items per thread whose boundaries follow the threads' measured
/// times, one instance per loop (kept by its engine from step to step). On a virtual machine one
/// half of a scene's bodies may take markedly longer per item than the other in every loop, even
/// in the ForceResetter's copy, whichever thread runs it (docs/dem.md, Speed: the per-thread busy
/// times), so equal halves leave one thread waiting at every barrier. After each run every boundary moves by 1/512 of the items towards the
/// thread that finished first: one late run (a descheduled thread) moves it by one step only,
/// and the ranges stay nearly the same from step to step, so each thread keeps its bodies'
/// data in its own cache, which dynamic scheduling lost (measured twice). Items must be
/// independent: the ranges change the speed only, never a result.
class BalancedRanges
{
public:
  static constexpr int maxThreads = 64;

  /// The items [first, second) of thread `thread` of `threads` in a loop over n items.
  /// @param n the loop's item count
  /// @param thread this thread's number, 0 to threads - 1
  /// @param threads the team's size; equal shares until rebalance has seen this count
  /// @return the thread's range; the ranges of all threads tile [0, n)
  [[nodiscard]] std::pair<std::int64_t, std::int64_t> range(std::int64_t n, int thread, int threads) const
  {
    if (threads != static_cast<int>(bounds_.size()) - 1)
      return {n * thread / threads, n * (thread + 1) / threads}; // not yet balanced for this count
    return {static_cast<std::int64_t>(bounds_[static_cast<std::size_t>(thread)] * static_cast<double>(n)),
            thread + 1 == threads ? n : static_cast<std::int64_t>(bounds_[static_cast<std::size_t>(thread + 1)] * static_cast<double>(n))};
  }
  /// Called by each thread with the seconds its range took.
  /// @param thread the thread's number, below maxThreads
  /// @param seconds the wall time of its range (s)
  void record(int thread, double seconds) { times_[static_cast<std::size_t>(thread)] = seconds; }
  /// Called after the loop by one thread: move the boundaries towards equal times.
  /// @param threads the team's size; 1 or more than maxThreads leaves the ranges as they are
  void rebalance(int threads)
  {
    if (threads < 2 || threads > maxThreads)
      return;
    if (static_cast<int>(bounds_.size()) != threads + 1)
    {
      bounds_.resize(static_cast<std::size_t>(threads) + 1);
      for (int t = 0; t <= threads; ++t)
        bounds_[static_cast<std::size_t>(t)] = static_cast<double>(t) / threads;
      return; // the times were measured on equal ranges of another count
    }
    constexpr double step = 1.0 / 512, least = 0.25; // of the items; of an equal share
    const double gap = least / threads;
    for (int t = 1; t < threads; ++t)
    {
      const auto k = static_cast<std::size_t>(t);
      const double moved = bounds_[k] + (times_[k - 1] > times_[k] ? -step : times_[k - 1] < times_[k] ? step : 0.0);
      bounds_[k] = std::clamp(moved, bounds_[k - 1] + gap, 1.0 - (threads - t) * gap);
    }
  }

private:
  std::vector<double> bounds_;            ///< fractions of the items where each thread's range starts, and 1
  std::array<double, maxThreads> times_{}; ///< seconds of each thread's last range
};

/// Run body(first, last) on contiguous ranges of [0, n) in parallel (one thread below
/// parallelLoopMinimum items), the ranges balanced by `ranges`; returns the per-range results
/// combined in range order with `combine`, so the result does not depend on the ranges.
/// @param ranges the loop's own ranges, rebalanced by the threads' times after the loop
/// @param n the item count
/// @param init each range's result before body runs (and combine's first argument)
/// @param body body(first, last) returns the range's Result
/// @param combine combine(total, rangeResult), called in range order
/// @return the combined result
template <class Result, class Body, class Combine>
Result balancedFor(BalancedRanges& ranges, std::int64_t n, Result init, Body&& body, Combine&& combine)
{
  std::array<Result, BalancedRanges::maxThreads> results;
  results.fill(init);
  int used = 1;
#pragma omp parallel if (n >= parallelLoopMinimum)
  {
#ifdef _OPENMP
    const int thread = omp_get_thread_num(), threads = std::min(omp_get_num_threads(), BalancedRanges::maxThreads);
    const double start = omp_get_wtime();
#else
    const int thread = 0, threads = 1;
#endif
    if (thread < threads)
    {
      const auto [first, last] = ranges.range(n, thread, threads);
      results[static_cast<std::size_t>(thread)] = body(first, last);
#ifdef _OPENMP
      ranges.record(thread, omp_get_wtime() - start);
#endif
    }
    if (thread == 0)
      used = threads;
  }
  ranges.rebalance(used);
  Result total = init;
  for (int t = 0; t < used; ++t)
    total = combine(total, results[static_cast<std::size_t>(t)]);
  return total;
}

/// balancedFor for a body with no result.
/// @param ranges the loop's own ranges
/// @param n the item count
/// @param body body(first, last) for each range
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
