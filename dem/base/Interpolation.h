#pragma once

#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

namespace talus::dem
{
/// x wrapped into [x0, x1) by whole periods (Yade's Shop::periodicWrap, the same arithmetic).
/// @param x the value
/// @param x0, x1 the period's bounds, x0 < x1
/// @return x plus a whole number of periods x1 - x0, in [x0, x1)
inline double periodicWrap(double x, double x0, double x1)
{
  const double normalised = (x - x0) / (x1 - x0);
  return x0 + (normalised - std::floor(normalised)) * (x1 - x0);
}

/// The table (times, values) read at time t, as Yade's interpolating engines read theirs: linear
/// between readings, the first value before the first time, the last after the last time, or
/// with `wrap` the time wrapped into [first time, last time) first.
/// @param times, values the table
/// @param t the time read
/// @param wrap wrap t into the table's span (a periodic table)
/// @param owner the engine's name, for errors
/// @return the value at t
/// @throws std::invalid_argument (naming `owner`) unless the times increase and match the values
inline double interpolate(const std::vector<double>& times, const std::vector<double>& values, double t, bool wrap,
                          const std::string& owner)
{
  if (times.size() != values.size() || times.size() < 2)
    throw std::invalid_argument(owner + ": times and values must have the same length, at least 2 (got "
                                + std::to_string(times.size()) + " and " + std::to_string(values.size()) + ")");
  for (std::size_t k = 1; k < times.size(); ++k)
    if (!(times[k] > times[k - 1]))
      throw std::invalid_argument(owner + ": times must increase (times[" + std::to_string(k) + "] = "
                                  + std::to_string(times[k]) + " after " + std::to_string(times[k - 1]) + ")");
  if (wrap)
    t = periodicWrap(t, times.front(), times.back());
  if (t <= times.front())
    return values.front();
  if (t >= times.back())
    return values.back();
  std::size_t k = 0;
  while (times[k + 1] < t)
    ++k;
  return values[k] + (values[k + 1] - values[k]) * ((t - times[k]) / (times[k + 1] - times[k]));
}
} // namespace talus::dem
