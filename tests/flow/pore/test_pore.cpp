// Pore-scale flow (flow/pore/): geometry against analytic values, the pressure solvers against
// each other, flux conservation, and the bad-input errors. The comparison with Yade's FlowEngine
// on the same packing is tests/flow/pore/test_pore.py.
#include "dem/engines/ForceResetter.h"
#include "dem/engines/NewtonIntegrator.h"
#include "flow/pore/FlowCoupling.h"
#include "flow/pore/PoreFlow.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <numeric>
#include <random>
#include <sstream>
#include <stdexcept>
#include <string>

using namespace talus::flow::pore;

namespace
{
/// The spheres of a file of tests/flow/data ("x y z r" lines), numbered from `id` (6 by default:
/// as in Yade, after the six walls).
std::vector<PoreSphere> loadPacking(const std::string& file = "pore_packing.txt", std::int64_t id = 6)
{
  std::ifstream in(std::string(TALUS_FLOW_TEST_DATA) + "/" + file);
  std::vector<PoreSphere> s;
  std::string line;
  while (std::getline(in, line))
  {
    if (line.empty() || line[0] == '#')
      continue;
    std::istringstream ls(line);
    PoreSphere p;
    ls >> p.pos.x() >> p.pos.y() >> p.pos.z() >> p.radius;
    p.id = id++;
    s.push_back(p);
  }
  return s;
}

/// The pores touching ymin or ymax (the imposed pressures of yFlow).
std::vector<char> yImposed(const PoreNetwork& net)
{
  std::vector<char> imposed(net.pores.size(), 0);
  for (int k : {2, 3})
    for (int pi : net.boundaryPores[static_cast<std::size_t>(k)])
      imposed[static_cast<std::size_t>(pi)] = 1;
  return imposed;
}

/// Pressure 1 at ymin, 0 at ymax, no flux elsewhere.
PoreFlow yFlow()
{
  PoreFlow f;
  f.params.bndCondIsPressure = {false, false, true, true, false, false};
  f.params.bndCondValue = {0, 0, 1, 0, 0, 0};
  return f;
}
} // namespace

TEST(PoreGeometry, SolidAngleOfAnOctantIsAnEighthOfTheSphere)
{
  EXPECT_NEAR(solidAngle(Vec3::Zero(), Vec3::UnitX(), Vec3::UnitY(), Vec3::UnitZ()), 4 * M_PI / 8, 1e-14);
  // a small triangle far away: area / distance^2
  const double a = solidAngle(Vec3::Zero(), Vec3(100, 0, 0), Vec3(100, 1, 0), Vec3(100, 0, 1));
  EXPECT_NEAR(a, 0.5 / 1e4, 1e-8);
}

TEST(PoreNetwork, PoresTileTheBoxAndVoidVolumeIsTheBoxMinusTheSpheres)
{
  PoreFlow f = yFlow();
  const auto spheres = loadPacking();
  ASSERT_EQ(spheres.size(), 400u);
  f.build(spheres);
  const PoreNetwork& net = f.network();
  EXPECT_TRUE(net.hiddenSpheres.empty());
  double vol = 0;
  double voidVol = 0;
  for (const Pore& p : net.pores)
  {
    vol += std::abs(p.volume);
    voidVol += p.voidVolume;
  }
  double box = 1;
  for (int c = 0; c < 3; ++c)
    box *= net.boundaries[2 * c + 1].position - net.boundaries[2 * c].position;
  double spheresVol = 0;
  for (const PoreSphere& s : spheres)
    spheresVol += 4.0 / 3.0 * M_PI * std::pow(s.radius, 3);
  // Yade's boundary-cell volumes (prisms to the walls) do not tile the box exactly: the
  // measured gap is below 1 % on this packing (it is 0.67 % in Yade too).
  EXPECT_NEAR(vol / box, 1.0, 0.01);
  // The sphere sectors of the inner pores sum to the sphere volumes; in boundary pores Yade's
  // sector formula is approximate, hence the tolerance.
  EXPECT_NEAR((vol - voidVol) / spheresVol, 1.0, 0.05);
}

