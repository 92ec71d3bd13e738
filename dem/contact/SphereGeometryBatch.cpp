// Four contacts in the four lanes of AVX2 vectors (dem/base/Avx2Lanes.h): each lane does
// contactGeometry's sphere path with the same operations in the same order.
#include "dem/contact/SphereGeometryBatch.h"
#include "dem/base/Avx2Lanes.h"

#include <array>
#include <vector>

namespace talus::dem
{
namespace
{
using namespace avx2;

/// v[i[0]], ..., v[i[3]] as lanes 0 to 3.
[[TALUS_AVX2]] inline Lanes3 load(const std::vector<Vec3>& v, const std::size_t* i)
{
  return avx2::load(v[i[0]].data(), v[i[1]].data(), v[i[2]].data(), v[i[3]].data());
}
[[TALUS_AVX2]] inline __m256d load(const std::vector<double>& v, const std::size_t* i)
{
  return _mm256_set_pd(v[i[3]], v[i[2]], v[i[1]], v[i[0]]);
}
/// The member of the four contacts as lanes 0 to 3.
[[TALUS_AVX2]] inline Lanes3 load(Contact* const* c, Vec3 Contact::*member)
{
  return avx2::load((c[0]->*member).data(), (c[1]->*member).data(), (c[2]->*member).data(), (c[3]->*member).data());
}
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
  const Lanes3 contactPoint = add(p1, scale(sub(r1, mul(broadcast(0.5), penetration)), normal));

  // The shear force turned with the frame: by the change of the normal, then by the mean spin
  // about the old one.
  const Lanes3 oldNormal = load(contacts, &Contact::normal);
  const Lanes3 w1 = load(b.angVel, i1), w2 = load(b.angVel, i2);
  const Lanes3 orthonormalAxis = cross(oldNormal, normal);
  const Lanes3 twistAxis = scale(mul(broadcast(0.5 * dt), dot(oldNormal, add(w1, w2))), oldNormal);
  Lanes3 shear = load(contacts, &Contact::shearForce);
  shear = sub(shear, cross(shear, orthonormalAxis));
  shear = sub(shear, cross(shear, twistAxis));

  // The shear increment: the incident velocity with Yade's ratcheting factor on the
  // translation, its tangential part times dt.
  const __m256d alpha = div(reach, sub(reach, penetration));
  const Lanes3 relative = sub(add(load(b.vel, i2), Lanes3{zero, zero, zero}), load(b.vel, i1));
  const __m256d minusR2 = _mm256_xor_pd(r2, broadcast(-0.0));
  const Lanes3 incident
      = sub(add(scale(alpha, relative), cross(w2, scale(minusR2, normal))), cross(w1, scale(r1, normal)));
  const Lanes3 shearIncrement
      = scale(broadcast(dt), sub(incident, scale(dot(normal, incident), normal)));

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
