// The step's scheduler: the plans it makes from engine lists (regions, barriers, where serial
// stages go), the regions a step really enters, the serial stages' view of the step, timing,
// the distributed scene's communication stages, and the same bits as the engines one by one.
#include "dem/contact/Collider.h"
#include "dem/core/Domain.h"
#include "dem/core/Scene.h"
#include "dem/laws/ContactLaw.h"
#include "dem/engines/CallbackEngine.h"
#include "dem/engines/ForceResetter.h"
#include "dem/engines/InteractionLoop.h"
#include "dem/engines/NewtonIntegrator.h"
#include "dem/step/Scheduler.h"
#include "dem/step/StepPlan.h"

#include <gtest/gtest.h>

using namespace talus::dem;

namespace
{
using EngineList = std::vector<std::shared_ptr<Engine>>;

std::shared_ptr<InteractionLoop> loopWith(std::initializer_list<const char*> laws)
{
  auto loop = std::make_shared<InteractionLoop>();
  for (const char* law : laws)
    loop->laws.push_back(makeContactLaw(law));
  return loop;
}

std::shared_ptr<CallbackEngine> hook(std::function<void()> call = [] {})
{
  auto engine = std::make_shared<CallbackEngine>();
  engine->callback = std::move(call);
  return engine;
}

/// ForceResetter, Collider, InteractionLoop (linear law), NewtonIntegrator.
EngineList usualEngines(double gravity = -9.81)
{
  auto newton = std::make_shared<NewtonIntegrator>();
  newton->gravity = Vec3(0, 0, gravity);
  newton->damping = 0.3;
  return {std::make_shared<ForceResetter>(), std::make_shared<Collider>(), loopWith({"linear"}), newton};
}

/// 12 x 12 x 8 spheres (more than parallelLoopMinimum) above a floor, slightly jittered, with
/// the usual engines; `gravity` 0 leaves them at rest.
Scene bed(double gravity = -9.81)
{
  Scene scene;
  scene.addMaterial(Material{});
  scene.addWall(0, 2, 1, 0);
  for (int i = 0; i < 12; ++i)
    for (int j = 0; j < 12; ++j)
      for (int k = 0; k < 8; ++k)
      {
        const double jitter = 0.001 * ((i * 7 + j * 3 + k * 5) % 5 - 2);
        scene.addSphere(Vec3(0.05 * i + jitter, 0.05 * j - jitter, 0.03 + 0.05 * k), 0.024, 0);
      }
  scene.engines = usualEngines(gravity);
  scene.dt = 0.3 * scene.pWaveTimeStep();
  return scene;
}

StepPlan planOf(const EngineList& engines, PlanConditions conditions = {})
{
  return planStep(engines, 0, conditions);
}

/// Yade's sub-steps: each engine's own run() in turn, `steps` times.
void runOneByOne(Scene& scene, int steps)
{
  scene.subStepping = true;
  for (int k = 0; k < steps * static_cast<int>(scene.engines.size() + 2); ++k)
    scene.step();
  scene.subStepping = false;
}

/// A domain that is the whole scene: its calls counted.
class WholeDomain : public Domain
{
public:
  std::size_t ownedBodies(const Scene& scene) const override { return scene.bodies.size(); }
  bool owns(std::size_t) const override { return true; }
  bool computesPair(std::size_t, std::size_t) const override { return true; }
  void beforeDetection(Scene&) override { ++migrations; }
  void afterIntegration(Scene&) override { ++ghostUpdates; }
  void sum(std::span<double>) const override {}
  double min(double value) const override { return value; }
  void min(std::span<double>) const override { ++reductions; }
  mutable int reductions = 0;
  int migrations = 0, ghostUpdates = 0;
};
} // namespace

TEST(StepPlan, TheUsualEnginesShareOneRegionWithOneBarrier)
{
  const StepPlan plan = planOf(usualEngines());
  EXPECT_EQ(plan.describe(), "forces+integration");
  EXPECT_TRUE(plan.alone);
  EXPECT_EQ(plan.regions, 1);
  EXPECT_EQ(plan.barriers, 1); // after the contacts; the skin was checked ahead
  EXPECT_EQ(plan.serialStages, 0);
}

TEST(StepPlan, PyRunnersRunBeforeAndAfterTheSharedRegion)
{
  EngineList engines = usualEngines();
  engines.insert(engines.begin(), hook());
  engines.push_back(hook());
  const StepPlan plan = planOf(engines);
  EXPECT_EQ(plan.describe(), "serial 0 | forces+integration | serial 5");
  EXPECT_FALSE(plan.alone);
  EXPECT_EQ(plan.regions, 1);
  EXPECT_EQ(plan.barriers, 2); // the skin check's (a PyRunner may move bodies) and the contacts'
  EXPECT_EQ(plan.serialStages, 2);
}