TEST(PoreFlowSolve, FluxIsConservedAndBothSolversAgree)
{
  PoreFlow f = yFlow();
  f.build(loadPacking());
  f.solve();
  const double qIn = f.boundaryFlux(2);
  const double qOut = f.boundaryFlux(3);
  EXPECT_LT(qIn, 0);
  EXPECT_NEAR(qIn + qOut, 0.0, 1e-10 * std::abs(qIn));
  EXPECT_TRUE(f.factorized());
  const std::vector<double> pc = f.pressures();

  PoreFlow g = yFlow(); // from zero pressures, not from the Cholesky solution
  g.params.useSolver = 0;
  g.params.tolerance = 1e-10;
  g.build(loadPacking());
  g.solve();
  double maxDiff = 0;
  for (std::size_t i = 0; i < pc.size(); ++i)
    maxDiff = std::max(maxDiff, std::abs(pc[i] - g.pressures()[i]));
  EXPECT_LT(maxDiff, 1e-6);
  EXPECT_GT(g.lastIterations(), 10);
  EXPECT_FALSE(g.factorized());
}

TEST(PoreFlowSolve, FactorIsReusedWhenOnlyPressureValuesChangeAndTheSystemIsLinear)
{
  PoreFlow f = yFlow();
  f.build(loadPacking());
  f.solve();
  const double q1 = f.boundaryFlux(2);
  f.params.bndCondValue[2] = 3.0;
  f.params.bndCondValue[3] = 1.0;
  f.solve();
  EXPECT_TRUE(f.factorized());
  EXPECT_NEAR(f.boundaryFlux(2), 2 * q1, 1e-10 * std::abs(q1));
  // a uniform pressure shift changes nothing: p at a point = shifted
  const double k = f.samplePermeability(2, 3);
  EXPECT_GT(k, 0);
}

TEST(PressureSolver, SymbolicAnalysisIsKeptWhileThePatternIsUnchanged)
{
  PoreFlow f = yFlow();
  f.build(loadPacking());
  const PoreNetwork& net = f.network();
  std::vector<char> imposed = yImposed(net);
  PressureSolver solver;
  std::vector<double> p(net.pores.size(), 0.0);
  for (int pi : net.boundaryPores[2])
    p[static_cast<std::size_t>(pi)] = 1.0;
  solver.setSystem(net, imposed);
  solver.solve(SolverKind::Cholmod, p);
  const std::vector<double> steady = p;
  // a storage term on the diagonal: new values, same pattern -> numeric factorisation only
  const std::vector<double> storage(net.pores.size(), 1e-3);
  solver.setSystem(net, imposed, storage);
  EXPECT_FALSE(solver.factorized());
  std::vector<double> source(net.pores.size());
  for (std::size_t i = 0; i < source.size(); ++i)
    source[i] = storage[i] * steady[i]; // the steady field is a fixed point of the transient step
  solver.solve(SolverKind::Cholmod, p, source);
  EXPECT_EQ(solver.counters().analyses, 1);
  EXPECT_EQ(solver.counters().factorizations, 2);
  for (std::size_t i = 0; i < p.size(); ++i)
    ASSERT_NEAR(p[i], steady[i], 1e-10);
  // Gauss-Seidel on the same shifted system agrees
  std::vector<double> gs(p.size(), 0.0);
  for (int pi : net.boundaryPores[2])
    gs[static_cast<std::size_t>(pi)] = 1.0;
  solver.tolerance = 1e-12;
  solver.solve(SolverKind::GaussSeidel, gs, source);
  for (std::size_t i = 0; i < p.size(); ++i)
    ASSERT_NEAR(gs[i], steady[i], 1e-8);
  // another pattern (one more imposed pore): a new analysis
  imposed[static_cast<std::size_t>(std::find(imposed.begin(), imposed.end(), 0) - imposed.begin())] = 1;
  solver.setSystem(net, imposed);
  solver.solve(SolverKind::Cholmod, p);
  EXPECT_EQ(solver.counters().analyses, 2);
}

namespace
{
/// side^3 spheres on a unit cubic lattice, centres moved and radii drawn (0.3 to 0.4) from a
/// fixed seed.
std::vector<PoreSphere> latticeSpheres(int side)
{
  std::mt19937 random(7);
  std::uniform_real_distribution<double> shift(-0.05, 0.05);
  std::uniform_real_distribution<double> radius(0.3, 0.4);
  std::vector<PoreSphere> s;
  for (int i = 0; i < side; ++i)
    for (int j = 0; j < side; ++j)
      for (int k = 0; k < side; ++k)
      {
        PoreSphere p;
        p.pos = Vec3(i + shift(random), j + shift(random), k + shift(random));
        p.radius = radius(random);
        p.id = static_cast<std::int64_t>(s.size());
        s.push_back(p);
      }
  return s;
}
} // namespace

