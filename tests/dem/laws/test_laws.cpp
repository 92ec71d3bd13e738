// The contact laws' kernels, each on two spheres moved kinematically: a normal force from the
// overlap (the law's formula), the Coulomb cap on the shear force while sliding, and no force
// once the spheres are apart; the shared parts alone (the cap, the springs, the dashpots, the
// rolling resistance, the rock joints); and the parameters a composed law takes from its parts.
#include "dem/contact/Collider.h"
#include "dem/core/Scene.h"
#include "dem/laws/ContactLaw.h"
#include "dem/laws/parts/AreaDashpot.h"
#include "dem/laws/parts/Bond.h"
#include "dem/laws/parts/Coulomb.h"
#include "dem/laws/parts/JointCoulomb.h"
#include "dem/laws/parts/JointSpring.h"
#include "dem/laws/parts/Normal.h"
#include "dem/laws/parts/NormalDashpot.h"
#include "dem/laws/parts/RollingResistance.h"
#include "dem/laws/parts/VelocityShear.h"
#include "dem/engines/ForceResetter.h"
#include "dem/engines/InteractionLoop.h"
#include "dem/engines/NewtonIntegrator.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>
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

namespace
{
/// A Motion part of the test's choosing (the parts read vn, vs and the arms).
struct GivenMotion
{
  double vn = 0;
  Vec3 vs = Vec3::Zero(), c1x = Vec3::Zero(), c2x = Vec3::Zero();
};

/// Two spheres of the linear law's material (sphere 1 above sphere 0) and their contact along z,
/// for the parts that read the bodies.
struct PartScene
{
  Scene scene;
  Contact c;
  PartScene()
  {
    const int m = scene.addMaterial(material("linear"));
    scene.addSphere(Vec3::Zero(), R, m);
    scene.addSphere(Vec3(0, 0, 2 * R), R, m);
    c.id1 = 0;
    c.id2 = 1;
    c.real = true;
    c.kind = ContactGeometryKind::SphereSphere;
    c.normal = Vec3(0, 0, 1);
    c.refR1 = c.refR2 = R;
    c.contactPoint = Vec3(0, 0, R);
  }
  [[nodiscard]] StepContext step() const { return {scene.bodies, scene.materials, nullptr, dt, nullptr}; }
};
} // namespace

TEST(CoulombPart, SlideOverCapsOnlyAboveTheStrength)
{
  Contact c;
  c.ks = 1.0;
  c.shearForce = Vec3(4, 0, 0);
  ContactEnergy energy;
  auto keep = [](double maxFs) { return maxFs; };
  EXPECT_FALSE(parts::slideOver<true>(c, 4.0, keep, energy)); // at the strength: sticks
  EXPECT_EQ(c.shearForce, Vec3(4, 0, 0));
  EXPECT_EQ(energy.plastDissip, 0.0);
  EXPECT_TRUE(parts::slideOver<true>(c, 3.0, [](double) { return 1.0; }, energy)); // over: the cap given
  EXPECT_DOUBLE_EQ(c.shearForce.x(), 1.0);
  EXPECT_DOUBLE_EQ(energy.plastDissip, 3.0 * 1.0);
}

TEST(NormalDashpotPart, AddsTheDashpotAndNeverPulls)
{
  PartScene p;
  Contact& c = p.c;
  c.cn = 10;
  ContactEnergy energy;
  GivenMotion approaching{2.0};
  EXPECT_DOUBLE_EQ(parts::NormalDashpot::normal<true>(c, nullptr, p.step(), approaching, 100.0, energy), 120.0);
  EXPECT_EQ(c.normalForce, Vec3(0, 0, 120));
  EXPECT_DOUBLE_EQ(energy.viscDamp, 20.0 * 2.0 * dt);
  GivenMotion parting{-20.0}; // the dashpot would pull: no force, the spring's energy released
  EXPECT_EQ(parts::NormalDashpot::normal<true>(c, nullptr, p.step(), parting, 100.0, energy), 0.0);
  EXPECT_EQ(c.normalForce, Vec3::Zero());
  EXPECT_DOUBLE_EQ(energy.viscDamp, 20.0 * 2.0 * dt + 100.0 * 20.0 * dt);
}

TEST(VelocityShearPart, StickingAddsTheDashpotSlidingCapsTheSpring)
{
  PartScene p;
  Contact& c = p.c;
  c.ks = 1e5;
  c.cs = 5;
  c.tanPhi = 0.5;
  c.normalForce = Vec3(0, 0, 100);
  GivenMotion sliding;
  sliding.vs = Vec3(1, 0, 0); // 1e-5 m a step: 1 N more on the spring
  ContactEnergy energy;
  parts::VelocityShear::force<true>(c, nullptr, 100.0, p.step(), sliding, energy);
  EXPECT_DOUBLE_EQ(c.shearForce.x(), 1.0);
  EXPECT_DOUBLE_EQ(c.force.x(), 1.0 + 5.0); // the spring and the dashpot
  EXPECT_DOUBLE_EQ(energy.viscDamp, 5.0 * dt);
  c.shearForce = Vec3(60, 0, 0); // past the cap of 50 N: slides, no dashpot
  parts::VelocityShear::force<true>(c, nullptr, 100.0, p.step(), sliding, energy);
  EXPECT_DOUBLE_EQ(c.shearForce.x(), 50.0);
  EXPECT_EQ(c.force, Vec3(50, 0, 100));
  EXPECT_DOUBLE_EQ(energy.viscDamp, 5.0 * dt);
  // The capped force's work over the increment (50 x 1 N) less the spring's loss (3600 - 2500) / 2.
  EXPECT_NEAR(energy.plastDissip, (50.0 + 550.0) / 1e5, 1e-15);
}

