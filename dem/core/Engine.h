#pragma once

#include "dem/base/Timing.h"
#include "dem/core/Stage.h"

#include <cstdint>
#include <string>

namespace talus::dem
{
class Scene;

/// One stage of a time step (Yade's Engine): the scene runs its engines in order every step.
/// Engines are called once per step, so a virtual call here costs nothing; hot loops live
/// inside `run`.
class Engine
{
public:
  Engine() = default;
  Engine(const Engine&) = delete;
  Engine& operator=(const Engine&) = delete;
  virtual ~Engine() = default;

  /// Do this engine's work for the current step.
  virtual void run(Scene& scene) = 0;
  /// Yade's class name of the engine, for messages and for Python.
  [[nodiscard]] virtual std::string typeName() const = 0;
  /// Whether an exception from run() leaves the scene as the engines before this one left it
  /// (true for a Python callback), so that the step can go on with the next engine.
  [[nodiscard]] virtual bool resumableAfterError() const { return false; }
  /// The stages of the step this engine takes part in and how each splits among threads; the
  /// step's scheduler runs the declared stages of the usual engines in shared parallel regions
  /// through their range functions. Nothing declared (the default): run() is called at the
  /// engine's place in the list, between parallel regions.
  [[nodiscard]] virtual Stages stages() const { return {}; }

  std::string label; ///< optional user label
  bool dead = false; ///< skipped when true

  // Timing (O.timingEnabled; Yade's Engine.execTime, execCount and timingDeltas).
  std::int64_t execTime = 0;  ///< nanoseconds spent in run()
  std::int64_t execCount = 0; ///< timed calls of run()
  TimingDeltas timingDeltas;  ///< stages inside run(), for engines that label them
};
} // namespace talus::dem
