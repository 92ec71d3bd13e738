#pragma once

#include "dem/core/Engine.h"

#include <chrono>
#include <cstdint>
#include <functional>

namespace talus::dem
{
/// Calls a function every `iterPeriod` steps (Yade's PyRunner when the function is Python; a
/// coupling's step hook when it is C++). As Yade's PeriodicEngine: called when `iterPeriod`
/// steps, `virtPeriod` seconds of simulated time or `realPeriod` seconds of wall time have
/// passed since the last call (whichever is set and comes first), and at the first step with
/// `initRun`; at most `nDo` times.
class CallbackEngine : public Engine
{
public:
  /// Call the callback if a period has passed (or at the first step with initRun).
  /// @throws std::invalid_argument if no period is set (all three 0) or one is negative
  void run(Scene& scene) override;
  [[nodiscard]] std::string typeName() const override { return "PyRunner"; }
  [[nodiscard]] bool resumableAfterError() const override { return resumable; }

  std::function<void()> callback;
  std::int64_t iterPeriod = 1; ///< steps between calls (0: not by steps)
  double realPeriod = 0;       ///< wall-clock seconds between calls (0: not by time)
  double virtPeriod = 0;       ///< simulated seconds between calls (0: not by simulated time)
  bool initRun = false;
  std::int64_t nDo = -1;       ///< calls after which it is not called any more (-1: no limit)
  /// The callback is a script's Python code (a PyRunner): when it raises, the scene is as the
  /// engines before it left it, and the step may go on (a coupling's C++ hook may stop halfway);
  /// on a scene split over processes, what it wrote into the bodies goes to their ghosts.
  bool resumable = false;
  std::int64_t iterLast = 0; ///< iteration of the last call
  double virtLast = 0;       ///< simulated time of the last call
  std::int64_t nDone = 0;    ///< number of calls so far

private:
  std::chrono::steady_clock::time_point realLast_ = std::chrono::steady_clock::now();
};
} // namespace talus::dem
