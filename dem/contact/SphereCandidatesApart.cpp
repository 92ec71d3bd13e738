// Four candidates' distance test in the four lanes of AVX2 vectors (dem/base/Avx2Lanes.h).
#include "dem/contact/SphereCandidatesApart.h"
#include "dem/base/Avx2Lanes.h"

namespace talus::dem
{
[[gnu::target("avx2")]] unsigned spheresApart(const Contact* const* contacts, const Bodies& b)
{
  using namespace avx2;
  const Vec3* p1[4];
  const Vec3* p2[4];
  double r1[4], r2[4];
  for (int i = 0; i < 4; ++i)
  {
    const auto i1 = static_cast<std::size_t>(contacts[i]->id1), i2 = static_cast<std::size_t>(contacts[i]->id2);
    p1[i] = &b.pos[i1];
    p2[i] = &b.pos[i2];
    r1[i] = b.radius[i1];
    r2[i] = b.radius[i2];
  }
  // d = pos2 + shift2 - pos1 with a zero shift: adding +0 can change only a zero's sign, which
  // the squares do not see.
  const Lanes3 d = sub(load(p2[0]->data(), p2[1]->data(), p2[2]->data(), p2[3]->data()),
                       load(p1[0]->data(), p1[1]->data(), p1[2]->data(), p1[3]->data()));
  const __m256d dist2 = add(mul(d.x, d.x), add(mul(d.y, d.y), mul(d.z, d.z))); // yadeSquaredNorm's order
  const __m256d reach = add(_mm256_loadu_pd(r1), _mm256_loadu_pd(r2));
  // spheresBegin: apart where dist2 > reach^2 (ordered: a NaN is not apart).
  return static_cast<unsigned>(_mm256_movemask_pd(_mm256_cmp_pd(dist2, mul(reach, reach), _CMP_GT_OQ)));
}
} // namespace talus::dem
