#pragma once

// What the laws' AVX2 lanes (dem/contact/SphereGeometryLanes.h) write of four sphere contacts,
// and which of them the contact loop must still check for too deep an overlap.
#include "dem/contact/SphereGeometryLanes.h"

#include <cstddef>

namespace talus::dem::avx2
{
/// The lanes among `lanes` whose overlap passes `ratio` of the smaller reference radius: the
/// first tests of overlapsTooMuch (ratio > 0, penetration > ratio min(r1, r2)), in its operations.
[[TALUS_AVX2]] inline unsigned deepLanes(const SphereGeometry& g, double ratio, unsigned lanes)
{
  if (!(ratio > 0))
    return 0;
  // std::min(r1, r2) is r2 < r1 ? r2 : r1, as MINPD of (r2, r1).
  const __m256d limit = mul(broadcast(ratio), _mm256_min_pd(g.r2, g.r1));
  return lanes & static_cast<unsigned>(_mm256_movemask_pd(_mm256_cmp_pd(g.penetration, limit, _CMP_GT_OQ)));
}

/// The two doubles `offset` bytes into contact i's record as lane i of a and of b (storePairs'
/// reverse): a load per record.
[[TALUS_AVX2]] inline void loadPairs(Contact* const* contacts, std::size_t offset, __m256d& a, __m256d& b)
{
  auto at = [&](int i) { return reinterpret_cast<const double*>(reinterpret_cast<const char*>(contacts[i]) + offset); };
  const __m256d low = _mm256_insertf128_pd(_mm256_castpd128_pd256(_mm_loadu_pd(at(0))), _mm_loadu_pd(at(2)), 1);
  const __m256d high = _mm256_insertf128_pd(_mm256_castpd128_pd256(_mm_loadu_pd(at(1))), _mm_loadu_pd(at(3)), 1);
  a = _mm256_unpacklo_pd(low, high);
  b = _mm256_unpackhi_pd(low, high);
}
/// Lane i of a and of b to the two doubles `offset` bytes into contact i's record (a first).
[[TALUS_AVX2]] inline void storePairs(__m256d a, __m256d b, Contact* const* contacts, std::size_t offset)
{
  const __m256d low = _mm256_unpacklo_pd(a, b), high = _mm256_unpackhi_pd(a, b); // lanes 0 and 2, 1 and 3
  auto at = [&](int i) { return reinterpret_cast<double*>(reinterpret_cast<char*>(contacts[i]) + offset); };
  _mm_storeu_pd(at(0), _mm256_castpd256_pd128(low));
  _mm_storeu_pd(at(1), _mm256_castpd256_pd128(high));
  _mm_storeu_pd(at(2), _mm256_extractf128_pd(low, 1));
  _mm_storeu_pd(at(3), _mm256_extractf128_pd(high, 1));
}
/// Lane i of a to the double `offset` bytes into contact i's record.
[[TALUS_AVX2]] inline void storeLanes(__m256d a, Contact* const* contacts, std::size_t offset)
{
  const __m128d low = _mm256_castpd256_pd128(a), high = _mm256_extractf128_pd(a, 1);
  auto at = [&](int i) { return reinterpret_cast<double*>(reinterpret_cast<char*>(contacts[i]) + offset); };
  _mm_store_sd(at(0), low);
  _mm_storeh_pd(at(1), low);
  _mm_store_sd(at(2), high);
  _mm_storeh_pd(at(3), high);
}

/// What a law's lanes write of four contacts, where bit i of `lanes` is set: the geometry g (as
/// store()), the normal force and the force. With all four lanes set (nearly always), the
/// neighbouring members of a record go two doubles a store, far fewer instructions than a store
/// per lane and member (measured in docs/dem.md, Speed).
[[TALUS_AVX2]] inline void storeForces(const SphereGeometry& g, const Lanes3& normalForce, const Lanes3& force,
                                       Contact* const* contacts, unsigned lanes)
{
  if (lanes != 15U)
  {
    store(g, contacts, lanes);
    store(normalForce, at(contacts, &Contact::normalForce).data(), lanes);
    store(force, at(contacts, &Contact::force).data(), lanes);
    return;
  }
  // The members from the force to the shear increment lie one after the other, as do the normal
  // force and the shear force.
  static_assert(offsetof(Contact, contactPoint) == offsetof(Contact, force) + 24
                && offsetof(Contact, normal) == offsetof(Contact, contactPoint) + 24
                && offsetof(Contact, penetration) == offsetof(Contact, normal) + 24
                && offsetof(Contact, refR1) == offsetof(Contact, penetration) + 8
                && offsetof(Contact, refR2) == offsetof(Contact, refR1) + 8
                && offsetof(Contact, shearIncrement) == offsetof(Contact, refR2) + 8
                && offsetof(Contact, shearForce) == offsetof(Contact, normalForce) + 24
                && offsetof(Contact, force) % 16 == 0 && offsetof(Contact, normalForce) % 16 == 0,
                "storeForces writes the record's members in pairs");
  constexpr std::size_t f = offsetof(Contact, force), n = offsetof(Contact, normalForce);
  // The records' addresses in a local array, which the stores cannot alias: read from `contacts`,
  // they would be loaded again after each store.
  Contact* const record[4] = {contacts[0], contacts[1], contacts[2], contacts[3]};
  storePairs(force.x, force.y, record, f);
  storePairs(force.z, g.contactPoint.x, record, f + 16);
  storePairs(g.contactPoint.y, g.contactPoint.z, record, f + 32);
  storePairs(g.normal.x, g.normal.y, record, f + 48);
  storePairs(g.normal.z, g.penetration, record, f + 64);
  storePairs(g.r1, g.r2, record, f + 80);
  storePairs(g.shearIncrement.x, g.shearIncrement.y, record, f + 96);
  storeLanes(g.shearIncrement.z, record, f + 112);
  storePairs(normalForce.x, normalForce.y, record, n);
  storePairs(normalForce.z, g.shearForce.x, record, n + 16);
  storePairs(g.shearForce.y, g.shearForce.z, record, n + 32);
  for (Contact* c : record)
    c->fresh = false;
}
} // namespace talus::dem::avx2