TEST(StepPlan, ACoupledSceneSplitsTheRegionsAroundItsHooks)
{
  // A coupling adding its forces after the reset, one reading the forces before the
  // integration, one reading the new positions after it (ParticleExchange's hook points).
  EngineList engines = usualEngines();
  engines.insert(engines.begin() + 1, hook());
  engines.insert(engines.begin() + 4, hook());
  engines.push_back(hook());
  const StepPlan plan = planOf(engines);
  EXPECT_EQ(plan.describe(), "reset | serial 1 | forces | serial 4 | integration | serial 6");
  EXPECT_EQ(plan.regions, 3);
  EXPECT_EQ(plan.barriers, 2);
  EXPECT_EQ(plan.serialStages, 3);
}

TEST(StepPlan, SeveralLawsAndDomainsStayOnTheSharedStages)
{
  EngineList severalLaws = usualEngines();
  severalLaws[2] = loopWith({"linear", "hertz"});
  const StepPlan laws = planOf(severalLaws);
  EXPECT_EQ(laws.describe(), "forces+integration");
  EXPECT_FALSE(laws.contactsInRegion); // one serial call between the two regions
  EXPECT_EQ(laws.regions, 2);
  EXPECT_EQ(laws.barriers, 0);

  const StepPlan distributed = planOf(usualEngines(), {.distributed = true});
  EXPECT_EQ(distributed.describe(), "forces+integration");
  EXPECT_EQ(distributed.regions, 2); // the skin check's reduction over processes between them
  EXPECT_EQ(distributed.barriers, 1);
}

TEST(StepPlan, WithoutTheUsualGroupEveryEngineRunsWhole)
{
  EngineList engines = usualEngines();
  engines.erase(engines.begin()); // no ForceResetter
  EXPECT_EQ(planOf(engines).describe(), "serial 0 | serial 1 | serial 2");
  EngineList withDead = usualEngines();
  withDead.insert(withDead.begin() + 1, hook());
  withDead[1]->dead = true; // a dead engine is not there
  EXPECT_EQ(planOf(withDead).describe(), "forces+integration");
}

TEST(Scheduler, AStepEntersTheRegionsAndBarriersPlanned)
{
  for (bool pyRunner : {false, true})
  {
    Scene scene = bed(0); // at rest: no re-detection after the first step
    if (pyRunner)
      scene.engines.push_back(hook());
    scene.run(5);
    auto& scheduler = dynamic_cast<Scheduler&>(scene.stepLoop());
    EXPECT_EQ(scheduler.regionsEntered(), scheduler.plan().regions) << pyRunner;
    EXPECT_EQ(scheduler.barriersPassed(), scheduler.plan().barriers) << pyRunner;
    EXPECT_EQ(scheduler.sharedSteps(), 5);
  }
}

TEST(Scheduler, TrackedEnergyStaysInTheOneRegionAndGivesTheEnginesBits)
{
  // Each body's terms (gravity, damping, the imposed motions' work) are summed in the blocks of
  // the engines' loops, whichever thread integrates them.
  Scene shared = bed(), oneByOne = bed();
  for (Scene* scene : {&shared, &oneByOne})
  {
    scene->energy.enabled = true;
    scene->bodies.dynamic[3] = 0; // an imposed motion
    scene->bodies.vel[3] = Vec3(0, 0, -0.01);
    scene->bodies.blockedDofs[4] = 1; // a blocked direction of a dynamic body
    scene->bodies.vel[4] = Vec3(0.01, 0, 0);
  }
  shared.run(300);
  runOneByOne(oneByOne, 300);
  auto& scheduler = dynamic_cast<Scheduler&>(shared.stepLoop());
  EXPECT_EQ(scheduler.plan().describe(), "forces+integration");
  EXPECT_EQ(scheduler.plan().regions, 1);
  EXPECT_EQ(scheduler.plan().barriers, 1);
  EXPECT_EQ(shared.bodies.pos, oneByOne.bodies.pos);
  for (double EnergyTracker::*term : {&EnergyTracker::gravWork, &EnergyTracker::nonviscDamp,
                                      &EnergyTracker::kinematicWork, &EnergyTracker::plastDissip})
    EXPECT_EQ(shared.energy.*term, oneByOne.energy.*term);
  EXPECT_NE(shared.energy.kinematicWork, 0.0);
  EXPECT_NE(shared.energy.gravWork, 0.0);
}

