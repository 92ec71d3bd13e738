#pragma once

#ifdef _OPENMP
#include <omp.h>
#endif

namespace talus::dem
{
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
