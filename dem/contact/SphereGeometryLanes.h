#pragma once

// contactGeometry's sphere path for four contacts in the lanes of AVX2 vectors
// (dem/base/Avx2Lanes.h): the same operations in the same order, so the same bits. For the
// files whose AVX2 kernels start from a contact's geometry (sphereGeometryBatch, the laws'
// own lanes).
#include "dem/base/Avx2Lanes.h"
#include "dem/core/Bodies.h"
#include "dem/core/Cell.h"
#include "dem/core/Contacts.h"

#include <array>
#include <cstddef>
#include <vector>

namespace talus::dem::avx2
{
/// Where body 2's periodic image of each of four contacts is relative to body 2, and its
/// velocity: zero for a pair inside the cell, else the cell's own products (Cell::shift,
/// shiftVelocity) as contactGeometry takes them.
struct ImageShift
{
  Lanes3 offset, velocity;
};

/// What contactGeometry writes of four contacts, in lanes, and the image shifts it took.
struct SphereGeometry
{
  unsigned touching = 0; ///< bit i: contact i's spheres overlap (the other lanes' values mean nothing)
  __m256d penetration, r1, r2;
  Lanes3 normal, contactPoint, shearForce, shearIncrement;
  ImageShift image;
};

/// v[i[0]], ..., v[i[3]] as lanes 0 to 3.
[[TALUS_AVX2]] inline Lanes3 load(const std::vector<Vec3>& v, const std::size_t* i)
{
  return load(v[i[0]].data(), v[i[1]].data(), v[i[2]].data(), v[i[3]].data());
}
[[TALUS_AVX2]] inline __m256d load(const std::vector<double>& v, const std::size_t* i)
{
  return _mm256_set_pd(v[i[3]], v[i[2]], v[i[1]], v[i[0]]);
}
/// Rows i[0], ..., i[3] of a table of near images as lanes 0 to 3.
[[TALUS_AVX2]] inline Lanes3 load(const NearImageRows& t, const int* i)
{
  return load(t.row[i[0]], t.row[i[1]], t.row[i[2]], t.row[i[3]]);
}
/// The member of the four contacts (or contact states) as lanes 0 to 3.
template <class Record>
[[TALUS_AVX2]] inline Lanes3 load(Record* const* c, Vec3 Record::*member)
{
  return load((c[0]->*member).data(), (c[1]->*member).data(), (c[2]->*member).data(), (c[3]->*member).data());
}
template <class Record>
[[TALUS_AVX2]] inline __m256d load(Record* const* c, double Record::*member)
{
  return _mm256_set_pd(c[3]->*member, c[2]->*member, c[1]->*member, c[0]->*member);
}
/// Where the member of each of the four contacts is, for store().
template <class Record>
inline std::array<double*, 4> at(Record* const* c, Vec3 Record::*member)
{
  return {(c[0]->*member).data(), (c[1]->*member).data(), (c[2]->*member).data(), (c[3]->*member).data()};
}
template <class Record>
inline std::array<double*, 4> at(Record* const* c, double Record::*member)
{
  return {&(c[0]->*member), &(c[1]->*member), &(c[2]->*member), &(c[3]->*member)};
}

/// The rows (nearImage) of the four contacts' images in a table of near images, made in the
/// lanes of integer vectors: the cell offsets of the four records turned to one vector per edge.
/// @return false if one lies more than a cell away (row not set)
[[TALUS_AVX2]] inline bool nearImageRows(Contact* const* contacts, int* row)
{
  // A whole vector's load per record: its cell offset and the four bytes after it (lane 3, unused).
  static_assert(offsetof(Contact, cellDist) + 4 * sizeof(int) <= sizeof(Contact));
  auto offsets = [&](int i) { return _mm_loadu_si128(reinterpret_cast<const __m128i*>(contacts[i]->cellDist.data())); };
  const __m128i c0 = offsets(0), c1 = offsets(1), c2 = offsets(2), c3 = offsets(3);
  const __m128i xy01 = _mm_unpacklo_epi32(c0, c1), xy23 = _mm_unpacklo_epi32(c2, c3); // x0 x1 y0 y1, x2 x3 y2 y3
  const __m128i z01 = _mm_unpackhi_epi32(c0, c1), z23 = _mm_unpackhi_epi32(c2, c3);   // z0 z1 - -, z2 z3 - -
  const __m128i x = _mm_unpacklo_epi64(xy01, xy23), y = _mm_unpackhi_epi64(xy01, xy23), z = _mm_unpacklo_epi64(z01, z23);
  // |x|, |y| and |z| at most 1: their bits OR-ed have none but the lowest (|INT_MIN| keeps its sign bit).
  const __m128i magnitudes = _mm_or_si128(_mm_or_si128(_mm_abs_epi32(x), _mm_abs_epi32(y)), _mm_abs_epi32(z));
  if (!_mm_testz_si128(magnitudes, _mm_set1_epi32(~1)))
    return false;
  // 9 (x + 1) + 3 (y + 1) + (z + 1)
  const __m128i nine = _mm_add_epi32(_mm_slli_epi32(x, 3), x), three = _mm_add_epi32(_mm_slli_epi32(y, 1), y);
  _mm_store_si128(reinterpret_cast<__m128i*>(row),
                  _mm_add_epi32(_mm_add_epi32(nine, three), _mm_add_epi32(z, _mm_set1_epi32(13))));
  return true;
}

/// The image shifts of four contacts (ImageShift).
/// @param cell the periodic cell, or null
/// @param images its near images (CellImages), or null: then each lane across the boundary
///        computes its own
[[TALUS_AVX2]] inline ImageShift imageShift(Contact* const* contacts, const Cell* cell, const CellImages* images)
{
  const __m256d zero = _mm256_setzero_pd();
  ImageShift s{{zero, zero, zero}, {zero, zero, zero}};
  if (cell == nullptr)
    return s;
  if (images != nullptr)
  {
    // Each lane's row, the pairs inside the cell included (their row is +0): no branch per lane
    // (which a lane across the boundary, one in five in a small cell, mispredicts).
    alignas(16) int row[4];
    if (nearImageRows(contacts, row)) [[likely]]
      return {load(images->shift, row), load(images->velocity, row)};
  }
  alignas(32) double offset[3][4] = {}, velocity[3][4] = {};
  bool across = false;
  for (int i = 0; i < 4; ++i)
    if (contacts[i]->cellDist != Eigen::Vector3i::Zero())
    {
      const Vec3 o = cell->shift(contacts[i]->cellDist), v = cell->shiftVelocity(contacts[i]->cellDist);
      for (int d = 0; d < 3; ++d)
      {
        offset[d][i] = o[d];
        velocity[d][i] = v[d];
      }
      across = true;
    }
  if (across)
    s = {{_mm256_load_pd(offset[0]), _mm256_load_pd(offset[1]), _mm256_load_pd(offset[2])},
         {_mm256_load_pd(velocity[0]), _mm256_load_pd(velocity[1]), _mm256_load_pd(velocity[2])}};
  return s;
}

/// The four contacts' shear forces turned with their frames (ScGeom's rotate): by the change
/// from the old normal to the new one, then by the mean spin of the two bodies about the old one.
/// @param w1, w2 the bodies' angular velocities
/// @param dt the time step (s)
[[TALUS_AVX2]] inline Lanes3 turnedShearForce(Contact* const* contacts, const Lanes3& oldNormal, const Lanes3& normal,
                                             const Lanes3& w1, const Lanes3& w2, double dt)
{
  const Lanes3 orthonormalAxis = cross(oldNormal, normal);
  const Lanes3 twistAxis = scale(mul(broadcast(0.5 * dt), dot(oldNormal, add(w1, w2))), oldNormal);
  Lanes3 shear = load(contacts, &Contact::shearForce);
  shear = sub(shear, cross(shear, orthonormalAxis));
  return sub(shear, cross(shear, twistAxis));
}

/// contactGeometry<true> of four contacts that were real at the last step, between two
/// spheres (in a periodic cell, inside it or across its boundary); nothing written.
/// @param dt the time step (s)
/// @param cell the periodic cell, or null
/// @param images the cell's near images, or null (imageShift)
[[TALUS_AVX2]] inline SphereGeometry sphereGeometry(Contact* const* contacts, const Bodies& b, double dt, const Cell* cell,
                                                   const CellImages* images)
{
  std::size_t i1[4], i2[4];
  for (int i = 0; i < 4; ++i)
  {
    i1[i] = static_cast<std::size_t>(contacts[i]->id1);
    i2[i] = static_cast<std::size_t>(contacts[i]->id2);
  }
  SphereGeometry g;
  // The overlap: d = (pos2 + shift2) - pos1.
  const ImageShift shift = imageShift(contacts, cell, images);
  g.image = shift;
  const Lanes3 p1 = load(b.pos, i1);
  const __m256d zero = _mm256_setzero_pd();
  const Lanes3 d = sub(add(load(b.pos, i2), shift.offset), p1);
  g.r1 = load(b.radius, i1);
  g.r2 = load(b.radius, i2);
  // Real contacts: they hold on while the penetration is not negative (spheresHold: a NaN goes
  // on), |d|^2 summed in Yade's order (yadeSquaredNorm).
  const __m256d dist2 = add(mul(d.x, d.x), add(mul(d.y, d.y), mul(d.z, d.z)));
  const __m256d reach = add(g.r1, g.r2);
  const __m256d dist = _mm256_sqrt_pd(dist2);
  g.penetration = sub(reach, dist);
  g.touching = static_cast<unsigned>(_mm256_movemask_pd(_mm256_cmp_pd(g.penetration, zero, _CMP_NLT_UQ)));
  if (g.touching == 0)
    return g;
  g.normal = {div(d.x, dist), div(d.y, dist), div(d.z, dist)};
  g.contactPoint = add(p1, scale(sub(g.r1, mul(broadcast(0.5), g.penetration)), g.normal));

  // The shear force turned with the frame: by the change of the normal, then by the mean spin
  // about the old one.
  const Lanes3 oldNormal = load(contacts, &Contact::normal);
  const Lanes3 w1 = load(b.angVel, i1), w2 = load(b.angVel, i2);
  g.shearForce = turnedShearForce(contacts, oldNormal, g.normal, w1, w2, dt);

  // The shear increment: the incident velocity with Yade's ratcheting factor on the
  // translation, its tangential part times dt.
  const __m256d alpha = div(reach, sub(reach, g.penetration));
  const Lanes3 relative = sub(add(load(b.vel, i2), shift.velocity), load(b.vel, i1));
  const __m256d minusR2 = _mm256_xor_pd(g.r2, broadcast(-0.0));
  const Lanes3 incident
      = sub(add(scale(alpha, relative), cross(w2, scale(minusR2, g.normal))), cross(w1, scale(g.r1, g.normal)));
  g.shearIncrement = scale(broadcast(dt), sub(incident, scale(dot(g.normal, incident), g.normal)));
  return g;
}

/// Write g's lanes `lanes` to their contacts, as contactGeometry does (no longer fresh).
[[TALUS_AVX2]] inline void store(const SphereGeometry& g, Contact* const* contacts, unsigned lanes)
{
  store(g.shearForce, at(contacts, &Contact::shearForce).data(), lanes);
  store(g.normal, at(contacts, &Contact::normal).data(), lanes);
  store(g.penetration, at(contacts, &Contact::penetration).data(), lanes);
  store(g.contactPoint, at(contacts, &Contact::contactPoint).data(), lanes);
  store(g.r1, at(contacts, &Contact::refR1).data(), lanes);
  store(g.r2, at(contacts, &Contact::refR2).data(), lanes);
  store(g.shearIncrement, at(contacts, &Contact::shearIncrement).data(), lanes);
  for (int i = 0; i < 4; ++i)
    if (lanes & (1U << i))
      contacts[i]->fresh = false;
}
} // namespace talus::dem::avx2
