#pragma once

#include <array>
#include <bit>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <span>

namespace talus::dem
{
/// The exact sum of doubles, kept as a fixed-point integer over the whole range of doubles, so
/// that its value does not depend on the order of the additions: a sum split over processes
/// (each adding its share, the shares added in any order) gives the bits of the sum made in one
/// process. What the periodic cell's controllers read (the stress, the bodies' mass) must be the
/// same bits at any process count, or the cell and with it every position drifts apart.
///
/// The integer is held in 32-bit digits stored in 64-bit words, so that 2^30 additions fit
/// before the carries are propagated; value() rounds the exact sum to a double (within one unit
/// in the last place, by a rule that depends on the exact sum only).
class ExactSum
{
public:
  /// Digits: 2^-1074 (the smallest subnormal) to beyond 2^1024, 32 bits each.
  static constexpr std::size_t digits = 68;
  /// Doubles parts() writes and fromParts() reads: the digits and the non-finite terms' sum.
  static constexpr std::size_t partCount = digits + 1;

  /// Add `x` exactly (an infinity or NaN makes the value that infinity or NaN).
  ExactSum& operator+=(double x)
  {
    const auto bits = std::bit_cast<std::uint64_t>(x);
    const auto exponent = static_cast<unsigned>((bits >> 52) & 0x7ff);
    if (exponent == 0x7ff)
    {
      special_ += x;
      return *this;
    }
    // x = mantissa * 2^(position - 1074), position >= 0 (subnormals have exponent field 0).
    const std::uint64_t mantissa = (bits & ((std::uint64_t{1} << 52) - 1)) | (exponent ? std::uint64_t{1} << 52 : 0);
    const unsigned position = exponent ? exponent - 1 : 0;
    // The 53-bit mantissa shifted into place spans three digits: bits 0-63 and 64-84.
    const unsigned shift = position & 31;
    const std::uint64_t low = mantissa << shift, high = shift ? mantissa >> (64 - shift) : 0;
    // Negated as two's complement words: (v ^ -1) + 1 = -v, (v ^ 0) + 0 = v.
    const std::uint64_t negative = -(bits >> 63);
    std::uint64_t* d = digits_.data() + (position >> 5);
    d[0] += ((low & 0xffffffffu) ^ negative) - negative;
    d[1] += ((low >> 32) ^ negative) - negative;
    d[2] += (high ^ negative) - negative;
    if (++pending_ == std::uint32_t{1} << 30)
      carry();
    return *this;
  }

  /// The exact sum rounded to a double (the same bits for the same exact sum).
  [[nodiscard]] double value() const
  {
    ExactSum s = *this;
    s.carry();
    if (s.special_ != 0 || std::isnan(s.special_))
      return s.special_;
    double sign = 1;
    if (static_cast<std::int64_t>(s.digits_[digits - 1]) < 0) // negative: round its magnitude
    {
      sign = -1;
      for (std::uint64_t& d : s.digits_)
        d = -d;
      s.carry();
    }
    double v = 0;
    for (std::size_t k = 0; k < digits; ++k) // each term exact; the smallest first
      v += std::ldexp(static_cast<double>(s.digits_[k]), static_cast<int>(32 * k) - 1074);
    return sign * v;
  }

  /// The sum as partCount doubles, each digit an integer below 2^32 in magnitude: added
  /// element-wise over up to 2^20 processes, in any order, they stay exact (below 2^53).
  /// @param out partCount doubles
  void parts(std::span<double> out) const
  {
    ExactSum s = *this;
    s.carry();
    for (std::size_t k = 0; k < digits; ++k)
      out[k] = static_cast<double>(static_cast<std::int64_t>(s.digits_[k]));
    out[digits] = s.special_;
  }

  /// The sum whose parts (summed over processes) are `in`.
  /// @param in partCount doubles, as parts() wrote them or their element-wise sums
  [[nodiscard]] static ExactSum fromParts(std::span<const double> in)
  {
    ExactSum s;
    for (std::size_t k = 0; k < digits; ++k)
      s.digits_[k] = static_cast<std::uint64_t>(static_cast<std::int64_t>(in[k]));
    s.special_ = in[digits];
    return s;
  }

private:
  /// Bring every digit but the top one into [0, 2^32), the top one keeping the sign.
  void carry()
  {
    for (std::size_t k = 0; k + 1 < digits; ++k)
    {
      // floor division of the signed digit by 2^32 (an arithmetic shift)
      const std::int64_t c = static_cast<std::int64_t>(digits_[k]) >> 32;
      digits_[k] &= 0xffffffffu;
      digits_[k + 1] += static_cast<std::uint64_t>(c);
    }
    pending_ = 0;
  }

  /// Two's complement digits, as unsigned words (wrapping arithmetic: no undefined overflow).
  std::array<std::uint64_t, digits> digits_{};
  std::uint32_t pending_ = 0; ///< additions since the carries were last propagated
  double special_ = 0;
};
} // namespace talus::dem