TEST(RollingResistancePart, OpposesTheRelativeRotation)
{
  PartScene p;
  p.scene.bodies.angVel[0] = Vec3(0, 1, 0);
  ContactExtra x;
  x.mR = 0.05;
  GivenMotion arms;
  arms.c1x = Vec3(0, 0, R);
  arms.c2x = Vec3(0, 0, -R);
  ContactEnergy energy;
  const parts::RollingResistance rolling;
  rolling.force<true>(p.c, &x, 100.0, p.step(), arms, energy);
  EXPECT_EQ(x.momentBending, Vec3(0, 0.05 * 100.0, 0)); // on body 2; body 1 the opposite
  EXPECT_DOUBLE_EQ(energy.viscDamp, 5.0 * dt);
  x.mRtype = 2; // times |c1x x w1 - c2x x w2| = R
  rolling.force<false>(p.c, &x, 100.0, p.step(), arms, energy);
  EXPECT_DOUBLE_EQ(x.momentBending.y(), 5.0 * R);
  x.mR = 0;
  rolling.force<false>(p.c, &x, 100.0, p.step(), arms, energy);
  EXPECT_EQ(x.momentBending, Vec3::Zero());
  EXPECT_EQ(rolling.addElastic(1.0, &x), 1.0); // stores nothing
}

TEST(JointSpringPart, ABondPullsUpToItsTensionThenBreaks)
{
  Contact c;
  c.kn = 1e6;
  ContactExtra x;
  x.intactRock = 1;
  x.tensionBroken = x.cohesionBroken = 0;
  x.normalAdhesion = 10;
  ContactEnergy energy;
  parts::JointSpring<true> joint;
  joint.initialOverlapDistance = 1e-5;
  c.penetration = 5e-6; // 5e-6 short of the overlap at rest: pulls
  EXPECT_DOUBLE_EQ(joint.force<false>(c, &x, energy), -5.0);
  c.penetration = -2e-5; // -30 N against a tension of 10 N: breaks
  EXPECT_EQ(joint.force<false>(c, &x, energy), 0.0);
  EXPECT_TRUE(x.tensionBroken && x.cohesionBroken);
  c.penetration = 5e-6; // no bond: never pulls
  EXPECT_EQ(joint.force<false>(c, &x, energy), 0.0);
  const parts::JointSpring<false> plain;
  EXPECT_DOUBLE_EQ(plain.force<false>(c, &x, energy), 5.0);
  c.penetration = -1e-6;
  EXPECT_EQ(plain.force<false>(c, &x, energy), 0.0);
}

TEST(AreaDashpotPart, DampsWithoutTurningTheSpringAround)
{
  PartScene p;
  Contact& c = p.c;
  c.kn = 1e6;
  p.scene.bodies.vel[1] = Vec3(0, 0, -1); // approaching at 1 m/s
  parts::AreaDashpot dashpot;
  ContactEnergy energy;
  EXPECT_EQ(dashpot.normal<true>(c, nullptr, p.step(), GivenMotion{}, 10.0, energy), 10.0);
  EXPECT_EQ(c.normalForce, Vec3(0, 0, 10)); // no damping asked
  dashpot.viscousDamping = 0.5;
  const double m = p.scene.bodies.mass[0] / 2, cn = 0.5 * 2 * std::sqrt(m * c.kn);
  EXPECT_EQ(dashpot.normal<true>(c, nullptr, p.step(), GivenMotion{}, 10.0, energy), 10.0);
  EXPECT_NEAR(c.normalForce.z(), 10.0 + cn, 1e-12 * cn);
  EXPECT_NEAR(energy.viscDamp, cn * dt, 1e-12 * cn * dt);
  p.scene.bodies.vel[1] = Vec3(0, 0, 1e3); // parting fast: the dashpot would pull
  dashpot.normal<false>(c, nullptr, p.step(), GivenMotion{}, 10.0, energy);
  EXPECT_EQ(c.normalForce, Vec3::Zero());
  dashpot.allowViscousAttraction = true;
  dashpot.normal<false>(c, nullptr, p.step(), GivenMotion{}, 10.0, energy);
  EXPECT_LT(c.normalForce.z(), 0);
}

