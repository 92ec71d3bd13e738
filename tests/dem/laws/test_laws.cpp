// The contact laws' kernels, each on two spheres moved kinematically: a normal force from the
// overlap (the law's formula), the Coulomb cap on the shear force while sliding, and no force
// once the spheres are apart; and the shared parts alone (the cap, the springs).
#include "dem/contact/Collider.h"
#include "dem/core/Scene.h"
#include "dem/laws/ContactLaw.h"
#include "dem/laws/parts/Bond.h"
#include "dem/laws/parts/Coulomb.h"
#include "dem/laws/parts/Normal.h"
#include "dem/step/ForceResetter.h"
#include "dem/step/InteractionLoop.h"
#include "dem/step/NewtonIntegrator.h"

#include <gtest/gtest.h>

#include <cmath>
#include <string>

using namespace talus::dem;

namespace
{
constexpr double R = 0.1, young = 1e7, poisson = 0.3, friction = 0.5, dt = 1e-5;

Material material(const std::string& law)
{
  Material m;
  m.young = young;
  m.poisson = poisson;
  m.frictionAngle = friction;
  m.density = 2600;
  if (law == "viscoelastic")
  {
    m.kind = MaterialKind::ViscEl;
    m.tc = 1e-3, m.en = 0.5, m.et = 0.5;
  }
  else if (law == "cohesive")
  {
    m.kind = MaterialKind::CohFrict;
    m.isCohesive = false; // the frictional contact; bonds are the replay test's
  }
  return m;
}

/// Sphere 0 fixed at the origin, sphere 1 above it overlapping by `overlap`, moved only by the
/// velocity it is given (no integration of forces), with the law of that name.
void pair(Scene& scene, const std::string& law, double overlap)
{
  const int m = scene.addMaterial(material(law));
  scene.addSphere(Vec3::Zero(), R, m);
  scene.addSphere(Vec3(0, 0, 2 * R - overlap), R, m);
  scene.bodies.dynamic[0] = scene.bodies.dynamic[1] = 0;
  auto loop = std::make_shared<InteractionLoop>();
  loop->laws.push_back(makeContactLaw(law));
  scene.engines = {std::make_shared<ForceResetter>(), std::make_shared<Collider>(), loop,
                   std::make_shared<NewtonIntegrator>()};
  scene.dt = dt;
}

const Contact* realContact(const Scene& scene)
{
  for (const Contact& c : scene.contacts.list)
    if (c.real)
      return &c;
  return nullptr;
}

class EveryLaw : public ::testing::TestWithParam<std::string>
{
};
} // namespace

TEST_P(EveryLaw, PushesApartAlongTheNormal)
{
  Scene scene;
  pair(scene, GetParam(), 1e-4);
  scene.step();
  const Contact* c = realContact(scene);
  ASSERT_NE(c, nullptr);
  EXPECT_GT(c->normalForce.z(), 0); // on sphere 1, upwards
  EXPECT_NEAR(c->normalForce.x(), 0, 1e-12 * c->normalForce.z());
  EXPECT_DOUBLE_EQ(scene.bodies.force[1].z(), c->normalForce.z());
  EXPECT_DOUBLE_EQ(scene.bodies.force[0].z(), -c->normalForce.z());
}

TEST_P(EveryLaw, ShearForceStaysUnderTheCoulombCap)
{
  Scene scene;
  pair(scene, GetParam(), 1e-4);
  scene.bodies.vel[1] = Vec3(1, 0, 0);
  double largest = 0;
  for (int k = 0; k < 200; ++k) // 2 mm of slide, well past the cap
  {
    scene.step();
    const Contact* c = realContact(scene);
    ASSERT_NE(c, nullptr);
    const double cap = std::tan(friction) * c->normalForce.norm();
    EXPECT_LE(c->shearForce.norm(), cap * (1 + 1e-12)) << "step " << k;
    largest = std::max(largest, c->shearForce.norm() / cap);
  }
  EXPECT_GT(largest, 1 - 1e-9); // it slid
}

TEST_P(EveryLaw, NoForceOnceApart)
{
  Scene scene;
  pair(scene, GetParam(), 1e-4);
  scene.step();
  scene.bodies.vel[1] = Vec3(0, 0, 1);
  for (int k = 0; k < 20; ++k) // 2e-4 m up: 1e-4 m apart
    scene.step();
  EXPECT_EQ(realContact(scene), nullptr);
  EXPECT_EQ(scene.bodies.force[1], Vec3::Zero());
  EXPECT_EQ(scene.bodies.torque[1], Vec3::Zero());
}

INSTANTIATE_TEST_SUITE_P(Laws, EveryLaw, ::testing::Values("linear", "hertz", "viscoelastic", "cohesive"));

