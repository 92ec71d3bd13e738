// Four contacts in the four lanes of AVX2 vectors: each lane does contactGeometry's sphere path
// with the same additions, multiplications, divisions and square roots in the same order, and
// IEEE arithmetic rounds a lane as it rounds a scalar, so a lane's results are the scalar
// path's bits. Eigen's sums of three products (dot, squaredNorm) add the first two, then the
// third. Fused multiply-adds would round differently: the functions' target is AVX2 alone (no
// FMA), and the file is compiled without contraction.
#include "dem/contact/SphereGeometryBatch.h"

#include <immintrin.h>

#include <array>
#include <vector>

namespace talus::dem
{
namespace
{
#define TALUS_AVX2 gnu::target("avx2"), gnu::always_inline

/// Three coordinates of four lanes.
struct Lanes3
{
  __m256d x, y, z;
};

/// The Vec3s at a, b, c, d as lanes 0 to 3.
[[TALUS_AVX2]] inline Lanes3 load(const double* a, const double* b, const double* c, const double* d)
{
  const __m256d ac = _mm256_insertf128_pd(_mm256_castpd128_pd256(_mm_loadu_pd(a)), _mm_loadu_pd(c), 1);
  const __m256d bd = _mm256_insertf128_pd(_mm256_castpd128_pd256(_mm_loadu_pd(b)), _mm_loadu_pd(d), 1);
  return {_mm256_unpacklo_pd(ac, bd), _mm256_unpackhi_pd(ac, bd), _mm256_set_pd(d[2], c[2], b[2], a[2])};
}

/// v[i[0]], ..., v[i[3]] as lanes 0 to 3.
[[TALUS_AVX2]] inline Lanes3 load(const std::vector<Vec3>& v, const std::size_t* i)
{
  return load(v[i[0]].data(), v[i[1]].data(), v[i[2]].data(), v[i[3]].data());
}
[[TALUS_AVX2]] inline __m256d load(const std::vector<double>& v, const std::size_t* i)
{
  return _mm256_set_pd(v[i[3]], v[i[2]], v[i[1]], v[i[0]]);
}
/// The member of the four contacts as lanes 0 to 3.
[[TALUS_AVX2]] inline Lanes3 load(Contact* const* c, Vec3 Contact::*member)
{
  return load((c[0]->*member).data(), (c[1]->*member).data(), (c[2]->*member).data(), (c[3]->*member).data());
}

/// The lane i of v to at[i] where bit i of `lanes` is set.
[[TALUS_AVX2]] inline void store(__m256d v, double* const* at, unsigned lanes)
{
  alignas(32) double lane[4];
  _mm256_store_pd(lane, v);
  for (int i = 0; i < sphereBatchWidth; ++i)
    if (lanes & (1U << i))
      *at[i] = lane[i];
}

/// The lanes of v to the Vec3s at[i] where bit i of `lanes` is set.
[[TALUS_AVX2]] inline void store(const Lanes3& v, double* const* at, unsigned lanes)
{
  alignas(32) double x[4], y[4], z[4];
  _mm256_store_pd(x, v.x);
  _mm256_store_pd(y, v.y);
  _mm256_store_pd(z, v.z);
  for (int i = 0; i < sphereBatchWidth; ++i)
    if (lanes & (1U << i))
    {
      at[i][0] = x[i];
      at[i][1] = y[i];
      at[i][2] = z[i];
    }
}

[[TALUS_AVX2]] inline __m256d add(__m256d a, __m256d b) { return _mm256_add_pd(a, b); }
[[TALUS_AVX2]] inline __m256d sub(__m256d a, __m256d b) { return _mm256_sub_pd(a, b); }
[[TALUS_AVX2]] inline __m256d mul(__m256d a, __m256d b) { return _mm256_mul_pd(a, b); }
[[TALUS_AVX2]] inline __m256d div(__m256d a, __m256d b) { return _mm256_div_pd(a, b); }
[[TALUS_AVX2]] inline Lanes3 add(const Lanes3& a, const Lanes3& b) { return {add(a.x, b.x), add(a.y, b.y), add(a.z, b.z)}; }
[[TALUS_AVX2]] inline Lanes3 sub(const Lanes3& a, const Lanes3& b) { return {sub(a.x, b.x), sub(a.y, b.y), sub(a.z, b.z)}; }
/// s v, component by component.
[[TALUS_AVX2]] inline Lanes3 scale(__m256d s, const Lanes3& v) { return {mul(s, v.x), mul(s, v.y), mul(s, v.z)}; }
/// (a0 b0 + a1 b1) + a2 b2, Eigen's order.
[[TALUS_AVX2]] inline __m256d dot(const Lanes3& a, const Lanes3& b)
{
  return add(add(mul(a.x, b.x), mul(a.y, b.y)), mul(a.z, b.z));
}
/// Eigen's cross product, a1 b2 - a2 b1, ...
[[TALUS_AVX2]] inline Lanes3 cross(const Lanes3& a, const Lanes3& b)
{
  return {sub(mul(a.y, b.z), mul(a.z, b.y)), sub(mul(a.z, b.x), mul(a.x, b.z)), sub(mul(a.x, b.y), mul(a.y, b.x))};
}
#undef TALUS_AVX2
} // namespace

bool sphereBatchAvailable()
{
  static const bool available = __builtin_cpu_supports("avx2");
  return available;
}

[[gnu::target("avx2")]] unsigned sphereGeometryBatch(Contact* const* contacts, const Bodies& b, double dt)
{
  Contact& c0 = *contacts[0];
  Contact& c1 = *contacts[1];
  Contact& c2 = *contacts[2];
  Contact& c3 = *contacts[3];
  const std::size_t i1[4] = {static_cast<std::size_t>(c0.id1), static_cast<std::size_t>(c1.id1),
                             static_cast<std::size_t>(c2.id1), static_cast<std::size_t>(c3.id1)};
  const std::size_t i2[4] = {static_cast<std::size_t>(c0.id2), static_cast<std::size_t>(c1.id2),
                             static_cast<std::size_t>(c2.id2), static_cast<std::size_t>(c3.id2)};

  // The overlap, as contactGeometry: d = (pos2 + shift2) - pos1 with a zero shift.
  const Lanes3 p1 = load(b.pos, i1);
  const __m256d zero = _mm256_setzero_pd();
  const Lanes3 d = sub(add(load(b.pos, i2), Lanes3{zero, zero, zero}), p1);
  const __m256d r1 = load(b.radius, i1), r2 = load(b.radius, i2);
  const __m256d dist2 = dot(d, d);
  const __m256d reach = add(r1, r2);
  // Not "dist2 <= reach^2": a NaN distance goes on, as in contactGeometry.
  const auto lanes = static_cast<unsigned>(_mm256_movemask_pd(_mm256_cmp_pd(dist2, mul(reach, reach), _CMP_NGT_UQ)));
  if (lanes == 0)
    return 0;
  const __m256d dist = _mm256_sqrt_pd(dist2);
  const __m256d penetration = sub(reach, dist);
  const Lanes3 normal{div(d.x, dist), div(d.y, dist), div(d.z, dist)};
  const Lanes3 contactPoint = add(p1, scale(sub(r1, mul(_mm256_set1_pd(0.5), penetration)), normal));

  // The shear force turned with the frame: by the change of the normal, then by the mean spin
  // about the old one.
  const Lanes3 oldNormal = load(contacts, &Contact::normal);
  const Lanes3 w1 = load(b.angVel, i1), w2 = load(b.angVel, i2);
  const Lanes3 orthonormalAxis = cross(oldNormal, normal);
  const Lanes3 twistAxis = scale(mul(_mm256_set1_pd(0.5 * dt), dot(oldNormal, add(w1, w2))), oldNormal);
  Lanes3 shear = load(contacts, &Contact::shearForce);
  shear = sub(shear, cross(shear, orthonormalAxis));
  shear = sub(shear, cross(shear, twistAxis));

  // The shear increment: the incident velocity with Yade's ratcheting factor on the
  // translation, its tangential part times dt.
  const __m256d alpha = div(reach, sub(reach, penetration));
  const Lanes3 relative = sub(add(load(b.vel, i2), Lanes3{zero, zero, zero}), load(b.vel, i1));
  const __m256d minusR2 = _mm256_xor_pd(r2, _mm256_set1_pd(-0.0));
  const Lanes3 incident
      = sub(add(scale(alpha, relative), cross(w2, scale(minusR2, normal))), cross(w1, scale(r1, normal)));
  const Lanes3 shearIncrement
      = scale(_mm256_set1_pd(dt), sub(incident, scale(dot(normal, incident), normal)));

  auto vectors = [&](Vec3 Contact::*member) {
    return std::array<double*, 4>{(c0.*member).data(), (c1.*member).data(), (c2.*member).data(), (c3.*member).data()};
  };
  auto scalars = [&](double Contact::*member) {
    return std::array<double*, 4>{&(c0.*member), &(c1.*member), &(c2.*member), &(c3.*member)};
  };
  store(shear, vectors(&Contact::shearForce).data(), lanes);
  store(normal, vectors(&Contact::normal).data(), lanes);
  store(penetration, scalars(&Contact::penetration).data(), lanes);
  store(contactPoint, vectors(&Contact::contactPoint).data(), lanes);
  store(r1, scalars(&Contact::refR1).data(), lanes);
  store(r2, scalars(&Contact::refR2).data(), lanes);
  store(shearIncrement, vectors(&Contact::shearIncrement).data(), lanes);
  for (int i = 0; i < sphereBatchWidth; ++i)
    if (lanes & (1U << i))
      contacts[i]->fresh = false;
  return lanes;
}
} // namespace talus::dem
