// The bodies' heat in a checkpoint (internal, not installed): temperature, Cp, k and alpha
// (Yade's ThermalState), one dataset each under /bodies, written only when a body has a value,
// so that a scene without heat writes none; a file without one (written before the bodies had
// heat, or by a scene without any) reads NaN for every body.
#pragma once

#include "dem/checkpoint/Hdf5.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <string>
#include <utility>
#include <vector>

namespace talus::dem::checkpoint
{
inline constexpr std::pair<const char*, std::vector<double> Bodies::*> bodyHeat[] = {
    {"temperature", &Bodies::temperature}, {"heatCapacity", &Bodies::heatCapacity},
    {"conductivity", &Bodies::conductivity}, {"thermalExpansion", &Bodies::thermalExpansion}};

/// Whether a body has a value of each heat field.
/// @param b the bodies
/// @return one flag per entry of bodyHeat
inline std::array<bool, std::size(bodyHeat)> bodyHeatHeld(const Bodies& b)
{
  std::array<bool, std::size(bodyHeat)> held{};
  for (std::size_t k = 0; k < held.size(); ++k)
  {
    const std::vector<double>& values = b.*bodyHeat[k].second;
    held[k] = std::any_of(values.begin(), values.end(), [](double x) { return !std::isnan(x); });
  }
  return held;
}

/// Write each heat field that a body has a value of.
/// @param w the writer (of this process's rows when several processes write the file)
/// @param b the bodies
/// @param written the fields written (null: those a body of `b` has a value of): processes
///        writing one file together must all write the same datasets, whatever their own
///        bodies hold
inline void writeBodyHeat(const Writer& w, const Bodies& b, const std::array<bool, std::size(bodyHeat)>* written)
{
  const std::array<bool, std::size(bodyHeat)> held = written ? *written : bodyHeatHeld(b);
  for (std::size_t k = 0; k < held.size(); ++k)
    if (held[k])
      w.doubles(std::string("/bodies/") + bodyHeat[k].first, {b.size()}, (b.*bodyHeat[k].second).data());
}

/// Read the heat fields of `n` bodies, NaN for a field the file lacks.
/// @param r the reader
/// @param b the bodies read, given their heat
/// @param n the number of bodies
inline void readBodyHeat(const Reader& r, Bodies& b, std::size_t n)
{
  for (const auto& [name, field] : bodyHeat)
  {
    (b.*field).assign(n, std::numeric_limits<double>::quiet_NaN());
    if (r.exists(std::string("/bodies/") + name))
      r.doubles(std::string("/bodies/") + name, {n}, (b.*field).data());
  }
}
} // namespace talus::dem::checkpoint
