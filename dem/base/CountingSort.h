#pragma once

#include "dem/base/Threads.h"

#include <cstdint>
#include <utility>
#include <vector>

namespace talus::dem
{
/// A stable counting sort of items into buckets, in parallel: item i has one or more keys (a
/// bucket each; forEachKey(i, emit) calls emit(bucket, tag) for each), and place(i, tag, slot)
/// is called once per key with its slot in bucket order. On return, bucket k's slots are
/// [start[k], start[k+1]). Within a bucket, slots follow the item order (and the keys' order
/// within an item), so the result is the same for every thread count.
///
/// Each thread counts, then files, one contiguous run of items (the entries it writes are those
/// of the items it read): the linked cells of the collider and the per-body contact index are
/// built this way, and both were serial parts of a re-detection.
/// @param items the item count
/// @param buckets the bucket count (keys lie in [0, buckets))
/// @param start resized to buckets + 1 and filled with the buckets' first slots (start[buckets]:
///        the total number of keys)
/// @param forEachKey forEachKey(i, emit): emit(bucket, tag) for each key of item i, the same
///        keys in both passes (it is called twice per item)
/// @param place place(i, tag, slot) once per key
template <class ForEachKey, class Place>
void stableCountingSort(std::int64_t items, std::int64_t buckets, std::vector<std::int64_t>& start,
                        ForEachKey&& forEachKey, Place&& place)
{
  // The threads' counts cost in proportion to the buckets: with more buckets than items (the
  // collider's cells) one thread is faster than several clearing and summing their own counts
  // (docs/dem.md, "Measurements behind the code").
  const int threads = (items >= parallelLoopMinimum && buckets < items) ? threadCount() : 1;
  // counts[t * buckets + k]: how many keys of run t fall in bucket k; then where run t's slots
  // begin within bucket k's.
  std::vector<std::int64_t> counts(static_cast<std::size_t>(threads) * static_cast<std::size_t>(buckets), 0);
  start.resize(static_cast<std::size_t>(buckets) + 1);
#pragma omp parallel num_threads(threads) if (threads > 1)
  {
#ifdef _OPENMP
    const int t = omp_get_thread_num(), team = omp_get_num_threads();
#else
    const int t = 0, team = 1;
#endif
    const std::int64_t first = items * t / team, last = items * (t + 1) / team;
    std::int64_t* count = counts.data() + static_cast<std::ptrdiff_t>(t) * buckets;
    for (std::int64_t i = first; i < last; ++i)
      forEachKey(i, [count](std::int64_t k, int) { ++count[k]; });
#pragma omp barrier
#pragma omp for schedule(static)
    for (std::int64_t k = 0; k < buckets; ++k)
    {
      std::int64_t total = 0;
      for (int u = 0; u < team; ++u)
        total += std::exchange(counts[static_cast<std::size_t>(u * buckets + k)], total);
      start[static_cast<std::size_t>(k) + 1] = total;
    }
#pragma omp single
    {
      start[0] = 0;
      for (std::size_t k = 0; k < static_cast<std::size_t>(buckets); ++k)
        start[k + 1] += start[k];
    }
    for (std::int64_t i = first; i < last; ++i)
      forEachKey(i, [&, i](std::int64_t k, int tag) { place(i, tag, start[static_cast<std::size_t>(k)] + count[k]++); });
  }
}
} // namespace talus::dem