// A new factor (a remesh, here a new pattern) takes the large blocks the previous one freed,
// instead of fresh pages the kernel faults in one by one; the kept blocks go back to the system
// with the last solver.
TEST(FactorMemory, ANewFactorTakesTheFreedFactorsBlocksAndTheLastSolverReturnsThem)
{
  {
    PoreFlow f = yFlow();
    f.build(latticeSpheres(20)); // 8 000 spheres: a factor of some tens of MB
    const PoreNetwork& net = f.network();
    std::vector<char> imposed = yImposed(net);
    PressureSolver solver;
    solver.setSystem(net, imposed);
    solver.prepare(SolverKind::Cholmod);
    const std::size_t workspace = FactorMemory::keptBytes();
    imposed[static_cast<std::size_t>(std::find(imposed.begin(), imposed.end(), 0) - imposed.begin())] = 1;
    solver.setSystem(net, imposed); // another pattern: the factor is freed
    const std::size_t freed = FactorMemory::keptBytes();
    EXPECT_GT(freed, workspace + 2 * FactorMemory::kLargeBlock);
    solver.prepare(SolverKind::Cholmod);
    EXPECT_LE(FactorMemory::keptBytes(), workspace + FactorMemory::kLargeBlock);
    EXPECT_EQ(solver.counters().analyses, 2);
  }
  EXPECT_EQ(FactorMemory::keptBytes(), 0U);
}

namespace
{
/// The pressures of `net` with CHOLMOD, `imposed` pores held at 1 (the first) or 0 (the others),
/// the source `source`, with the factor simplicial below `supernodalFrom` unknowns.
std::vector<double> choleskyPressures(const PoreNetwork& net, const std::vector<char>& imposed,
                                      const std::vector<double>& source, int supernodalFrom)
{
  PressureSolver solver;
  solver.supernodalFrom = supernodalFrom;
  std::vector<double> p(net.pores.size(), 0.0);
  p[static_cast<std::size_t>(std::find(imposed.begin(), imposed.end(), 1) - imposed.begin())] = 1.0;
  solver.setSystem(net, imposed);
  solver.solve(SolverKind::Cholmod, p, source);
  return p;
}

/// Largest |a - b| relative to the largest |a|.
double relativeDifference(const std::vector<double>& a, const std::vector<double>& b)
{
  double diff = 0;
  double scale = 0;
  for (std::size_t i = 0; i < a.size(); ++i)
  {
    diff = std::max(diff, std::abs(a[i] - b[i]));
    scale = std::max(scale, std::abs(a[i]));
  }
  return diff / scale;
}
} // namespace

// The supernodal factor is given the upper triangle of the matrix, the simplicial one the lower
// (PressureSolver::factorize): both kinds on one system must give the same pressures, on a box
// network and on a periodic one (couplings across the period; this cell has no pore meeting a
// neighbour twice or its own image). Giving the supernodal factor the lower triangle's stype
// with the upper triangle's entries fails here by 0.89 and 0.55.
TEST(PressureSolver, SupernodalAndSimplicialFactorsGiveTheSamePressures)
{
  PoreFlow box = yFlow();
  box.build(loadPacking());
  const PoreNetwork& net = box.network();
  const std::vector<char> imposed = yImposed(net);
  const std::vector<double> none;
  const std::vector<double> simplicial = choleskyPressures(net, imposed, none, 1 << 30);
  const std::vector<double> supernodal = choleskyPressures(net, imposed, none, 0);
  EXPECT_LT(relativeDifference(simplicial, supernodal), 1e-12);
  // a wrong triangle or a lost entry is far above round-off: the pressures are O(1)
  EXPECT_GT(*std::max_element(simplicial.begin(), simplicial.end()), 0.5);

  PoreFlow cell;
  cell.params.periodic = true;
  cell.params.hasBoundary = {false, false, false, false, false, false};
  cell.params.cellSize = Vec3::Ones();
  cell.params.duplicateThreshold = 0.25;
  const std::vector<PoreSphere> spheres = loadPacking("pore_periodic_packing.txt", 0);
  ASSERT_EQ(spheres.size(), 300U);
  cell.build(spheres);
  const PoreNetwork& periodic = cell.network();
  // one pore held, a source everywhere else (flowing out through that pore)
  std::vector<char> held(periodic.pores.size(), 0);
  held[0] = 1;
  std::vector<double> source(periodic.pores.size());
  for (std::size_t i = 0; i < source.size(); ++i)
    source[i] = std::sin(static_cast<double>(i));
  const std::vector<double> a = choleskyPressures(periodic, held, source, 1 << 30);
  const std::vector<double> b = choleskyPressures(periodic, held, source, 0);
  EXPECT_LT(relativeDifference(a, b), 1e-12);
}

