#include "dem/step/Scheduler.h"

#include "dem/contact/Collider.h"
#include "dem/core/Scene.h"
#include "dem/engines/InteractionLoop.h"
#include "dem/engines/NewtonIntegrator.h"

#include <chrono>

namespace talus::dem
{
namespace
{
PlanConditions conditionsOf(const Scene& scene) { return {scene.domain != nullptr}; }

std::vector<StepCheck>& checks()
{
  static std::vector<StepCheck> registered;
  return registered;
}
} // namespace

std::unique_ptr<StepLoop> makeStepLoop() { return std::make_unique<Scheduler>(); }

bool addStepCheck(StepCheck check)
{
  checks().push_back(check);
  return true;
}

const std::vector<StepCheck>& stepChecks() { return checks(); }

bool Scheduler::Signature::matches(const Scene& scene) const
{
  if (!(conditions == conditionsOf(scene)) || engines.size() != scene.engines.size())
    return false;
  for (std::size_t k = 0; k < engines.size(); ++k)
  {
    const Engine& e = *scene.engines[k];
    if (!(engines[k] == Key{&e, e.dead, e.stages()}))
      return false;
  }
  return true;
}

void Scheduler::Signature::take(const Scene& scene)
{
  engines.clear();
  for (const auto& e : scene.engines)
    engines.push_back({e.get(), e->dead, e->stages()});
  conditions = conditionsOf(scene);
}

void Scheduler::runStep(Scene& scene, const EngineRunner& runEngine)
{
  if (!signature_.matches(scene))
  {
    signature_.take(scene);
    plan_ = planStep(scene.engines, 0, signature_.conditions);
  }
  run(scene, plan_, signature_, runEngine);
}

void Scheduler::run(Scene& scene, const StepPlan& plan, const Signature& signature, const EngineRunner& runEngine)
{
  if (plan.shared())
    regions_.begin(scene);
  bool serialBefore = false, sharedStarted = false;
  for (const StepPlan::Entry& e : plan.entries)
  {
    if (e.item == StepPlan::Item::Serial)
    {
      runSerial(scene, e.engine, runEngine);
      serialBefore = true;
      continue;
    }
    // The engines before the shared stages may have changed what the rest of the step can be
    // (an engine killed, a law added, energy tracking turned on): the rest runs by a new plan.
    const bool first = !sharedStarted;
    sharedStarted = true;
    if (first && serialBefore && !signature.matches(scene))
    {
      Signature rest;
      rest.take(scene);
      run(scene, planStep(scene.engines, plan.resetter, rest.conditions), rest, runEngine);
      return;
    }
    runShared(scene, plan, e.item);
  }
  if (plan.shared())
  {
    regions_.stepDone();
    bookStageTimes(scene, plan);
    ++sharedSteps_;
  }
}

void Scheduler::runShared(Scene& scene, const StepPlan& plan, StepPlan::Item item)
{
  // planStep checked the engines' kinds.
  auto& newton = static_cast<NewtonIntegrator&>(*scene.engines[plan.newton]);
  if (item == StepPlan::Item::Reset)
    regions_.reset(scene);
  else if (item == StepPlan::Item::Integration)
    regions_.integrate(scene, newton);
  else
  {
    const SharedRegions::Engines engines{static_cast<Collider&>(*scene.engines[plan.collider]),
                                         static_cast<InteractionLoop&>(*scene.engines[plan.loop]), newton};
    regions_.forces(scene, engines,
                    {!plan.separateReset(), plan.contactsInRegion, !plan.separateIntegration(), plan.alone});
  }
}

void Scheduler::runSubStep(Scene& scene, std::size_t k, const EngineRunner& runEngine)
{
  runSerial(scene, k, runEngine);
}

void Scheduler::runSerial(Scene& scene, std::size_t k, const EngineRunner& runEngine)
{
  Engine& engine = *scene.engines[k];
  const bool timed = scene.timingEnabled && !engine.dead;
  const auto start = std::chrono::steady_clock::now();
  runEngine(k);
  const std::int64_t nsec =
      std::chrono::duration_cast<std::chrono::nanoseconds>(std::chrono::steady_clock::now() - start).count();
  serialSeconds_ += 1e-9 * static_cast<double>(nsec);
  if (timed)
  {
    engine.execTime += nsec;
    ++engine.execCount;
  }
}

void Scheduler::bookStageTimes(Scene& scene, const StepPlan& plan) const
{
  if (!scene.timingEnabled)
    return;
  auto nsec = [this](StagePoint point) {
    return static_cast<std::int64_t>(1e9 * regions_.stageSeconds[static_cast<std::size_t>(point)]);
  };
  auto book = [&](std::size_t k, std::int64_t time) -> Engine& {
    Engine& engine = *scene.engines[k];
    engine.execTime += time;
    ++engine.execCount;
    return engine;
  };
  book(plan.resetter, nsec(StagePoint::Reset));
  book(plan.collider, nsec(StagePoint::SkinCheck) + nsec(StagePoint::Detection))
      .timingDeltas.add("skin check", nsec(StagePoint::SkinCheck));
  Engine& loop = book(plan.loop, nsec(StagePoint::Contacts) + nsec(StagePoint::Gather));
  loop.timingDeltas.add("geometry, physics, law", nsec(StagePoint::Contacts));
  loop.timingDeltas.add("forces per body", nsec(StagePoint::Gather));
  book(plan.newton, nsec(StagePoint::Integration));
}

void Scheduler::endStep(Scene& scene)
{
  for (StepCheck check : stepChecks())
    check(scene);
}
} // namespace talus::dem
