// The particle exchange interface, as a coupling uses it: read arrays, apply persistent and
// per-step forces, hook into the step.
#include "dem/interface/Exchange.h"
#include "dem/laws/ContactLaw.h"
#include "dem/engines/ForceResetter.h"
#include "dem/engines/InteractionLoop.h"
#include "dem/engines/NewtonIntegrator.h"
#include "dem/contact/Collider.h"

#include <gtest/gtest.h>

using namespace talus::dem;

namespace
{
/// A sphere in free fall with the standard engines, no damping.
Scene fallingSphere()
{
  Scene scene;
  scene.addMaterial(Material{});
  scene.addSphere(Vec3(0, 0, 1), 0.1, 0);
  auto newton = std::make_shared<NewtonIntegrator>();
  newton->gravity = Vec3(0, 0, -10);
  newton->damping = 0;
  auto loop = std::make_shared<InteractionLoop>();
  loop->laws.push_back(makeContactLaw("linear"));
  scene.engines = {std::make_shared<ForceResetter>(), std::make_shared<Collider>(), loop, newton};
  scene.dt = 1e-3;
  return scene;
}
} // namespace

TEST(Exchange, PersistentForceBalancesGravity)
{
  Scene scene = fallingSphere();
  ParticleExchange exchange(scene);
  exchange.persistentForces()[0] = Vec3(0, 0, 10 * exchange.masses()[0]);
  for (int k = 0; k < 100; ++k)
    scene.step();
  EXPECT_NEAR(exchange.positions()[0].z(), 1.0, 1e-12);
  EXPECT_TRUE(exchange.isSphere(0));
  EXPECT_FALSE(exchange.isSphere(1));
}

TEST(Exchange, StepForceFromAHookActsOnlyWhileTheHookRuns)
{
  Scene scene = fallingSphere();
  ParticleExchange exchange(scene);
  int calls = 0;
  auto hook = exchange.addHook(ParticleExchange::HookPoint::BeforeForces, [&] {
    exchange.stepForces()[0] += Vec3(0, 0, 10 * exchange.masses()[0]);
    ++calls;
  });
  ASSERT_EQ(scene.engines[1], hook); // right after the ForceResetter
  for (int k = 0; k < 50; ++k)
    scene.step();
  EXPECT_EQ(calls, 50);
  EXPECT_NEAR(exchange.velocities()[0].z(), 0.0, 1e-12);
  hook->dead = true;
  scene.step();
  EXPECT_NEAR(exchange.velocities()[0].z(), -10 * scene.dt, 1e-12);
}

TEST(Exchange, HooksRunAtTheirPeriodAndPlace)
{
  Scene scene = fallingSphere();
  ParticleExchange exchange(scene);
  std::vector<std::int64_t> seen;
  exchange.addHook(ParticleExchange::HookPoint::AfterStep, [&] { seen.push_back(exchange.iter()); }, 10);
  EXPECT_EQ(scene.engines.back()->typeName(), "PyRunner");
  for (int k = 0; k < 25; ++k)
    scene.step();
  EXPECT_EQ(seen, (std::vector<std::int64_t>{0, 10, 20}));
  Scene empty;
  ParticleExchange none(empty);
  EXPECT_THROW(none.addHook(ParticleExchange::HookPoint::AfterForces, [] {}), std::logic_error);
}

TEST(Exchange, HeatIsNotGivenUntilAComponentWritesItAndEveryCopySeesIt)
{
  Scene scene = fallingSphere();
  scene.addSphere(Vec3(0, 0, 2), 0.1, 0);
  ParticleExchange heater(scene), reader(scene);
  for (const auto field : {reader.temperatures(), reader.heatCapacities(), reader.conductivities(),
                           reader.thermalExpansions()})
    for (const double x : field)
      EXPECT_TRUE(std::isnan(x)); // a scene without heat: nothing given
  heater.temperatures()[1] = 350.0;
  heater.conductivities()[0] = 2.0;
  for (int k = 0; k < 10; ++k) // a step neither reads nor changes them
    scene.step();
  EXPECT_EQ(reader.temperatures()[1], 350.0);
  EXPECT_TRUE(std::isnan(reader.temperatures()[0]));
  EXPECT_EQ(reader.conductivities()[0], 2.0);
  const BodyId added = scene.addSphere(Vec3(0, 0, 3), 0.1, 0);
  EXPECT_EQ(reader.temperatures().size(), 3U);
  EXPECT_TRUE(std::isnan(reader.temperatures()[static_cast<std::size_t>(added)]));
}