// The solver numbers its rows along the network's curve (PoreNetwork::curveOrder), the pores
// keeping their ids: the Cholesky factor is ordered from the pores' sequence (NestedDissection),
// so the pressures are the same bits as with the rows in pore order; the multigrid's differ by
// the round-off of its tolerance. Also: the curve is a permutation of the pores, not theirs.
TEST(PressureSolver, RowsAlongTheCurveGiveThePressuresOfRowsInPoreOrder)
{
  PoreFlow f = yFlow();
  f.build(latticeSpheres(12));
  const PoreNetwork& net = f.network();
  std::vector<int> sorted = net.curveOrder;
  std::sort(sorted.begin(), sorted.end());
  std::vector<int> ids(net.pores.size());
  std::iota(ids.begin(), ids.end(), 0);
  ASSERT_EQ(sorted, ids);
  EXPECT_NE(net.curveOrder, ids);
  PoreNetwork inPoreOrder = net;
  inPoreOrder.curveOrder.clear();
  const std::vector<char> imposed = yImposed(net);
  const auto pressures = [&](const PoreNetwork& n, SolverKind kind) {
    PressureSolver solver;
    solver.multigridTolerance = 1e-10; // round-off of the tolerance well below the 1e-8 compared
    std::vector<double> p(n.pores.size(), 0.0);
    for (int pi : n.boundaryPores[2])
      p[static_cast<std::size_t>(pi)] = 1.0;
    solver.setSystem(n, imposed);
    solver.solve(kind, p);
    return p;
  };
  EXPECT_EQ(pressures(net, SolverKind::Cholmod), pressures(inPoreOrder, SolverKind::Cholmod));
  EXPECT_LT(relativeDifference(pressures(net, SolverKind::Multigrid), pressures(inPoreOrder, SolverKind::Multigrid)),
            1e-8);
}

TEST(PoreFlowErrors, FewerThanFourSpheresNaNAndOutside)
{
  PoreFlow f = yFlow();
  std::vector<PoreSphere> three = {{Vec3(0, 0, 0), 0.1, 7}, {Vec3(1, 0, 0), 0.1, 8}, {Vec3(0, 1, 0), 0.1, 9}};
  EXPECT_THROW(f.build(three), std::invalid_argument);
  auto s = loadPacking();
  s[10].pos.x() = std::nan("");
  try
  {
    f.build(s);
    FAIL() << "NaN position accepted";
  }
  catch (const std::invalid_argument& e)
  {
    EXPECT_NE(std::string(e.what()).find("body 16"), std::string::npos) << e.what();
  }
  s = loadPacking();
  f.params.boundaryUseMaxMin[1] = false;
  f.params.wallPosition[1] = 0.5; // xmax wall through the packing
  EXPECT_THROW(f.build(s), std::invalid_argument);
}

TEST(PoreFlowErrors, HiddenSphereIsReportedByBodyId)
{
  PoreFlow f = yFlow();
  auto s = loadPacking();
  PoreSphere hidden = s[0];
  hidden.radius = 0.01 * s[0].radius;
  hidden.pos += Vec3(1e-3 * s[0].radius, 0, 0);
  hidden.id = 9999;
  s.push_back(hidden);
  f.build(s);
  ASSERT_EQ(f.network().hiddenSpheres.size(), 1u);
  EXPECT_EQ(f.network().hiddenSpheres[0], 9999);
}