TEST(Scheduler, SerialStagesSeeTheStepAtTheirPlace)
{
  Scene scene = bed();
  scene.run(1500); // fallen onto the floor: the bottom spheres touch it
  const std::size_t bottom = 1;
  Vec3 startPos, afterReset, beforeIntegration, posBeforeIntegration;
  auto& b = scene.bodies;
  scene.engines.insert(scene.engines.begin(), hook([&] { startPos = b.pos[bottom]; }));
  scene.engines.insert(scene.engines.begin() + 2, hook([&] { afterReset = b.force[bottom]; }));
  scene.engines.insert(scene.engines.begin() + 5, hook([&] {
    beforeIntegration = b.force[bottom];
    posBeforeIntegration = b.pos[bottom];
  }));
  scene.step();
  EXPECT_EQ(dynamic_cast<Scheduler&>(scene.stepLoop()).plan().describe(),
            "serial 0 | reset | serial 2 | forces | serial 5 | integration");
  EXPECT_EQ(afterReset, Vec3::Zero());             // reset, no contact force yet
  EXPECT_GT(beforeIntegration.norm(), 0);          // the contacts' forces, gathered
  EXPECT_EQ(posBeforeIntegration, startPos);       // not moved yet
  EXPECT_NE(b.pos[bottom], startPos);              // moved after
}

TEST(Scheduler, TimingTimesTheStagesAndKeepsTheBits)
{
  Scene plain = bed(), timed = bed();
  timed.timingEnabled = true;
  plain.run(200);
  timed.run(200);
  EXPECT_EQ(plain.bodies.pos, timed.bodies.pos);
  EXPECT_EQ(plain.bodies.vel, timed.bodies.vel);
  EXPECT_EQ(timed.stepLoop().sharedSteps(), 200);
  for (const auto& engine : timed.engines)
  {
    EXPECT_EQ(engine->execCount, 200) << engine->typeName();
    // The gather resets each body's forces in its own pass (GatherAhead.h): the resetter is
    // counted, its time booked with the gather's.
    if (engine->typeName() != "ForceResetter")
    {
      EXPECT_GT(engine->execTime, 0) << engine->typeName();
    }
  }
  const TimingDeltas& loop = timed.engines[2]->timingDeltas;
  ASSERT_EQ(loop.labels, (std::vector<std::string>{"geometry, physics, law", "forces per body"}));
  EXPECT_LE(loop.nsec[0] + loop.nsec[1], timed.engines[2]->execTime);
}

TEST(Scheduler, SharedStagesGiveTheBitsOfTheEnginesOneByOne)
{
  auto withHooks = [](Scene& scene, bool severalLaws) {
    if (severalLaws)
      scene.engines[2] = loopWith({"linear", "hertz"});
    auto& b = scene.bodies;
    scene.engines.insert(scene.engines.begin() + 1, hook([&b] { b.force[5] += Vec3(0, 0, 0.001); }));
    scene.engines.push_back(hook([&b] { b.pos[7] += Vec3(1e-5, 0, 0); }));
  };
  for (bool severalLaws : {false, true})
  {
    Scene shared = bed(), oneByOne = bed();
    withHooks(shared, severalLaws);
    withHooks(oneByOne, severalLaws);
    shared.run(300);
    runOneByOne(oneByOne, 300);
    EXPECT_EQ(shared.stepLoop().sharedSteps(), 300);
    EXPECT_EQ(oneByOne.stepLoop().sharedSteps(), 0);
    EXPECT_GT(shared.contacts.list.size(), 1000u);
    EXPECT_EQ(shared.bodies.pos, oneByOne.bodies.pos) << severalLaws;
    EXPECT_EQ(shared.bodies.angVel, oneByOne.bodies.angVel) << severalLaws;
  }
}

TEST(Scheduler, ADomainIsCalledAtItsCommunicationStages)
{
  Scene plain = bed(), split = bed();
  auto domain = std::make_shared<WholeDomain>();
  split.domain = domain;
  plain.run(200);
  split.run(200);
  const auto& collider = dynamic_cast<const Collider&>(*split.engines[1]);
  EXPECT_EQ(domain->reductions, 200);             // the skin check's displacements, every step
  EXPECT_EQ(domain->migrations, collider.rebuilds); // before each re-detection
  EXPECT_GT(domain->migrations, 1);
  EXPECT_EQ(domain->ghostUpdates, 200);           // after each integration
  EXPECT_EQ(split.stepLoop().sharedSteps(), 200);
  EXPECT_EQ(plain.bodies.pos, split.bodies.pos);
}

TEST(Scheduler, GhostsAreLeftToTheirOwners)
{
  // Every third sphere a ghost: its owner (elsewhere) moves it, not this process's integrator,
  // in the shared step and in Yade's sub-steps alike.
  struct ThirdsGhosts : WholeDomain
  {
    bool owns(std::size_t row) const override { return row % 3 != 1; }
  };
  for (bool oneByOne : {false, true})
  {
    Scene split = bed();
    split.domain = std::make_shared<ThirdsGhosts>();
    const std::vector<Vec3> start = split.bodies.pos;
    if (oneByOne)
      runOneByOne(split, 20);
    else
      split.run(20);
    for (std::size_t i = 1; i < start.size(); ++i)
      if (i % 3 == 1)
        EXPECT_EQ(split.bodies.pos[i], start[i]) << i;
      else
        EXPECT_NE(split.bodies.pos[i], start[i]) << i;
  }
}
