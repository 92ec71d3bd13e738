#pragma once

#include <span>
#include <string_view>

/// Build-time facts about this Talus library: version, components and optional features.
namespace talus
{
/// One row of the configure-step summary.
struct BuildEntry
{
  const char* kind;    ///< "component" (dem, flow, ...) or "feature" (openmp, hdf5, ...)
  const char* name;    ///< component or feature name
  bool enabled;        ///< built into this library
  const char* note;    ///< what was found, or why it is off
};

/// @return the Talus version, "major.minor.patch"
std::string_view version();

/// @return every component and feature decided at configure time, components first
std::span<const BuildEntry> build_config();
} // namespace talus
