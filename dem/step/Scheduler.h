#pragma once

#include "dem/core/StepLoop.h"
#include "dem/step/SharedRegions.h"
#include "dem/step/StepPlan.h"

#include <cstdint>
#include <vector>

namespace talus::dem
{
/// The scene's step loop: runs any engine list by its plan (StepPlan, made again when the
/// engines, what they declare, energy tracking or the domain change), the shared stages in
/// SharedRegions, the others whole at their place; times each stage when scene.timingEnabled
/// (into the engines' execTime and timingDeltas, as Yade's timing); then the step's end checks.
class Scheduler final : public StepLoop
{
public:
  void runStep(Scene& scene, const EngineRunner& runEngine) override;
  void runSubStep(Scene& scene, std::size_t k, const EngineRunner& runEngine) override;
  void endStep(Scene& scene) override;
  void forgetAhead() override { regions_.forgetAhead(); }
  [[nodiscard]] std::int64_t sharedSteps() const override { return sharedSteps_; }
  [[nodiscard]] double serialSeconds() const override { return serialSeconds_; }

  /// The plan of the last step run whole.
  [[nodiscard]] const StepPlan& plan() const { return plan_; }
  /// Regions and barriers entered in the last step.
  [[nodiscard]] int regionsEntered() const { return regions_.regions; }
  [[nodiscard]] int barriersPassed() const { return regions_.barriers; }

private:
  /// What a plan was made for: the live engines' identities and declarations, and conditions.
  struct Key
  {
    const Engine* engine;
    bool dead;
    Stages stages;
    bool operator==(const Key&) const = default;
  };
  struct Signature
  {
    std::vector<Key> engines;
    PlanConditions conditions;
    [[nodiscard]] bool matches(const Scene& scene) const;
    void take(const Scene& scene);
  };
  /// Run `plan` (made for `signature`) for the current step.
  void run(Scene& scene, const StepPlan& plan, const Signature& signature, const EngineRunner& runEngine);
  /// The shared items: forces (with the integration) or the integration alone.
  void runShared(Scene& scene, const StepPlan& plan, StepPlan::Item item);
  /// Engine k whole, timed.
  void runSerial(Scene& scene, std::size_t k, const EngineRunner& runEngine);
  /// With timing: the shared stages' times into their engines.
  void bookStageTimes(Scene& scene, const StepPlan& plan) const;

  Signature signature_; ///< what plan_ was made for
  StepPlan plan_;
  SharedRegions regions_;
  std::int64_t sharedSteps_ = 0;
  double serialSeconds_ = 0;
};
} // namespace talus::dem
