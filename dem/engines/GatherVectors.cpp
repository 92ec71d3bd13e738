// A body's x, y and z in lanes 0 to 2 of an AVX2 vector (lane 3 held at zero): the scalar
// gather's (InteractionLoop.cpp, gatherRange) additions, products and differences are made
// lane by lane in the same order, and its cross product as Eigen's (a1 b2 - a2 b1, a2 b0 - a0 b2,
// a0 b1 - a1 b0) from the vectors' rotations. Where the time went before: docs/dem.md, Speed.
#include "dem/engines/GatherVectors.h"
#include "dem/core/Cell.h"

#include <immintrin.h>

#include <cstddef>

#include <optional>

namespace talus::dem
{
bool gatherVectorsAvailable()
{
  static const bool available = __builtin_cpu_supports("avx2");
  return available;
}

namespace
{
#define TALUS_GATHER_AVX2 gnu::target("avx2"), gnu::always_inline

/// The triple at p in lanes 0 to 2, lane 3 zero: two loads, so that no byte past the triple is
/// read (a contact point's triple ends its record's first cache line).
[[TALUS_GATHER_AVX2]] inline __m256d triple(const double* p)
{
  return _mm256_insertf128_pd(_mm256_castpd128_pd256(_mm_loadu_pd(p)), _mm_load_sd(p + 2), 1);
}
/// Lanes 0 to 2 of v to the triple at p.
[[TALUS_GATHER_AVX2]] inline void store(__m256d v, double* p)
{
  _mm_storeu_pd(p, _mm256_castpd256_pd128(v));
  _mm_store_sd(p + 2, _mm256_extractf128_pd(v, 1));
}
/// Eigen's a.cross(b), lane 3 zero when theirs are.
[[TALUS_GATHER_AVX2]] inline __m256d cross(__m256d a, __m256d b)
{
  constexpr int yzx = 0b11001001, zxy = 0b11010010; // lanes (1, 2, 0, 3) and (2, 0, 1, 3)
  return _mm256_sub_pd(_mm256_mul_pd(_mm256_permute4x64_pd(a, yzx), _mm256_permute4x64_pd(b, zxy)),
                       _mm256_mul_pd(_mm256_permute4x64_pd(a, zxy), _mm256_permute4x64_pd(b, yzx)));
}

/// The cell's shifts (Cell::shift) of the images one cell away or less each way, nearly every
/// pair across the boundary, made at the first such pair of a gather: loaded whole, where a
/// shift computed for each contact would be loaded from the scalar stores that wrote it.
class Images
{
public:
  explicit Images(const Cell& cell) : cell_(cell) {}
  /// Cell::shift(d) in lanes 0 to 2.
  [[TALUS_GATHER_AVX2]] __m256d shift(const Eigen::Vector3i& d)
  {
    const int row = nearImage(d);
    if (row < 0) [[unlikely]]
    {
      const Vec3 s = cell_.shift(d);
      return _mm256_setr_pd(s[0], s[1], s[2], 0);
    }
    if (!made_) [[unlikely]]
    {
      fillNearImages(near_, [this](const Eigen::Vector3i& image) { return cell_.shift(image); });
      made_ = true;
    }
    return _mm256_load_pd(near_.row[row]);
  }

private:
  const Cell& cell_;
  bool made_ = false;
  NearImageRows near_;
};

/// gatherVectors in or outside a periodic cell: outside, the loop over a body's contacts has no
/// test of the cell (GCC keeps the test of the pointer in the loop: three instructions of some
/// forty a contact).
template <bool Periodic>
[[gnu::target("avx2")]] void gatherIn(const Contacts& contacts, Bodies& b, const Cell* cell, std::int64_t first,
                                      std::int64_t last, bool reset)
{
  const Contact* list = contacts.list.data();
  const std::int64_t* entries = contacts.entries.data();
  const auto entryCount = static_cast<std::int64_t>(contacts.entries.size());
  constexpr std::int64_t prefetchDistance = 16; // as the scalar gather's
  // The force's triple is followed in its record by the contact point: a whole vector's load,
  // its lane 3 cleared.
  static_assert(offsetof(Contact, contactPoint) == offsetof(Contact, force) + 3 * sizeof(double));
  const __m256d xyz = _mm256_castsi256_pd(_mm256_setr_epi64x(-1, -1, -1, 0));
  static constexpr double signs[2] = {-1.0, 1.0}; // the scalar gather's 2 side - 1
  static constexpr double sides[2] = {0.0, 1.0};  // its side as a double
  std::optional<Images> images;
  if constexpr (Periodic)
    images.emplace(*cell);
  for (std::int64_t id = first; id < last; ++id)
  {
    const auto i = static_cast<std::size_t>(id);
    const __m256d pos = triple(b.pos[i].data());
    __m256d f = _mm256_setzero_pd(), t = _mm256_setzero_pd();
    for (std::int64_t e = contacts.start[i]; e < contacts.start[i + 1]; ++e)
    {
      const std::int64_t entry = entries[e];
      const Contact& c = list[entry >> 1];
      if (e + prefetchDistance < entryCount)
        __builtin_prefetch(list + (entries[e + prefetchDistance] >> 1));
      const std::int64_t second = entry & 1;
      const __m256d force = _mm256_mul_pd(_mm256_broadcast_sd(signs + second),
                                          _mm256_and_pd(_mm256_loadu_pd(c.force.data()), xyz));
      f = _mm256_add_pd(f, force);
      const __m256d point = triple(c.contactPoint.data());
      __m256d lever;
      // As the scalar gather: only pairs across the boundary take the image's shift.
      if (Periodic && c.cellDist != Eigen::Vector3i::Zero())
        lever = _mm256_sub_pd(
            point, _mm256_add_pd(pos, _mm256_mul_pd(_mm256_broadcast_sd(sides + second), images->shift(c.cellDist))));
      else
        lever = _mm256_sub_pd(point, pos);
      t = _mm256_add_pd(t, cross(lever, force));
    }
    store(_mm256_add_pd(triple((reset ? b.extForce : b.force)[i].data()), f), b.force[i].data());
    store(_mm256_add_pd(triple((reset ? b.extTorque : b.torque)[i].data()), t), b.torque[i].data());
  }
}
} // namespace

[[gnu::target("avx2")]] void gatherVectors(const Contacts& contacts, Bodies& b, const Cell* cell, std::int64_t first,
                                           std::int64_t last, bool reset)
{
  if (cell != nullptr)
    gatherIn<true>(contacts, b, cell, first, last, reset);
  else
    gatherIn<false>(contacts, b, cell, first, last, reset);
}

} // namespace talus::dem
