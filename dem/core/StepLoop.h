#pragma once

#include <cstddef>
#include <cstdint>
#include <functional>
#include <memory>
#include <vector>

namespace talus::dem
{
class Scene;

/// How a scene's engines run in a step. Scene keeps the step's protocol (the clock, sub-steps,
/// engines set during a step, a failed step) and hands the engines' work to this interface;
/// dem/step/ implements it (Scheduler), so the scene knows nothing of parallel regions.
class StepLoop
{
public:
  virtual ~StepLoop() = default;

  /// Runs engine k of the scene's list whole (Scene's wrapper: it marks the step failed or
  /// resumable when the engine throws).
  using EngineRunner = std::function<void(std::size_t)>;

  /// Run every engine of the scene's list for one step, the serial ones through `runEngine`.
  /// @param runEngine Scene's wrapper, which records a failure before passing the exception on
  virtual void runStep(Scene& scene, const EngineRunner& runEngine) = 0;
  /// Run engine k alone (one of Yade's sub-steps), through `runEngine`.
  /// @param k the engine's index in scene.engines
  /// @param runEngine Scene's wrapper, as for runStep
  virtual void runSubStep(Scene& scene, std::size_t k, const EngineRunner& runEngine) = 0;
  /// The checks of a step's end, after its engines, before the clock advances.
  /// @throws std::runtime_error when one fails (the energy-growth check)
  virtual void endStep(Scene& scene) = 0;
  /// Something outside the step may have moved bodies since the last one (a call from Python
  /// between steps): forget what the last step prepared for the next.
  virtual void forgetAhead() = 0;

  /// Steps whose usual engines ran in shared parallel regions (diagnostics).
  [[nodiscard]] virtual std::int64_t sharedSteps() const = 0;
  /// Wall seconds spent in serial stages, the engines that declare no stage (diagnostics).
  [[nodiscard]] virtual double serialSeconds() const = 0;
};

/// The step loop every scene uses (defined in dem/step/).
/// @return a new Scheduler, owned by the caller
std::unique_ptr<StepLoop> makeStepLoop();

/// A scene's step loop, made at its first use. A copy of the scene starts with a new one: the
/// loop keeps only what it prepared for the scene's next step.
class StepLoopHolder
{
public:
  StepLoopHolder() = default;
  StepLoopHolder(const StepLoopHolder&) {}
  StepLoopHolder& operator=(const StepLoopHolder&)
  {
    loop_.reset();
    return *this;
  }
  /// @return the loop, made by makeStepLoop on the first call; owned by the holder
  StepLoop& get()
  {
    if (!loop_)
      loop_ = makeStepLoop();
    return *loop_;
  }

private:
  std::unique_ptr<StepLoop> loop_;
};

/// A check made at the end of every step, after the engines and before the clock advances,
/// that stops the run by throwing. The layers above the step register theirs (measure/'s
/// energy-growth check), so that neither the scene nor the step includes them.
using StepCheck = void (*)(Scene&);
/// Register a check (at load time, through a namespace-scope initialiser).
/// @param check called with the scene at every step's end; throws to stop the run
/// @return true (so that the registration can initialise a constant)
bool addStepCheck(StepCheck check);
/// The registered checks, in the order registered.
/// @return the list, alive for the program's lifetime
const std::vector<StepCheck>& stepChecks();
} // namespace talus::dem
