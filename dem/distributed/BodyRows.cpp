#include "dem/distributed/BodyRows.h"

#include <cstddef>
#include <cstring>
#include <stdexcept>
#include <string>
#include <type_traits>

namespace talus::dem::distributed
{
// The per-body arrays are Bodies' first members, up to `walls`; forEachBodyField lists 25. A new
// per-body array declared among them moves `walls` and stops the build here: list it there.
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Winvalid-offsetof"
static_assert(offsetof(Bodies, walls) == 25 * sizeof(std::vector<double>),
              "Bodies has a per-body array forEachBodyField does not list: add it there");
#pragma GCC diagnostic pop

namespace
{
/// How one element of a per-body array is copied to and from bytes: plain types as they are;
/// Eigen's vectors and quaternions (not trivially copyable types) through their coefficients.
template <class T>
struct Element
{
  static_assert(std::is_trivially_copyable_v<T>);
  static constexpr std::size_t bytes = sizeof(T);
  static void store(std::byte* out, const T& x) { std::memcpy(out, &x, bytes); }
  static void load(const std::byte* in, T& x) { std::memcpy(&x, in, bytes); }
};
template <>
struct Element<Vec3>
{
  static constexpr std::size_t bytes = 3 * sizeof(double);
  static void store(std::byte* out, const Vec3& v) { std::memcpy(out, v.data(), bytes); }
  static void load(const std::byte* in, Vec3& v) { std::memcpy(v.data(), in, bytes); }
};
template <>
struct Element<Quat>
{
  static constexpr std::size_t bytes = 4 * sizeof(double);
  static void store(std::byte* out, const Quat& q) { std::memcpy(out, q.coeffs().data(), bytes); }
  static void load(const std::byte* in, Quat& q) { std::memcpy(q.coeffs().data(), in, bytes); }
};
/// The Element of a per-body array.
template <class Field>
using ElementOf = Element<typename std::decay_t<Field>::value_type>;
} // namespace

std::size_t rowBytes()
{
  static const std::size_t bytes = [] {
    std::size_t n = Element<GlobalId>::bytes;
    const Bodies probe;
    forEachBodyField(probe, [&](const auto& field) { n += ElementOf<decltype(field)>::bytes; });
    return n;
  }();
  return bytes;
}

void packRows(const RankBodies& from, std::span<const std::int64_t> rows, std::vector<std::byte>& out)
{
  const std::size_t row = rowBytes();
  std::size_t at = out.size();
  out.resize(at + rows.size() * row);
  for (const std::int64_t r : rows)
  {
    const auto i = static_cast<std::size_t>(r);
    std::byte* p = out.data() + at;
    forEachBodyField(from.bodies, [&](const auto& field) {
      ElementOf<decltype(field)>::store(p, field[i]);
      p += ElementOf<decltype(field)>::bytes;
    });
    Element<GlobalId>::store(p, from.globalId[i]);
    at += row;
  }
}

void unpackRows(std::span<const std::byte> in, RankBodies& into)
{
  const std::size_t row = rowBytes();
  if (in.size() % row != 0)
    throw std::invalid_argument("unpackRows: " + std::to_string(in.size()) + " bytes is not a whole number of "
                                + std::to_string(row) + "-byte body rows");
  const std::size_t count = in.size() / row;
  const std::size_t first = into.size();
  forEachBodyField(into.bodies, [&](auto& field) { field.resize(first + count); });
  into.globalId.resize(first + count);
  for (std::size_t k = 0; k < count; ++k)
  {
    const std::byte* p = in.data() + k * row;
    forEachBodyField(into.bodies, [&](auto& field) {
      ElementOf<decltype(field)>::load(p, field[first + k]);
      p += ElementOf<decltype(field)>::bytes;
    });
    Element<GlobalId>::load(p, into.globalId[first + k]);
  }
}

void keepRows(RankBodies& bodies, std::span<const std::uint8_t> keep)
{
  if (keep.size() != bodies.size())
    throw std::invalid_argument("keepRows: " + std::to_string(keep.size()) + " flags for "
                                + std::to_string(bodies.size()) + " rows");
  auto compact = [&](auto& field) {
    std::size_t to = 0;
    for (std::size_t from = 0; from < keep.size(); ++from)
      if (keep[from])
        field[to++] = field[from];
    field.resize(to);
  };
  forEachBodyField(bodies.bodies, compact);
  compact(bodies.globalId);
}

std::int64_t firstUndistributable(const RankBodies& bodies)
{
  const Bodies& b = bodies.bodies;
  for (std::size_t i = 0; i < bodies.size(); ++i)
    if ((b.shape[i] != ShapeKind::Sphere && b.shape[i] != ShapeKind::Clump) || b.clumpId[i] >= 0)
      return static_cast<std::int64_t>(i);
  return -1;
}
} // namespace talus::dem::distributed
