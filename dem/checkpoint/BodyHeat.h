// The bodies' heat in a checkpoint (internal, not installed): temperature, Cp, k and alpha
// (Yade's ThermalState), one dataset each under /bodies, written only when a body has a value,
// so that a scene without heat writes none; a file without one (written before the bodies had
// heat, or by a scene without any) reads NaN for every body.
#pragma once

#include "dem/checkpoint/Hdf5.h"

#include <algorithm>
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

/// Write each heat field that a body has a value of.
/// @param w the writer (of this process's rows when several processes write the file)
/// @param b the bodies
/// @param always write every field, values or not: processes writing one file together must
///        all write the same datasets, whatever their own bodies hold
inline void writeBodyHeat(const Writer& w, const Bodies& b, bool always)
{
  for (const auto& [name, field] : bodyHeat)
    if (always || std::any_of((b.*field).begin(), (b.*field).end(), [](double x) { return !std::isnan(x); }))
      w.doubles(std::string("/bodies/") + name, {b.size()}, (b.*field).data());
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