TEST(JointCoulombPart, ABondAddsItsCohesionUntilItBreaks)
{
  PartScene p;
  Contact& c = p.c;
  c.ks = 1e5;
  c.tanPhi = 0.5;
  c.normalForce = Vec3(0, 0, 4); // damped; the spring's is fn = 10
  ContactExtra x;
  x.intactRock = 1;
  x.cohesionBroken = 0;
  x.shearAdhesion = 20;
  ContactEnergy energy;
  parts::JointCoulomb<true> joint;
  auto push = [&](auto& part) {
    c.shearForce.setZero();
    c.shearIncrement = Vec3(-3e-4, 0, 0); // 30 N on the spring
    part.template force<false>(c, &x, 10.0, p.step(), GivenMotion{}, energy);
  };
  push(joint);
  EXPECT_DOUBLE_EQ(c.shearForce.x(), 25.0); // yields at cohesion + fn tan(phi)
  EXPECT_FALSE(x.cohesionBroken);
  joint.allowBreakage = true;
  push(joint);
  EXPECT_DOUBLE_EQ(c.shearForce.x(), 5.0); // broken: friction alone
  EXPECT_TRUE(x.cohesionBroken && x.tensionBroken);
  EXPECT_EQ(c.force, c.normalForce + c.shearForce);
  const parts::JointCoulomb<false> particles; // capped with the damped normal force
  push(particles);
  EXPECT_DOUBLE_EQ(c.shearForce.x(), 2.0);
}

TEST(PartsLaw, TheDeclaredParametersOfItsPartsAreTheLaws)
{
  const auto blocks = makeContactLaw("Law2_SCG_KnKsPBPhys_KnKsPBLaw");
  const std::vector<std::string> names = blocks->parameterNames();
  for (const char* name : {"Knormal", "Kshear", "kn_i", "ks_i", "calContactArea", "useFaceProperties", "cohesionBroken",
                           "tensionBroken", "initialOverlapDistance", "viscousDamping", "allowViscousAttraction",
                           "allowBreakage"})
    EXPECT_NE(std::find(names.begin(), names.end(), name), names.end()) << name;
  EXPECT_EQ(names.size(), 12u);
  blocks->setParameter("Knormal", 5e7); // the physics'
  EXPECT_EQ(blocks->parameter("Knormal"), 5e7);
  blocks->setParameter("allowBreakage", 2); // a yes/no of the tangential part
  EXPECT_EQ(blocks->parameter("allowBreakage"), 1.0);
  EXPECT_EQ(blocks->parameter("viscousDamping"), 0.0);
  try
  {
    blocks->setParameter("viscousDamping", -1);
    FAIL() << "a negative viscousDamping was taken";
  }
  catch (const std::invalid_argument& e)
  {
    EXPECT_NE(std::string(e.what()).find("Ip2_FrictMat_FrictMat_KnKsPBPhys.viscousDamping must be finite and >= 0"),
              std::string::npos)
        << e.what();
  }
  const auto particles = makeContactLaw("Law2_SCG_KnKsPhys_KnKsLaw"); // no rock joints
  EXPECT_THROW(particles->setParameter("allowBreakage", 1), std::invalid_argument);
  EXPECT_THROW(particles->parameter("initialOverlapDistance"), std::invalid_argument);
  const auto cohesive = makeContactLaw("cohesive"); // physics' and moments' flags
  cohesive->setParameter("always_use_moment_law", 1);
  EXPECT_EQ(cohesive->parameter("always_use_moment_law"), 1.0);
  EXPECT_EQ(cohesive->parameter("setCohesionOnNewContacts"), 0.0);
}

TEST(ViscoElasticLaw, RollingResistanceTurnsTheContactStateOn)
{
  auto rollingState = [](const Scene& scene) -> const ContactExtra& {
    const Contact* c = realContact(scene);
    EXPECT_NE(c, nullptr);
    return scene.contacts.extra.at(static_cast<std::size_t>(c - scene.contacts.list.data()));
  };
  Scene scene;
  pair(scene, "viscoelastic", 1e-4);
  scene.bodies.angVel[1] = Vec3(0, 10, 0);
  scene.step();
  EXPECT_TRUE(scene.contacts.extra.empty()); // the plain records
  scene.materials[0].mR = 0.05;
  scene.step();
  ASSERT_EQ(scene.contacts.extra.size(), scene.contacts.list.size());
  EXPECT_EQ(rollingState(scene).mR, 0.0); // made before: no rolling resistance
  EXPECT_EQ(rollingState(scene).momentBending, Vec3::Zero());
  Scene rolling;
  pair(rolling, "viscoelastic", 1e-4);
  rolling.materials[0].mR = 0.05;
  rolling.bodies.angVel[1] = Vec3(0, 10, 0);
  rolling.step();
  EXPECT_DOUBLE_EQ(rollingState(rolling).mR, 0.05); // twice the harmonic mean of 0.05 and 0.05
  EXPECT_LT(rollingState(rolling).momentBending.y(), 0); // the moment on body 2: against its spin
}
