#pragma once

#include <cmath>
#include <cstddef>
#include <span>
#include <sstream>
#include <stdexcept>
#include <string>

/// Input checks shared by the flow models: each error names the model (`owner`, e.g.
/// "VansFluid"), the parameter and the offending value.
namespace talus::flow::checks
{
/// A number as the user would write it (shortest round-trip form is not needed here).
/// @param value any number
/// @return its stream form (6 significant digits)
inline std::string str(double value)
{
  std::ostringstream out;
  out << value;
  return out.str();
}

/// Refuse a parameter unless `ok`.
/// @param ok the check's outcome
/// @param owner, name the model and the parameter, for the message
/// @param what the rest of the message ("must be positive, got -1")
/// @throws std::invalid_argument "<owner>: <name> <what>" if not ok
inline void require(bool ok, const char* owner, const char* name, const std::string& what)
{
  if (!ok)
    throw std::invalid_argument(std::string(owner) + ": " + name + " " + what);
}

/// @param value the parameter's value
/// @param owner, name the model and the parameter, for the message
/// @throws std::invalid_argument unless value is finite
inline void requireFinite(double value, const char* owner, const char* name)
{
  require(std::isfinite(value), owner, name, "must be finite, got " + str(value));
}

/// A per-layer profile: the expected length, finite values, and solid fractions in [0, 1).
/// @param owner, name the model and the profile, for the message
/// @param values the profile
/// @param expected the number of values it must have
/// @param isFraction each value must also lie in [0, 1)
/// @throws std::invalid_argument naming the index of the first bad value, or the count
inline void checkProfile(const char* owner, const char* name, std::span<const double> values, std::size_t expected,
                         bool isFraction)
{
  if (values.size() != expected)
    throw std::invalid_argument(std::string(owner) + ": " + name + " has " + std::to_string(values.size())
                                + " values, expected " + std::to_string(expected));
  for (std::size_t i = 0; i < values.size(); ++i)
  {
    const double v = values[i];
    if (!std::isfinite(v))
      throw std::invalid_argument(std::string(owner) + ": " + name + "[" + std::to_string(i) + "] is not finite ("
                                  + str(v) + ")");
    if (isFraction && (v < 0.0 || v >= 1.0))
      throw std::invalid_argument(std::string(owner) + ": " + name + "[" + std::to_string(i) + "] = " + str(v)
                                  + " is not a solid fraction in [0, 1)");
  }
}
} // namespace talus::flow::checks
