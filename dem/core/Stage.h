#pragma once

#include <array>
#include <cstddef>
#include <cstdint>

namespace talus::dem
{
/// The points of a step at which the usual engines work, in the order a step passes them. An
/// engine declares what it does at each (Engine::stages); one that declares nothing runs whole,
/// as a serial stage, at its place in the engine list (a PyRunner, a coupling hook, a controller,
/// a kinematic engine, a force engine).
enum class StagePoint : std::uint8_t
{
  Reset,       ///< forces start from the persistent external ones
  SkinCheck,   ///< has any body moved far enough that the candidate pairs must be found again?
  Detection,   ///< find the candidate pairs again
  Contacts,    ///< geometry and forces of every candidate pair
  Gather,      ///< sum each body's contact forces and moments
  Integration, ///< move the bodies
};
inline constexpr std::size_t stagePoints = 6;

/// How the work of a stage splits among threads.
enum class Grain : std::uint8_t
{
  None,       ///< no work at this point
  PerBody,    ///< each thread takes a range of bodies (rows of Scene::bodies)
  PerContact, ///< each thread takes a range of the contact list
  Serial,     ///< one call between parallel regions (which may parallelise its own loops)
};

/// What an engine does at each point of the step (Grain::None where it does nothing).
struct Stages
{
  std::array<Grain, stagePoints> grain{};

  /// @param point a point of the step
  /// @return how the engine works there (Grain::None: not at all)
  [[nodiscard]] Grain at(StagePoint point) const { return grain[static_cast<std::size_t>(point)]; }
  /// @param point a point of the step
  /// @return whether the engine works there
  [[nodiscard]] bool has(StagePoint point) const { return at(point) != Grain::None; }
  /// No stage declared: the engine runs whole as a serial stage at its place in the list.
  [[nodiscard]] bool empty() const { return *this == Stages{}; }
  /// This declaration with `grain` at `point`.
  /// @param point a point of the step
  /// @param g how the engine works there (replacing what was declared)
  /// @return the new declaration (this one is unchanged), for chaining
  [[nodiscard]] Stages with(StagePoint point, Grain g) const
  {
    Stages s = *this;
    s.grain[static_cast<std::size_t>(point)] = g;
    return s;
  }
  bool operator==(const Stages&) const = default;
};
} // namespace talus::dem
