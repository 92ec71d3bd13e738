#pragma once

#include "dem/Engine.h"

#include <cstdint>
#include <functional>

namespace talus::dem
{
/// Calls a function every `iterPeriod` steps (Yade's PyRunner when the function is Python; a
/// coupling's step hook when it is C++). As Yade's PeriodicEngine: first call when `iter`
/// reaches `iterPeriod`, or at the first step with `initRun`.
class CallbackEngine : public Engine
{
public:
  void run(Scene& scene) override;
  [[nodiscard]] std::string typeName() const override { return "PyRunner"; }

  std::function<void()> callback;
  std::int64_t iterPeriod = 1;
  bool initRun = false;
  std::int64_t iterLast = 0; ///< iteration of the last call
  std::int64_t nDone = 0;    ///< number of calls so far
};
} // namespace talus::dem
