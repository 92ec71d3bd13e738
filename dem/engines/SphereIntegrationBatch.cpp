// Four bodies in the four lanes of AVX2 vectors (dem/base/Avx2Lanes.h): each lane does
// NewtonIntegrator's sphere path with the same operations in the same order, the orientation's
// turn as `rotated` and Eigen's quaternion product (its SSE2 form) compute it.
#include "dem/engines/SphereIntegrationBatch.h"
#include "dem/base/Avx2Lanes.h"

namespace talus::dem
{
namespace
{
using namespace avx2;

/// NewtonIntegrator's Cundall damping of one acceleration component, a (1 - damping sign(a v))
/// with v the mid-step velocity estimate vel + dt/2 a.
[[TALUS_AVX2]] inline __m256d damped(__m256d accel, __m256d vel, __m256d halfDt, __m256d damping)
{
  const __m256d s = mul(accel, add(vel, mul(halfDt, accel)));
  const __m256d zero = _mm256_setzero_pd(), one = broadcast(1.0);
  const __m256d positive = _mm256_and_pd(_mm256_cmp_pd(s, zero, _CMP_GT_OQ), one);
  const __m256d negative = _mm256_and_pd(_mm256_cmp_pd(s, zero, _CMP_LT_OQ), one);
  return mul(accel, sub(one, mul(damping, sub(positive, negative))));
}
[[TALUS_AVX2]] inline Lanes3 damped(const Lanes3& accel, const Lanes3& vel, __m256d halfDt, __m256d damping)
{
  return {damped(accel.x, vel.x, halfDt, damping), damped(accel.y, vel.y, halfDt, damping),
          damped(accel.z, vel.z, halfDt, damping)};
}

/// m x for the four vectors x, as Eigen computes Matrix3d * Vector3d (SSE2): rows 0 and 1 as one
/// packet, (m0 x0 + m1 x1) + m2 x2, row 2 by its scalar reduction, m0 x0 + (m1 x1 + m2 x2).
[[TALUS_AVX2]] inline __m256d term(const Mat3& m, int row, int column, __m256d x)
{
  return mul(broadcast(m(row, column)), x);
}
[[TALUS_AVX2]] inline Lanes3 matrixTimes(const Mat3& m, const Lanes3& x)
{
  return {add(add(term(m, 0, 0, x.x), term(m, 0, 1, x.y)), term(m, 0, 2, x.z)),
          add(add(term(m, 1, 0, x.x), term(m, 1, 1, x.y)), term(m, 1, 2, x.z)),
          add(term(m, 2, 0, x.x), add(term(m, 2, 1, x.y), term(m, 2, 2, x.z)))};
}
/// v in all four lanes.
[[TALUS_AVX2]] inline Lanes3 lanesOf(const Vec3& v) { return {broadcast(v[0]), broadcast(v[1]), broadcast(v[2])}; }

/// The coefficients (x, y, z, w) of four quaternions.
struct Lanes4
{
  __m256d x, y, z, w;
};
/// The four consecutive quaternions from q (each x, y, z, w).
[[TALUS_AVX2]] inline Lanes4 loadQuaternions(const double* q)
{
  const __m256d q0 = _mm256_loadu_pd(q), q1 = _mm256_loadu_pd(q + 4), q2 = _mm256_loadu_pd(q + 8),
                q3 = _mm256_loadu_pd(q + 12);
  const __m256d xz01 = _mm256_unpacklo_pd(q0, q1), yw01 = _mm256_unpackhi_pd(q0, q1);
  const __m256d xz23 = _mm256_unpacklo_pd(q2, q3), yw23 = _mm256_unpackhi_pd(q2, q3);
  return {_mm256_permute2f128_pd(xz01, xz23, 0x20), _mm256_permute2f128_pd(yw01, yw23, 0x20),
          _mm256_permute2f128_pd(xz01, xz23, 0x31), _mm256_permute2f128_pd(yw01, yw23, 0x31)};
}
/// Lane i of v to the quaternion q + 4 i where bit i of `lanes` is set.
[[TALUS_AVX2]] inline void storeQuaternions(const Lanes4& v, double* q, unsigned lanes)
{
  const __m256d xz01 = _mm256_permute2f128_pd(v.x, v.z, 0x20), xz23 = _mm256_permute2f128_pd(v.x, v.z, 0x31);
  const __m256d yw01 = _mm256_permute2f128_pd(v.y, v.w, 0x20), yw23 = _mm256_permute2f128_pd(v.y, v.w, 0x31);
  const __m256d each[4] = {_mm256_unpacklo_pd(xz01, yw01), _mm256_unpackhi_pd(xz01, yw01),
                           _mm256_unpacklo_pd(xz23, yw23), _mm256_unpackhi_pd(xz23, yw23)};
  for (int i = 0; i < 4; ++i)
    if (lanes & (1U << i))
      _mm256_storeu_pd(q + 4 * i, each[i]);
}

/// The orientations turned by the rotation vectors w whose squared angle is in (0, 1e-6), as
/// NewtonIntegrator's `rotated`: (Quat(c, s w) * q).normalized() with c and s from their series.
/// @return the lanes whose turn is 1e-6 rad^2 or more (left alone)
[[TALUS_AVX2]] inline unsigned turn(double* q, const Lanes3& w)
{
  const __m256d angle2 = dot(w, w);
  const __m256d zero = _mm256_setzero_pd();
  const auto small = static_cast<unsigned>(_mm256_movemask_pd(_mm256_cmp_pd(angle2, broadcast(1e-6), _CMP_LT_OQ)));
  const auto still = static_cast<unsigned>(_mm256_movemask_pd(_mm256_cmp_pd(angle2, zero, _CMP_EQ_OQ)));
  const unsigned turned = small & ~still;
  const unsigned left = ~small & ~still & 15U;
  if (turned == 0)
    return left;
  const __m256d square = mul(angle2, angle2);
  const __m256d c = add(sub(broadcast(1.0), div(angle2, broadcast(8.0))), div(square, broadcast(384.0)));
  const __m256d s = add(sub(broadcast(0.5), div(angle2, broadcast(48.0))), div(square, broadcast(3840.0)));
  const __m256d ax = mul(s, w.x), ay = mul(s, w.y), az = mul(s, w.z), aw = c;
  const Lanes4 b = loadQuaternions(q);
  // Eigen's quaternion product of doubles on SSE2 (Geometry_SIMD.h), written out.
  const Lanes4 r{sub(add(mul(aw, b.x), mul(ay, b.z)), sub(mul(az, b.y), mul(ax, b.w))),
                 add(add(mul(aw, b.y), mul(ay, b.w)), sub(mul(az, b.x), mul(ax, b.z))),
                 add(sub(mul(aw, b.z), mul(ay, b.x)), add(mul(az, b.w), mul(ax, b.y))),
                 sub(sub(mul(aw, b.w), mul(ay, b.y)), add(mul(az, b.z), mul(ax, b.x)))};
  // normalized(): its squared norm adds (x^2 + z^2) and (y^2 + w^2), Eigen's pairs; a zero
  // norm leaves the coefficients.
  const __m256d norm2 = add(add(mul(r.x, r.x), mul(r.z, r.z)), add(mul(r.y, r.y), mul(r.w, r.w)));
  const auto positive = static_cast<unsigned>(_mm256_movemask_pd(_mm256_cmp_pd(norm2, zero, _CMP_GT_OQ)));
  const __m256d norm = _mm256_sqrt_pd(norm2);
  storeQuaternions({div(r.x, norm), div(r.y, norm), div(r.z, norm), div(r.w, norm)}, q, turned & positive);
  storeQuaternions(r, q, turned & ~positive);
  return left;
}
} // namespace

bool sphereIntegrationAvailable()
{
  static const bool available = __builtin_cpu_supports("avx2");
  return available;
}

[[gnu::target("avx2")]] unsigned integrateSphereBatch(Bodies& b, std::size_t first, const SphereStepParameters& p)
{
  const __m256d dt = broadcast(p.dt);
  Lanes3 a = product(load(b.force[first].data()), load(p.invMass[first].data()));
  Lanes3 alpha = product(load(b.torque[first].data()), load(p.invInertia[first].data()));
  const Lanes3 g{broadcast(p.gravity[0]), broadcast(p.gravity[1]), broadcast(p.gravity[2])};
  if (p.dampGravity)
    a = add(a, g);
  Lanes3 v = load(b.vel[first].data()), omega = load(b.angVel[first].data());
  const Lanes3 pos = load(b.pos[first].data());
  if (p.field)
  {
    // The fluctuations: the previous step's field at the previous position x - v dt taken off.
    v = sub(v, matrixTimes(p.field->previousVelGrad, sub(pos, scale(dt, v))));
    omega = sub(omega, lanesOf(p.field->previousSpin));
  }
  if (p.damping != 0)
  {
    // An undamped body's lane is multiplied by 1 - 0 sign = 1: its own bits.
    auto bodyDamping = [&](std::size_t i) { return b.damped[i] ? p.damping : 0.0; };
    const __m256d damping
        = _mm256_set_pd(bodyDamping(first + 3), bodyDamping(first + 2), bodyDamping(first + 1), bodyDamping(first));
    const __m256d halfDt = broadcast(0.5 * p.dt);
    a = damped(a, v, halfDt, damping);
    alpha = damped(alpha, omega, halfDt, damping);
  }
  if (!p.dampGravity)
    a = add(a, g);
  v = add(v, scale(dt, a));
  omega = add(omega, scale(dt, alpha));
  if (p.field)
  {
    v = add(v, matrixTimes(p.field->velGrad, pos));
    omega = add(omega, lanesOf(p.field->spin));
  }
  store(v, b.vel[first].data());
  store(omega, b.angVel[first].data());
  store(add(pos, scale(dt, v)), b.pos[first].data());
  return turn(b.ori[first].coeffs().data(), scale(dt, omega));
}
} // namespace talus::dem
