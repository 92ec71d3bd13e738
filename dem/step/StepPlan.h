#pragma once

#include "dem/core/Engine.h"

#include <cstddef>
#include <cstdint>
#include <limits>
#include <memory>
#include <string>
#include <vector>

namespace talus::dem
{
/// The order in which a step runs a list of engines, made from what each engine declares
/// (Engine::stages). The usual engines — one declaring the reset, later one declaring the skin
/// check and detection, the next the contacts and the gather, and later one declaring the
/// integration — form the shared stages, run in parallel regions that each thread enters with
/// one range of bodies for the reset, the skin check, the gather and the integration. Every
/// other engine (and any engine when the list has no such group) is a serial stage: its run()
/// is called at its place, between the regions: before the reset, between the reset and the
/// skin check (a coupling adding its forces), between the gather and the integration (force
/// engines, couplings reading the forces), or after the integration.
struct StepPlan
{
  static constexpr std::size_t none = std::numeric_limits<std::size_t>::max();

  enum class Item : std::uint8_t
  {
    Serial,      ///< engine `engine` runs whole
    Reset,       ///< the reset, in a region of its own (serial stages follow it)
    Forces,      ///< reset (unless a Reset entry came before), skin check (and detection),
                 ///< contacts, gather; and the integration when no serial stage comes
                 ///< between
    Integration, ///< the integration, in a region of its own
  };
  struct Entry
  {
    Item item;
    std::size_t engine; ///< the serial engine's index in the list (none for the shared items)
  };
  std::vector<Entry> entries;

  /// The engines of the shared stages (indices in the list; none without the group).
  std::size_t resetter = none, collider = none, loop = none, newton = none;
  /// The loop's contacts are split among the threads of a region (one law, no callbacks);
  /// otherwise they are one serial call between two regions.
  bool contactsInRegion = false;
  /// No serial stage at all: the skin check of the next step can be made as each thread
  /// finishes integrating its bodies (in an open scene without clumps: see SharedRegions).
  bool alone = false;

  /// What a step of an open, serial scene without clumps costs when it does not re-detect:
  /// parallel regions entered, barriers inside them, serial stages.
  int regions = 0, barriers = 0, serialStages = 0;

  /// The list has the shared group (a resetter, collider, loop and integrator in that order).
  [[nodiscard]] bool shared() const { return newton != none; }
  /// The integration has a region of its own (an Integration entry).
  [[nodiscard]] bool separateIntegration() const { return has(Item::Integration); }
  /// So has the reset (a Reset entry).
  [[nodiscard]] bool separateReset() const { return has(Item::Reset); }
  /// @param item the kind of entry looked for
  /// @return whether some entry is an `item`
  [[nodiscard]] bool has(Item item) const;
  /// One line per entry, for tests and diagnostics ("serial 0", "forces+integration", ...).
  [[nodiscard]] std::string describe() const;
};

/// What the plan of a step depends on besides the engines.
struct PlanConditions
{
  bool distributed = false; ///< Scene::domain set: the skin check is reduced over processes between regions
  bool operator==(const PlanConditions&) const = default;
};

/// The plan for the live engines of `engines` from index `from` on.
/// @param engines the scene's engine list (dead engines are left out of the plan)
/// @param from the first index planned (a step resumed after a sub-step starts later)
/// @param conditions distribution, which moves the skin check out of the forces' region
/// @return the plan; without the shared group every engine is a serial entry
StepPlan planStep(const std::vector<std::shared_ptr<Engine>>& engines, std::size_t from, PlanConditions conditions);
} // namespace talus::dem
