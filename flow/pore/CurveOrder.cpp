#include "flow/pore/CurveOrder.h"

#include <algorithm>
#include <bit>
#include <limits>

namespace talus::flow::pore
{
namespace
{
/// The lowest 21 bits of x spread to every third bit.
std::uint64_t spread(std::uint64_t x)
{
  x &= 0x1fffff;
  x = (x | x << 32) & 0x1f00000000ffffULL;
  x = (x | x << 16) & 0x1f0000ff0000ffULL;
  x = (x | x << 8) & 0x100f00f00f00f00fULL;
  x = (x | x << 4) & 0x10c30c30c30c30c3ULL;
  return (x | x << 2) & 0x1249249249249249ULL;
}
} // namespace

std::uint64_t mortonKey(const Vec3& x, const Vec3& lo, const Vec3& hi, int bits)
{
  if (!x.allFinite())
    return 0;
  const double cells = static_cast<double>((std::uint64_t{1} << bits) - 1);
  const Eigen::Array3d unit = ((x - lo).array() / (hi - lo).array().max(std::numeric_limits<double>::min()))
                                  .max(0.0)
                                  .min(1.0);
  std::uint64_t key = 0;
  for (int a = 0; a < 3; ++a)
    key |= spread(static_cast<std::uint64_t>(unit[a] * cells)) << a;
  return key;
}

std::vector<int> poresAlongCurve(const PoreNetwork& net)
{
  const std::size_t n = net.pores.size();
  Vec3 lo = Vec3::Constant(std::numeric_limits<double>::max());
  Vec3 hi = -lo;
  for (const Vertex& v : net.vertices)
    if (!v.fictitious)
    {
      lo = lo.cwiseMin(v.pos);
      hi = hi.cwiseMax(v.pos);
    }
  // key and index in one integer (the index in the low bits breaks ties): one sort of plain
  // integers, cheaper than sorting (key, index) pairs; the key keeps what the index
  // leaves, 21 bits an axis at most (13 for 6 million pores: 8 000 cells along each axis)
  const int indexBits = std::max(1, static_cast<int>(std::bit_width(n)));
  const int bits = std::min(21, (64 - indexBits) / 3);
  std::vector<std::uint64_t> keyed(n);
  for (std::size_t i = 0; i < n; ++i)
    keyed[i] = (mortonKey(net.pores[i].centre, lo, hi, bits) << indexBits) | i;
  std::sort(keyed.begin(), keyed.end());
  std::vector<int> order(n);
  const std::uint64_t mask = (std::uint64_t{1} << indexBits) - 1;
  for (std::size_t i = 0; i < n; ++i)
    order[i] = static_cast<int>(keyed[i] & mask);
  return order;
}
} // namespace talus::flow::pore