TEST(PoreFlowErrors, NoImposedPressureNeedsABalancedVolumeChange)
{
  // nothing fixes the level: the fluid at rest is at pZero; a net volume change has no solution
  PoreFlow f;
  f.params.pZero = 3.5;
  f.build(loadPacking());
  f.solve();
  for (const double p : f.pressures())
    ASSERT_EQ(p, 3.5);
  f.setExtraVolumeRates(std::vector<double>(f.network().pores.size(), 1e-9));
  try
  {
    f.solve();
    FAIL() << "an incompressible fluid took a net volume change in a closed network";
  }
  catch (const std::invalid_argument& e)
  {
    EXPECT_NE(std::string(e.what()).find("bndCondIsPressure"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("fluidBulkModulus > 0"), std::string::npos) << e.what();
  }
}

TEST(PoreFlowErrors, PoreConnectedToNoImposedPressureIsNamed)
{
  // A pore whose throats all have zero conductance is a group of pores (of one) connected to
  // no imposed pressure: the factorisation (simplicial for this size) reports it by its index,
  // and so does BoomerAMG's set-up (its smoother would leave the pore at its initial pressure).
  PoreFlow f = yFlow();
  f.build(loadPacking());
  PoreNetwork net = f.network();
  std::vector<char> imposed(net.pores.size(), 0);
  for (int k : {2, 3})
    for (int pi : net.boundaryPores[static_cast<std::size_t>(k)])
      imposed[static_cast<std::size_t>(pi)] = 1;
  const auto lonely = static_cast<std::size_t>(std::find(imposed.begin(), imposed.end(), 0) - imposed.begin());
  for (int t : net.pores[lonely].throats)
    if (t >= 0)
      net.throats[static_cast<std::size_t>(t)].conductance = 0;
  for (const SolverKind kind : {SolverKind::Cholmod, SolverKind::BoomerAmg})
  {
    PressureSolver solver;
    solver.setSystem(net, imposed);
    std::vector<double> p(net.pores.size(), 0.0);
    try
    {
      solver.solve(kind, p);
      FAIL() << "isolated pore accepted by solver " << static_cast<int>(kind);
    }
    catch (const std::runtime_error& e)
    {
      EXPECT_NE(std::string(e.what()).find("pore " + std::to_string(lonely) + " "), std::string::npos) << e.what();
    }
  }
}

TEST(FlowCoupling, FluidForcesReachTheParticlesAndBalanceThePressureDrop)
{
  // The packing as fixed spheres of a DEM scene; the coupling reads them through the exchange
  // interface and adds the fluid forces each step.
  using namespace talus::dem;
  Scene scene;
  scene.addMaterial(Material{});
  const auto spheres = loadPacking();
  for (const PoreSphere& s : spheres)
  {
    const BodyId id = scene.addSphere(s.pos, s.radius, 0);
    scene.setDynamic(id, false);
  }
  scene.engines = {std::make_shared<ForceResetter>(), std::make_shared<NewtonIntegrator>()};
  scene.dt = 1e-6;
  auto flow = std::make_shared<PoreFlow>(yFlow());
  auto coupling = std::make_shared<FlowCoupling>(ParticleExchange(scene), flow);
  coupling->meshUpdateInterval = 5;
  FlowCoupling::attach(coupling);
  for (int k = 0; k < 6; ++k)
    scene.step();
  EXPECT_EQ(coupling->rebuilds(), 2);
  Vec3 total = Vec3::Zero();
  for (const Vec3& f : coupling->forces())
    total += f;
  // Every closed pore pushes its walls with zero net force, so the solids (spheres and no-flux
  // walls) carry exactly what the two pressure boundaries receive, dP times their area.
  const std::vector<Vec3> all = flow->vertexForces();
  Vec3 solids = total;
  for (int k : {0, 1, 4, 5})
    solids += all[static_cast<std::size_t>(k)];
  // not to round-off: the sphere-edge overlap term S0 and the walls' projected facets close the
  // pores only approximately (measured 6e-6 relative here)
  EXPECT_NEAR((solids + all[2] + all[3]).norm(), 0.0, 1e-4 * solids.norm());
  const PoreNetwork& net = flow->network();
  const double area = (net.boundaries[1].position - net.boundaries[0].position) *
                      (net.boundaries[5].position - net.boundaries[4].position);
  EXPECT_NEAR(solids.y() / (1.0 * area), 1.0, 0.01) << "solids " << solids.transpose();
  std::printf("fluid force on solids / (dP A) = %.6f, on spheres only %.6f, inlet %.6f\n", solids.y() / area,
              total.y() / area, all[2].y() / area);
  // the forces were added to the scene's step forces (ForceResetter clears them each step)
  ParticleExchange ex(scene);
  EXPECT_NEAR((ex.stepForces()[3] - coupling->forces()[3]).norm(), 0.0, 1e-15);
}
