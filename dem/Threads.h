#pragma once

#ifdef _OPENMP
#include <omp.h>
#endif

#include <cstdint>

namespace talus::dem
{
/// Loops over fewer items than this run on one thread (OpenMP `if` clause): a parallel region
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
} // namespace talus::dem