TEST(LinearLaw, NormalForceIsTheSpringsInSeries)
{
  Scene scene;
  pair(scene, "linear", 1e-4);
  scene.step();
  // kn = 2 (E r)(E r) / (2 E r) = E r for two equal spheres
  EXPECT_NEAR(realContact(scene)->normalForce.z(), young * R * 1e-4, 1e-9 * young * R * 1e-4);
}

TEST(HertzLaw, NormalForceIsHertz)
{
  Scene scene;
  pair(scene, "hertz", 1e-4);
  scene.step();
  const double eStar = young / (2 * (1 - poisson * poisson)), rStar = R / 2;
  const double expected = 4.0 / 3.0 * eStar * std::sqrt(rStar) * std::pow(1e-4, 1.5);
  EXPECT_NEAR(realContact(scene)->normalForce.z(), expected, 1e-9 * expected);
}

TEST(CoulombPart, CapsAlongTheForceAndBooksTheSlip)
{
  Contact c;
  c.ks = 2.0;
  c.shearForce = Vec3(3, 4, 0); // |F| = 5, capped at 2
  ContactEnergy energy;
  parts::slide<true>(c, 2.0 / 5.0, energy);
  EXPECT_DOUBLE_EQ(c.shearForce.norm(), 2.0);
  EXPECT_DOUBLE_EQ(c.shearForce.normalized().dot(Vec3(0.6, 0.8, 0)), 1.0);
  EXPECT_DOUBLE_EQ(energy.plastDissip, 3.0 * 2.0 / 2.0); // slip 3/ks times the capped force 2
  c.ks = 0;                                              // no spring: nothing to book
  EXPECT_EQ(parts::plasticWork(Vec3(1, 0, 0), Vec3(0.5, 0, 0), 0.0), 0.0);
}

TEST(NormalParts, SpringsAndTheirEnergies)
{
  Contact c;
  c.kn = 1e6;
  c.penetration = 1e-4;
  ContactEnergy energy;
  EXPECT_DOUBLE_EQ(parts::LinearSpring::force<false>(c, nullptr, energy), 100.0);
  EXPECT_DOUBLE_EQ(parts::LinearSpring::elastic(c, nullptr), 0.5 * 1e6 * 1e-8);
  ContactExtra x;
  x.kno = 1e9;
  x.kso = 2e9;
  EXPECT_DOUBLE_EQ(parts::HertzSpring::force<false>(c, &x, energy), 1e9 * std::pow(1e-4, 1.5));
  EXPECT_DOUBLE_EQ(c.kn, 1.5 * 1e9 * 1e-2); // the tangent stiffness
  EXPECT_DOUBLE_EQ(c.ks, 2e9 * 1e-2);
  c.penetration = -1e-5; // apart: no force, no energy
  EXPECT_EQ(parts::HertzSpring::force<false>(c, &x, energy), 0.0);
  EXPECT_EQ(parts::HertzSpring::elastic(c, &x), 0.0);
}

TEST(BondPart, MohrCoulombWithATensionCutOff)
{
  EXPECT_DOUBLE_EQ(parts::bondedShearStrength(10, 20, 0.5), 20.0);       // cohesion + fn tan(phi)
  EXPECT_DOUBLE_EQ(parts::bondedShearStrength(10, -8, 0.5), 6.0);        // pulled: less
  EXPECT_EQ(parts::bondedShearStrength(10, -40, 0.5), 0.0);              // never below 0
  EXPECT_DOUBLE_EQ(parts::bondedShearStrength(10, 20, 0.5, true), 10.0); // cohesion alone
  EXPECT_DOUBLE_EQ(parts::bondedShearStrength(0, 20, 0.5, true), 10.0);  // none: friction
  EXPECT_DOUBLE_EQ(parts::frictionStrength(20, 0.5), 10.0);
  EXPECT_EQ(parts::frictionStrength(-20, 0.5), 0.0);
}

TEST(BondPart, APullBeyondTheStrengthEndsAFragileBondAndYieldsADuctileOne)
{
  Contact c;
  c.real = true;
  c.kn = 1e6;
  c.penetration = -3e-4; // pulled: -300 N against a strength of 100 N
  ContactExtra x;
  x.cohesionBroken = 0;
  x.normalAdhesion = 100;
  ContactEnergy energy;
  x.fragile = 0;
  EXPECT_DOUBLE_EQ(parts::BondedSpring::force<false>(c, &x, energy), -100.0); // yields at the strength
  EXPECT_DOUBLE_EQ(x.unp, -3e-4 + 1e-4);
  EXPECT_TRUE(c.real);
  x.unp = 0;
  x.fragile = 1;
  parts::BondedSpring::force<false>(c, &x, energy);
  EXPECT_FALSE(c.real); // the contact ends, its bond with it
  EXPECT_TRUE(x.cohesionBroken);
  EXPECT_EQ(x.normalAdhesion, 0.0);
}
