#pragma once

// Vectors of four doubles (AVX2) holding one value of four contacts or bodies, for the kernels
// that run four at a time where the processor has AVX2 (chosen at run time). A lane rounds as a
// scalar does (IEEE addition, multiplication, division and square root), so a kernel that does
// a scalar path's operations in the same order gives its bits: these functions compute what
// Eigen's scalar expressions compute (a dot product adds its first two products, then the
// third). No fused multiply-add: the target is AVX2 alone, and the files using them are
// compiled without contraction. Include only from such a file.
#include <immintrin.h>

#include <cstddef>

#define TALUS_AVX2 gnu::target("avx2"), gnu::always_inline

namespace talus::dem::avx2
{
/// The lanes of one value of each of four Vec3s.
struct Lanes3
{
  __m256d x, y, z;
};

[[TALUS_AVX2]] inline __m256d add(__m256d a, __m256d b) { return _mm256_add_pd(a, b); }
[[TALUS_AVX2]] inline __m256d sub(__m256d a, __m256d b) { return _mm256_sub_pd(a, b); }
[[TALUS_AVX2]] inline __m256d mul(__m256d a, __m256d b) { return _mm256_mul_pd(a, b); }
[[TALUS_AVX2]] inline __m256d div(__m256d a, __m256d b) { return _mm256_div_pd(a, b); }
[[TALUS_AVX2]] inline __m256d broadcast(double v) { return _mm256_set1_pd(v); }
[[TALUS_AVX2]] inline Lanes3 add(const Lanes3& a, const Lanes3& b) { return {add(a.x, b.x), add(a.y, b.y), add(a.z, b.z)}; }
[[TALUS_AVX2]] inline Lanes3 sub(const Lanes3& a, const Lanes3& b) { return {sub(a.x, b.x), sub(a.y, b.y), sub(a.z, b.z)}; }
/// s v (Eigen's scalar times vector), component by component.
[[TALUS_AVX2]] inline Lanes3 scale(__m256d s, const Lanes3& v) { return {mul(s, v.x), mul(s, v.y), mul(s, v.z)}; }
/// Eigen's cwiseProduct.
[[TALUS_AVX2]] inline Lanes3 product(const Lanes3& a, const Lanes3& b) { return {mul(a.x, b.x), mul(a.y, b.y), mul(a.z, b.z)}; }
/// Lane by lane, a where `mask` is set (all bits of a comparison's lane), else b.
[[TALUS_AVX2]] inline __m256d select(__m256d mask, __m256d a, __m256d b) { return _mm256_blendv_pd(b, a, mask); }
[[TALUS_AVX2]] inline Lanes3 select(__m256d mask, const Lanes3& a, const Lanes3& b)
{
  return {select(mask, a.x, b.x), select(mask, a.y, b.y), select(mask, a.z, b.z)};
}
/// (a0 b0 + a1 b1) + a2 b2, Eigen's order.
[[TALUS_AVX2]] inline __m256d dot(const Lanes3& a, const Lanes3& b)
{
  return add(add(mul(a.x, b.x), mul(a.y, b.y)), mul(a.z, b.z));
}
/// Eigen's cross product: a1 b2 - a2 b1, a2 b0 - a0 b2, a0 b1 - a1 b0.
[[TALUS_AVX2]] inline Lanes3 cross(const Lanes3& a, const Lanes3& b)
{
  return {sub(mul(a.y, b.z), mul(a.z, b.y)), sub(mul(a.z, b.x), mul(a.x, b.z)), sub(mul(a.x, b.y), mul(a.y, b.x))};
}

/// The three doubles at a, b, c, d as lanes 0 to 3.
[[TALUS_AVX2]] inline Lanes3 load(const double* a, const double* b, const double* c, const double* d)
{
  const __m256d ac = _mm256_insertf128_pd(_mm256_castpd128_pd256(_mm_loadu_pd(a)), _mm_loadu_pd(c), 1);
  const __m256d bd = _mm256_insertf128_pd(_mm256_castpd128_pd256(_mm_loadu_pd(b)), _mm_loadu_pd(d), 1);
  return {_mm256_unpacklo_pd(ac, bd), _mm256_unpackhi_pd(ac, bd), _mm256_set_pd(d[2], c[2], b[2], a[2])};
}
/// Four consecutive triples from p.
[[TALUS_AVX2]] inline Lanes3 load(const double* p) { return load(p, p + 3, p + 6, p + 9); }

/// Lane i of v to *at[i] where bit i of `lanes` is set.
[[TALUS_AVX2]] inline void store(__m256d v, double* const* at, unsigned lanes)
{
  alignas(32) double lane[4];
  _mm256_store_pd(lane, v);
  for (int i = 0; i < 4; ++i)
    if (lanes & (1U << i))
      *at[i] = lane[i];
}
/// Lane i of v to the triple at[i] where bit i of `lanes` is set.
[[TALUS_AVX2]] inline void store(const Lanes3& v, double* const* at, unsigned lanes)
{
  alignas(32) double x[4], y[4], z[4];
  _mm256_store_pd(x, v.x);
  _mm256_store_pd(y, v.y);
  _mm256_store_pd(z, v.z);
  for (int i = 0; i < 4; ++i)
    if (lanes & (1U << i))
    {
      at[i][0] = x[i];
      at[i][1] = y[i];
      at[i][2] = z[i];
    }
}
/// The four lanes to the consecutive triples from p.
[[TALUS_AVX2]] inline void store(const Lanes3& v, double* p)
{
  double* const at[4] = {p, p + 3, p + 6, p + 9};
  store(v, at, 15U);
}
} // namespace talus::dem::avx2
