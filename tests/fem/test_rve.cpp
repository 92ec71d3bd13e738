// The C++ RVE on a simple cubic lattice of overlapping spheres: the cell ends at (I + G) H0,
// stress and tangent are dem's, rollback restores the committed state exactly (without a new
// contact detection), bad input throws.
#include "fem/GaussPointRVEs.h"

#include "dem/contact/Collider.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <memory>
#include <stdexcept>
#include <vector>

using namespace talus;

namespace
{
dem::Scene lattice()
{
  dem::Scene s;
  const double a = 0.02, r = 0.0101;
  s.addMaterial(dem::Material{});
  s.periodic = true;
  s.setCellSize(dem::Mat3::Identity() * 3 * a);
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      for (int k = 0; k < 3; ++k)
        s.addSphere(dem::Vec3(a * (i + 0.5), a * (j + 0.5), a * (k + 0.5)), r, 0);
  s.dt = 1e-6;
  return s;
}

fem::Mat3 gradient()
{
  fem::Mat3 g;
  g << -1e-3, 2e-4, 0, 1e-4, 5e-4, 0, 0, -3e-4, 2e-4;
  return g;
}
} // namespace

TEST(RVE, DeformsTheCellToTheImposedGradient)
{
  const dem::Scene source = lattice();
  fem::RVE rve(source, {});
  rve.deform(gradient(), 10);
  const fem::Mat3 expected = (fem::Mat3::Identity() + gradient()) * source.cell.hSize;
  EXPECT_LT((rve.scene().cell.hSize - expected).norm(), 1e-15);
  EXPECT_TRUE(rve.hasTrial());
  EXPECT_EQ(rve.stress(), dem::loveWeberStress(rve.scene()));
  EXPECT_EQ(rve.tangent(), dem::contactStiffnessTangent(rve.scene()));
  EXPECT_LT(rve.stress()(0, 0), 0); // the lattice overlaps: compression
}

TEST(RVE, RollbackRestoresTheCommittedState)
{
  fem::RVE rve(lattice(), {});
  rve.deform(gradient(), 10);
  rve.commit();
  const std::vector<dem::Vec3> pos = rve.scene().bodies.pos;
  const fem::Mat3 h = rve.scene().cell.hSize, stress = rve.stress();
  rve.deform(2 * gradient(), 10);
  EXPECT_NE(rve.scene().bodies.pos, pos);
  rve.rollback();
  EXPECT_EQ(rve.scene().bodies.pos, pos);
  EXPECT_EQ(rve.scene().cell.hSize, h);
  EXPECT_EQ(rve.stress(), stress);
  EXPECT_FALSE(rve.hasTrial());
}

TEST(RVE, RollbackBeforeTheFirstCommitNeedsNoNewDetection)
{
  // The RVE detects its contacts when it is made: Newton iterations of the first load step
  // (deform, rollback, deform, ...) start from a committed list that still matches the
  // collider's references, and give the same state each time.
  fem::RVE rve(lattice(), {});
  const auto& collider = dynamic_cast<const dem::Collider&>(*rve.scene().engines[1]);
  EXPECT_EQ(collider.rebuilds, 1);
  rve.deform(gradient(), 10);
  const std::vector<dem::Vec3> pos = rve.scene().bodies.pos;
  rve.rollback();
  rve.deform(gradient(), 10);
  EXPECT_EQ(rve.scene().bodies.pos, pos);
  rve.deform(2 * gradient(), 10); // restores the committed state first
  EXPECT_EQ(collider.rebuilds, 1);
}

TEST(RVE, RejectsBadInput)
{
  dem::Scene open = lattice();
  open.periodic = false;
  EXPECT_THROW(fem::RVE(open, {}, "open"), std::invalid_argument);
  fem::RVE rve(lattice(), {});
  fem::Mat3 g = gradient();
  g(1, 2) = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THROW(rve.deform(g, 10), std::invalid_argument);
  EXPECT_THROW(rve.deform(-2 * fem::Mat3::Identity(), 10), std::invalid_argument);
  EXPECT_THROW(fem::RVE::load("/nonexistent/rve.h5", {}), std::invalid_argument);
}

TEST(GaussPointRVEs, NamesTheGaussPoint)
{
  std::vector<std::unique_ptr<fem::RVE>> rves;
  for (int i = 0; i < 2; ++i)
    rves.push_back(std::make_unique<fem::RVE>(lattice(), fem::RVEEngines{}));
  fem::GaussPointRVEs points(std::move(rves));
  std::vector<double> grads(18, 0.0);
  grads[9 + 4] = std::numeric_limits<double>::infinity();
  try
  {
    points.deform(grads, 3, 5);
    FAIL() << "no exception";
  }
  catch (const std::invalid_argument& e)
  {
    EXPECT_STREQ(e.what(), "Gauss point 1: displacement gradient is not finite");
  }
  EXPECT_THROW(points.deform(std::vector<double>(27, 0.0), 3, 5), std::invalid_argument);
  grads[13] = 0;
  points.deform(grads, 3, 5);
  std::vector<double> stress(18), tangent(72);
  points.getStressAndTangent(stress, tangent, 3);
  EXPECT_EQ(stress[0], stress[9]); // identical RVEs, identical gradients
}
