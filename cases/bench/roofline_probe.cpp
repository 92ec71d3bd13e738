// The two roofs of the roofline case (cases/bench/dem_roofline.py), compiled by the case with the
// project's compiler and flags:
//   roofline_probe bandwidth BYTES REPETITIONS   STREAM's copy and triad over arrays of BYTES in
//                                                total; prints "COPY GB/s" and "TRIAD GB/s",
//                                                the best repetition of each
//   roofline_probe flops REPETITIONS             independent multiply-add chains held in
//                                                registers; prints "FLOPS GFLOP/s LANES"
// Threads: OMP_NUM_THREADS (each thread its own part of the arrays, or its own chains).
#include <omp.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

namespace
{
double seconds()
{
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

// Bytes counted as STREAM counts them: each array element read or written once (a store's
// read-for-ownership is not counted), the convention the case's byte counts follow too.
// Each thread streams its own part with no barrier between passes and times itself; the rate
// is the sum of the threads' rates. On a shared machine a barrier waits for a descheduled
// thread, which would measure the load, not the memory: here a pause spoils one repetition of
// one thread, and the best repetition is near what the memory gives.
void bandwidth(std::size_t bytes, int repetitions)
{
  const std::size_t n = bytes / (3 * sizeof(double));
  std::vector<double> a(n), b(n), c(n);
  // Each repetition streams at least 64 MiB (small arrays many times over).
  const int passes = static_cast<int>(std::max<std::size_t>(1, (std::size_t{64} << 20) / bytes));
  double copy = 0, triad = 0;
  for (int r = 0; r < repetitions; ++r)
  {
    double copyRate = 0, triadRate = 0;
#pragma omp parallel reduction(+ : copyRate, triadRate)
    {
      const std::size_t threads = static_cast<std::size_t>(omp_get_num_threads());
      const std::size_t t = static_cast<std::size_t>(omp_get_thread_num());
      const std::size_t first = n * t / threads, last = n * (t + 1) / threads;
      for (std::size_t i = first; i < last; ++i) // first touch by the thread that streams the part
      {
        a[i] = 1.0;
        b[i] = 2.0;
        c[i] = 0.5;
      }
      const double items = static_cast<double>(last - first) * passes;
      double start = seconds();
      for (int p = 0; p < passes; ++p)
        for (std::size_t i = first; i < last; ++i)
          c[i] = a[i] + p; // + p: the passes differ, so none is elided
      copyRate = 2.0 * sizeof(double) * items / (seconds() - start);
      start = seconds();
      for (int p = 0; p < passes; ++p)
        for (std::size_t i = first; i < last; ++i)
          a[i] = b[i] + 3.0 * c[i];
      triadRate = 3.0 * sizeof(double) * items / (seconds() - start);
    }
    copy = std::max(copy, copyRate);
    triad = std::max(triad, triadRate);
  }
  std::printf("COPY %.4f\nTRIAD %.4f\nCHECK %g\n", copy * 1e-9, triad * 1e-9, a[n / 2] + c[n / 3]);
}

// Enough independent chains to cover the latency of a multiply-add on two pipes with the
// widest vectors the flags allow; each chain is one vector of the compiler's choice of width.
constexpr int lanes = LANES;
constexpr int chains = 12;
using Vector = double __attribute__((vector_size(lanes * sizeof(double))));

void flops(int repetitions)
{
  const long iterations = 4'000'000 / lanes; // a few milliseconds: short repetitions, more of them unpaused
  double best = 0, sink = 0;
  for (int r = 0; r < repetitions; ++r)
  {
    double total = 0, rate = 0;
#pragma omp parallel reduction(+ : total, rate)
    {
      const double start = seconds(); // each thread times itself, as in bandwidth()
      Vector x[chains];
      const Vector m = Vector{} + (1.0 - 1e-9), add = Vector{} + 1e-9;
      for (int k = 0; k < chains; ++k)
        x[k] = Vector{} + (1.0 + k * 1e-3);
      for (long i = 0; i < iterations; ++i)
      {
#pragma GCC unroll 12
        for (int k = 0; k < chains; ++k)
          x[k] = x[k] * m + add; // a multiply and an add (fused where the flags allow); not
                                 // reassociated without -ffast-math, so every one is executed
      }
      rate = 2.0 * lanes * chains * static_cast<double>(iterations) / (seconds() - start);
      for (int k = 0; k < chains; ++k)
        for (int l = 0; l < lanes; ++l)
          total += x[k][l];
    }
    sink += total;
    best = std::max(best, rate);
  }
  std::printf("FLOPS %.4f %d\nCHECK %g\n", best * 1e-9, lanes, sink);
}
} // namespace

int main(int argc, char** argv)
{
  const std::string mode = argc > 1 ? argv[1] : "";
  if (mode == "bandwidth" && argc == 4)
    bandwidth(std::strtoull(argv[2], nullptr, 10), std::atoi(argv[3]));
  else if (mode == "flops" && argc == 3)
    flops(std::atoi(argv[2]));
  else
  {
    std::fprintf(stderr, "usage: roofline_probe bandwidth BYTES REPETITIONS | flops REPETITIONS\n");
    return 2;
  }
  return 0;
}
