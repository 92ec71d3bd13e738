// HydroForce driven through the particle exchange interface (the C++ route of HydroForceEngine):
// a sphere settling in still fluid reaches the Dallavalle terminal velocity.
#include "flow/HydroForceExchange.h"

#include "dem/engines/ForceResetter.h"
#include "dem/engines/NewtonIntegrator.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

using namespace talus;

TEST(HydroForceExchange, SphereSettlesAtTheDallavalleVelocity)
{
  const double r = 5e-4, rhoP = 2500, rho = 1000, mu = 1e-3, g = 9.81;
  dem::Scene scene;
  dem::Material material;
  material.density = rhoP;
  scene.addMaterial(material);
  scene.addSphere(dem::Vec3(0, 0, 0.5), r, 0);
  auto newton = std::make_shared<dem::NewtonIntegrator>();
  newton->gravity = dem::Vec3(0, 0, -g);
  newton->damping = 0;
  scene.engines = {std::make_shared<dem::ForceResetter>(), newton};
  scene.dt = 1e-3; // a thirtieth of the relaxation time w / g'

  flow::HydroForceParameters p;
  p.nCell = 600;
  p.deltaZ = 1e-3;
  p.densFluid = rho;
  p.viscoDyn = mu;
  p.steadyFlow = false;
  p.gravity = {0, 0, -g};
  flow::HydroForce hydro(p);
  dem::ParticleExchange exchange(scene);
  auto hook = flow::attachHydroForce(exchange, hydro, {0});
  ASSERT_EQ(scene.engines[1], hook);
  for (int k = 0; k < 800; ++k) // 26 relaxation times
    scene.step();

  // Root of (rho_p - rho) V g = 1/2 rho pi r^2 (0.44 w + 24.4 nu / d) w.
  const double a = 0.5 * rho * std::numbers::pi * r * r * 0.44;
  const double b = 0.5 * rho * std::numbers::pi * r * r * 24.4 * mu / (rho * 2 * r);
  const double c = (rhoP - rho) * 4.0 / 3.0 * std::numbers::pi * r * r * r * g;
  const double w = (-b + std::sqrt(b * b + 4 * a * c)) / (2 * a);
  EXPECT_NEAR(-exchange.velocities()[0].z() / w, 1.0, 1e-8);
}

TEST(HydroForceExchange, OutsideTheGridIsAnErrorNamingTheBody)
{
  dem::Scene scene;
  scene.addMaterial(dem::Material{});
  scene.addSphere(dem::Vec3(0, 0, 5.0), 1e-3, 0);
  scene.engines = {std::make_shared<dem::ForceResetter>(), std::make_shared<dem::NewtonIntegrator>()};
  scene.dt = 1e-4;
  flow::HydroForceParameters p;
  p.nCell = 10;
  p.deltaZ = 1e-3;
  flow::HydroForce hydro(p);
  dem::ParticleExchange exchange(scene);
  flow::attachHydroForce(exchange, hydro, {0});
  EXPECT_THROW(
      {
        try
        {
          scene.step();
        }
        catch (const std::invalid_argument& e)
        {
          EXPECT_NE(std::string(e.what()).find("body 0 at z = 5"), std::string::npos);
          throw;
        }
      },
      std::invalid_argument);
}
