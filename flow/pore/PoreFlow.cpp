#include "flow/pore/PoreFlow.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

namespace talus::flow::pore
{
const PoreNetwork& PoreFlow::network() const
{
  if (!net_)
    throw std::logic_error("FlowEngine: no pore network yet (triangulate first)");
  return *net_;
}

std::array<Boundary, kBoundaries> PoreFlow::boundaries(const std::vector<PoreSphere>& spheres) const
{
  std::array<Boundary, kBoundaries> b = boundingBoxBoundaries(spheres);
  for (int k = 0; k < kBoundaries; ++k)
  {
    if (!params.boundaryUseMaxMin[static_cast<std::size_t>(k)])
      b[static_cast<std::size_t>(k)].position = params.wallPosition[static_cast<std::size_t>(k)];
    b[static_cast<std::size_t>(k)].imposedPressure = params.bndCondIsPressure[static_cast<std::size_t>(k)];
    b[static_cast<std::size_t>(k)].value = params.bndCondValue[static_cast<std::size_t>(k)];
  }
  return b;
}

Vec3 interiorPoint(const PoreNetwork& net, const Pore& pore)
{
  Vec3 real = Vec3::Zero();
  int nReal = 0;
  for (int v : pore.vertices)
    if (!net.vertices[static_cast<std::size_t>(v)].fictitious)
    {
      real += net.vertices[static_cast<std::size_t>(v)].pos;
      ++nReal;
    }
  if (nReal == 0) // four walls: no sphere to place it by
    return Vec3::Constant(std::numeric_limits<double>::quiet_NaN());
  real /= nReal;
  Vec3 sum = Vec3::Zero();
  for (int v : pore.vertices)
  {
    const Vertex& vx = net.vertices[static_cast<std::size_t>(v)];
    if (vx.fictitious)
    {
      const Boundary& b = net.boundaries[static_cast<std::size_t>(vx.id)];
      Vec3 q = real;
      q[b.coordinate] = b.position;
      sum += q;
    }
    else
      sum += vx.pos;
  }
  return sum / 4;
}

namespace
{
/// The pore containing x, -1 outside the box (the triangulation itself extends far beyond it,
/// to the fictitious boundary spheres).
int locateInBox(const PoreNetwork& net, const Vec3& x)
{
  for (const Boundary& b : net.boundaries)
    if ((x[b.coordinate] - b.position) * b.normal[b.coordinate] < 0)
      return -1;
  return locatePore(net, x);
}
/// Whether two alphaBound values give the same mesh (every negative value: none).
bool sameAlphaBound(double a, double b)
{
  return (a < 0 && b < 0) || a == b;
}
} // namespace

void PoreFlow::build(const std::vector<PoreSphere>& spheres)
{
  // on bad input the old network stays
  if (params.periodic && params.alphaBound >= 0)
    throw std::invalid_argument("FlowEngine.alphaBound: the alpha-shape boundary needs a box network, not a periodic "
                                "one (set alphaBound < 0)");
  if (std::isnan(params.alphaBound))
    throw std::invalid_argument("FlowEngine.alphaBound must be a number (negative: no alpha-shape boundary)");
  if (params.concurrentTriangulation && params.yadeInsertionOrder && !params.periodic && params.alphaBound < 0)
    throw std::invalid_argument("FlowEngine.concurrentTriangulation needs yadeInsertionOrder=False (the threads "
                                "insert the spheres in no fixed order, Yade's is one by one)");
  const InsertionOrder order = params.yadeInsertionOrder ? InsertionOrder::Yade : InsertionOrder::Sorted;
  AlphaBoundary alpha;
  PoreNetwork fresh = params.periodic ? triangulatePeriodic(spheres, boundaries(spheres), params.hasBoundary,
                                                            params.cellSize, params.duplicateThreshold, order)
                      : params.alphaBound >= 0 ? triangulateAlphaShape(spheres, params.alphaBound, alpha)
                                               : triangulate(spheres, boundaries(spheres), order,
                                                             params.concurrentTriangulation);
  std::vector<double> p = carriedPressures(fresh);
  net_ = std::move(fresh);
  p_ = std::move(p);
  alpha_ = std::move(alpha);
  alphaBuilt_ = params.alphaBound;
  lubricationMeshed_ = false;
  const PoreNetwork& net = *net_;
  dv_.assign(net.pores.size(), 0.0);
  extraDv_.clear();
  voidsStale_ = false;
  for (PointPressure& f : fluxPoints_)
    f.pore = -1;
  maxStrain_ = 0;
  inverted_ = 0;
  computeHydraulics();
  // the mesh's volumes before the system is set: its storage term uses the void volumes
  meshVolume_.resize(net.pores.size());
  meshVoidVolume_.resize(net.pores.size());
  for (std::size_t i = 0; i < net.pores.size(); ++i)
  {
    meshVolume_[i] = net.pores[i].volume;
    meshVoidVolume_[i] = net.pores[i].voidVolume;
  }
  applyBoundaryTypes();
}

std::vector<double> PoreFlow::carriedPressures(const PoreNetwork& fresh) const
{
  std::vector<double> p(fresh.pores.size(), params.pZero);
  if (!net_ || net_->pores.empty())
    return p;
  for (std::size_t i = 0; i < fresh.pores.size(); ++i)
  {
    const Vec3 x = interiorPoint(fresh, fresh.pores[i]);
    Vec3i period;
    // the search starts beside one of the pore's spheres (the boundaries are vertices 0-5) as
    // the old network had it, where the new pore's point usually is: a short walk (a sphere
    // list that changed only makes it longer)
    const auto& v = fresh.pores[i].vertices;
    int near = cellAtVertex(*net_, *std::max_element(v.begin(), v.end()));
    const int at = x.allFinite() ? locatePore(*net_, x, &period, &near) : -1;
    if (at >= 0)
      p[i] = p_[static_cast<std::size_t>(at)] + pressureJump(period);
  }
  return p;
}

std::unique_ptr<PoreFlow> PoreFlow::detachedCopy() const
{
  auto copy = std::make_unique<PoreFlow>();
  copy->params = params;
  copy->points_ = points_;
  copy->fluxPoints_ = fluxPoints_;
  copy->dt_ = dt_;
  return copy;
}

void PoreFlow::prepareSolver()
{
  // an incompressible fluid keeps the matrix until the next mesh: factorise it now; a
  // compressible one rebuilds it at every solve anyway
  if (params.useSolver != 0 && params.fluidBulkModulus <= 0)
    solver_.prepare(static_cast<SolverKind>(params.useSolver));
}

void PoreFlow::adopt(std::unique_ptr<PoreFlow> fresh, const std::vector<Vec3>& spherePositions,
                     const std::array<double, kBoundaries>& boundaryPositions)
{
  if (!fresh || !fresh->net_)
    throw std::logic_error("FlowEngine: no background network to adopt");
  // what changed here since the copy was taken wins: parameters, time step, imposed points
  const bool samePoints =
      fresh->points_.size() == points_.size() &&
      std::equal(points_.begin(), points_.end(), fresh->points_.begin(),
                 [](const PointPressure& a, const PointPressure& b) { return a.pos == b.pos; });
  std::vector<int> located(points_.size(), -1);
  if (samePoints)
    for (std::size_t n = 0; n < points_.size(); ++n)
      located[n] = fresh->points_[n].pore;
  fresh->points_ = points_;
  for (std::size_t n = 0; n < points_.size(); ++n)
    fresh->points_[n].pore = located[n];
  fresh->pointsChanged_ = fresh->pointsChanged_ || !samePoints;
  fresh->fluxPoints_ = fluxPoints_;
  for (PointPressure& f : fresh->fluxPoints_)
    f.pore = -1;
  fresh->params = params;
  fresh->dt_ = dt_;
  fresh->p_ = carriedPressures(*fresh->net_);
  fresh->solver_.addCounters(solver_.counters());
  // the spheres have moved since the snapshot: bring the mesh to where they are now, without a
  // volume change source (that motion happened while the old mesh gave the sources)
  fresh->placeVertices(spherePositions, boundaryPositions);
  std::fill(fresh->dv_.begin(), fresh->dv_.end(), 0.0);
  // the lubrication springs' loads go on to the new pairs
  fresh->lubrication_ = std::move(lubrication_);
  fresh->lubricationMeshed_ = false;
  *this = std::move(*fresh);
}

void PoreFlow::computeViscousForces(const std::vector<Vec3>& velocities, const std::vector<Vec3>& angularVelocities,
                                    double dt)
{
  if (!params.any())
    throw std::invalid_argument("FlowEngine: set viscousShear, shearLubrication or normalLubrication to compute "
                                "viscous forces between the spheres");
  const PoreNetwork& net = network();
  if (!lubricationMeshed_)
  {
    lubrication_.setNetwork(net);
    lubricationMeshed_ = true;
  }
  lubrication_.compute(net, params, params.viscosity, velocities, angularVelocities, dt);
}

void PoreFlow::updateVoidVolumes()
{
  if (!voidsStale_)
    return;
  updatePoreVolumes(*net_, true);
  voidsStale_ = false;
}

void PoreFlow::setTimeStep(double dt)
{
  if (!(dt > 0) || !std::isfinite(dt))
    throw std::invalid_argument("FlowEngine: the time step must be positive, got " + std::to_string(dt));
  dt_ = dt;
}

void PoreFlow::moveVertices(const std::vector<Vec3>& spherePositions,
                            const std::array<double, kBoundaries>& boundaryPositions, double dt)
{
  if (!net_)
    throw std::logic_error("FlowEngine: no pore network yet (triangulate first)");
  if (!(dt > 0) || !std::isfinite(dt))
    throw std::invalid_argument("FlowEngine: the time step must be positive, got " + std::to_string(dt));
  std::vector<double> before(net_->pores.size());
  for (std::size_t i = 0; i < before.size(); ++i)
    before[i] = net_->pores[i].volume;
  placeVertices(spherePositions, boundaryPositions);
  setTimeStep(dt);
  for (std::size_t i = 0; i < before.size(); ++i)
  {
    // the sign of the mesh volume orients the pore (Yade's volumeSign)
    const double sign = meshVolume_[i] < 0 ? -1.0 : 1.0;
    dv_[i] = sign * (net_->pores[i].volume - before[i]) / dt;
  }
}

void PoreFlow::setExtraVolumeRates(std::vector<double> rates)
{
  if (!net_ || rates.size() != net_->pores.size())
    throw std::invalid_argument("FlowEngine: " + std::to_string(rates.size()) + " extra volume rates for " +
                                std::to_string(net_ ? net_->pores.size() : 0) + " pores");
  for (const double r : rates)
    if (!std::isfinite(r))
      throw std::invalid_argument("FlowEngine: a non-finite extra volume rate");
  extraDv_ = std::move(rates);
}

void PoreFlow::placeVertices(const std::vector<Vec3>& spherePositions,
                             const std::array<double, kBoundaries>& boundaryPositions)
{
  if (!net_)
    throw std::logic_error("FlowEngine: no pore network yet (triangulate first)");
  PoreNetwork& net = *net_;
  if (spherePositions.size() != net.sphereCount())
    throw std::invalid_argument("FlowEngine: " + std::to_string(spherePositions.size()) + " positions for " +
                                std::to_string(net.sphereCount()) + " spheres of the pore network");
  // everything is checked before anything moves: a refused call leaves the network as it was
  for (std::size_t i = 0; i < spherePositions.size(); ++i)
    if (!spherePositions[i].allFinite())
      throw std::invalid_argument("FlowEngine: non-finite position of body " +
                                  std::to_string(net.vertices[kBoundaries + i].id));
  for (int k = 0; k < kBoundaries; ++k)
    if (!std::isfinite(boundaryPositions[static_cast<std::size_t>(k)]))
      throw std::invalid_argument("FlowEngine: non-finite position of boundary " + std::to_string(k));
  // nothing moved (a static packing): the volumes, the strain and the inverted pores are those
  // computed already
  bool moved = net.periodic && net.cellSize != params.cellSize;
  for (std::size_t i = 0; i < spherePositions.size() && !moved; ++i)
    moved = net.vertices[kBoundaries + i].pos !=
            (net.periodic ? Vec3(spherePositions[i] - net.shift(net.wrap[i])) : spherePositions[i]);
  for (int k = 0; k < kBoundaries && !moved; ++k)
    moved = net.boundaries[static_cast<std::size_t>(k)].position != boundaryPositions[static_cast<std::size_t>(k)];
  if (!moved)
    return;
  if (net.periodic)
    net.cellSize = params.cellSize; // the cell may deform between remeshes
  for (std::size_t i = 0; i < spherePositions.size(); ++i)
    net.vertices[kBoundaries + i].pos = net.periodic ? Vec3(spherePositions[i] - net.shift(net.wrap[i])) : spherePositions[i];
  for (std::size_t v = kBoundaries + net.nSpheres; v < net.vertices.size(); ++v)
  {
    Vertex& image = net.vertices[v];
    if (image.image >= 0) // alpha vertices stay where the mesh put them
      image.pos = net.vertices[static_cast<std::size_t>(image.image)].pos + net.shift(image.period);
  }
  for (int k = 0; k < kBoundaries; ++k)
    net.boundaries[static_cast<std::size_t>(k)].position = boundaryPositions[static_cast<std::size_t>(k)];
  // void volumes (the costly sphere sectors) are recomputed only when asked for
  updatePoreVolumes(net, false);
  voidsStale_ = true;
  maxStrain_ = 0;
  inverted_ = 0;
  for (std::size_t i = 0; i < net.pores.size(); ++i)
  {
    const double v = net.pores[i].volume;
    const double sign = meshVolume_[i] < 0 ? -1.0 : 1.0;
    if (sign * v <= 0)
      ++inverted_;
    maxStrain_ = std::max(maxStrain_, std::abs(v - meshVolume_[i]) / std::abs(meshVolume_[i]));
  }
  if (inverted_ > 0)
    maxStrain_ = std::numeric_limits<double>::infinity();
}

std::vector<double> PoreFlow::storage() const
{
  if (params.fluidBulkModulus <= 0)
    return {};
  if (!(dt_ > 0))
    throw std::invalid_argument("FlowEngine: a compressible fluid (fluidBulkModulus > 0) needs a time step "
                                "(run it as an engine, or setTimeStep / moveVertices)");
  // the void volumes of the mesh, as Yade (invVoidVolume is set at meshing only): between
  // remeshes they change by the pore strain, a second-order effect on the storage term
  std::vector<double> c(net_->pores.size());
  for (std::size_t i = 0; i < c.size(); ++i)
    c[i] = std::max(meshVoidVolume_[i], 0.0) / (params.fluidBulkModulus * dt_);
  return c;
}

void PoreFlow::updateConductances()
{
  computeHydraulics();
  applyBoundaryTypes();
}

void PoreFlow::computeHydraulics()
{
  if (!net_)
    throw std::logic_error("FlowEngine: no pore network yet (triangulate first)");
  PoreNetwork& net = *net_;
  for (int k = 0; k < kBoundaries; ++k)
    net.boundaries[static_cast<std::size_t>(k)].imposedPressure = params.bndCondIsPressure[static_cast<std::size_t>(k)];
  computeGeometry(net, params.slipBoundary);
  globalK_ = computeConductances(net, params, alpha_.exteriorPores);
  computeUnitForces();
}

void PoreFlow::computeUnitForces()
{
  // the fluid area of a facet shared by the solid surface of each vertex in the throat
  std::vector<std::array<double, 3>> shares(net_->throats.size(), {0.0, 0.0, 0.0});
  for (std::size_t t = 0; t < shares.size(); ++t)
    if (const Throat& throat = net_->throats[t]; throat.solidSurface > 0)
      for (std::size_t y = 0; y < 3; ++y)
        shares[t][y] = throat.solidSurfaces[y] / throat.solidSurface;
  unitForces_ = unitForceVectors(*net_, shares);
}

std::vector<std::array<Vec3, 4>> unitForceVectors(const PoreNetwork& net, const std::vector<std::array<double, 3>>& shares)
{
  constexpr std::size_t kPrefetchAhead = 16;
  std::vector<std::array<Vec3, 4>> unitForces(net.pores.size(), {Vec3::Zero(), Vec3::Zero(), Vec3::Zero(), Vec3::Zero()});
  for (std::size_t ti = 0; ti < net.throats.size(); ++ti)
  {
    if (ti + kPrefetchAhead < net.throats.size())
    {
      // the second pore of a throat is anywhere in the arrays (its first one is near the last
      // throat's): fetch its rows a few throats ahead instead of waiting for them
      const auto ahead = static_cast<std::size_t>(net.throats[ti + kPrefetchAhead].pores[1]);
      __builtin_prefetch(&unitForces[ahead], 1);
      __builtin_prefetch(reinterpret_cast<const char*>(&unitForces[ahead]) + 64, 1);
      __builtin_prefetch(&net.pores[ahead].vertices);
    }
    const Throat& t = net.throats[ti];
    if (t.area <= 0)
      continue;
    for (int side = 0; side < 2; ++side)
    {
      const auto c = static_cast<std::size_t>(t.pores[static_cast<std::size_t>(side)]);
      const Pore& pore = net.pores[c];
      // local index in this pore of each facet vertex (t.vertices are in pores[0]'s frame; the
      // pore's vertex opposite the facet is the one left out), found once per side: looking
      // them up inside the loops below made this function 5 % of a 1 000-sphere remesh
      std::array<std::size_t, 3> local{};
      for (std::size_t y = 0; y < 3; ++y)
        local[y] = side == 1 ? static_cast<std::size_t>(t.mirrorLocal[y])
                             : static_cast<std::size_t>(std::find(pore.vertices.begin(), pore.vertices.end(), t.vertices[y]) -
                                                        pore.vertices.begin());
      const std::size_t opposite = 6 - local[0] - local[1] - local[2];
      // the facet vector pointing away from the other pore, as Yade orients it per cell
      const Vec3 s = side == 0 ? t.facetVector : Vec3(-t.facetVector);
      const Vec3 normal = s / t.area;
      if (const Vertex& opp = net.vertices[static_cast<std::size_t>(pore.vertices[opposite])]; opp.fictitious)
      {
        // the facet facing a wall pushes the wall with its projected area
        const Boundary& b = net.boundaries[static_cast<std::size_t>(opp.id)];
        unitForces[c][opposite] -= std::abs(s[b.coordinate]) * b.normal;
      }
      const Vec3 fluidArea = -s * (t.fluidArea / t.area);
      for (std::size_t y = 0; y < 3; ++y)
      {
        const std::size_t k = local[y];
        unitForces[c][k] += fluidArea * shares[ti][y];
        if (!net.vertices[static_cast<std::size_t>(t.vertices[y])].fictitious)
          unitForces[c][k] -= normal * t.crossSections[y];
      }
    }
  }
  return unitForces;
}

std::vector<Vec3> PoreFlow::vertexForces() const
{
  const PoreNetwork& net = network();
  std::vector<Vec3> f(net.vertices.size(), Vec3::Zero());
  for (std::size_t c = 0; c < net.pores.size(); ++c)
    for (std::size_t k = 0; k < 4; ++k)
    {
      // an image vertex takes the pressure of the pore as seen from the real sphere (Yade's
      // unshiftedP), so that all the pores around a sphere use one frame
      const auto v = static_cast<std::size_t>(net.pores[c].vertices[k]);
      f[v] += (p_[c] - pressureJump(net.vertices[v].period)) * unitForces_[c][k];
    }
  // images pass their force to the sphere they copy
  for (std::size_t v = kBoundaries + net.nSpheres; v < net.vertices.size(); ++v)
    if (net.vertices[v].image >= 0)
      f[static_cast<std::size_t>(net.vertices[v].image)] += f[v];
  f.resize(kBoundaries + net.nSpheres); // alpha vertices are no bodies
  if (alphaBuilt_ >= 0)
    std::fill(f.begin(), f.begin() + kBoundaries, Vec3::Zero()); // the box is no boundary then
  return f;
}

void PoreFlow::applyBoundaryTypes()
{
  // As Yade's initializePressure: every pore touching a pressure boundary takes its value; a
  // pore touching two takes the later one in the order xmin .. zmax.
  imposed_.assign(net_->pores.size(), 0);
  if (!sameAlphaBound(alphaBuilt_, params.alphaBound))
    throw std::invalid_argument("FlowEngine.alphaBound changed since the triangulation: triangulate again (the alpha "
                                "vertices are part of the mesh)");
  if (params.alphaBound >= 0)
    imposed_ = alpha_.exteriorPores; // the alpha shape replaces the box: its conditions do not apply
  else
    for (int k = 0; k < kBoundaries; ++k)
      if (params.bndCondIsPressure[static_cast<std::size_t>(k)])
        for (int pi : net_->boundaryPores[static_cast<std::size_t>(k)])
          imposed_[static_cast<std::size_t>(pi)] = 1;
  for (std::size_t n = 0; n < points_.size(); ++n)
  {
    points_[n].pore = locateInBox(*net_, points_[n].pos);
    if (points_[n].pore < 0)
      throw std::invalid_argument("imposePressure: point " + std::to_string(n) + " is outside the pore network");
    imposed_[static_cast<std::size_t>(points_[n].pore)] = 1;
  }
  reference_ = params.fluidBulkModulus <= 0 && std::find(imposed_.begin(), imposed_.end(), 1) == imposed_.end() &&
               !imposed_.empty();
  if (reference_)
    imposed_[0] = 1;
  builtTypes_ = params.bndCondIsPressure;
  pointsChanged_ = false;
  // before the first time step is known (a standalone build) the storage term waits for solve()
  storageInMatrix_ = params.fluidBulkModulus > 0 && dt_ > 0;
  solver_.setSystem(*net_, imposed_, storageInMatrix_ ? storage() : std::vector<double>{});
}

void PoreFlow::solve()
{
  if (!net_)
    throw std::logic_error("FlowEngine: no pore network yet (triangulate first)");
  if (params.useSolver != 0 && params.useSolver != 3 && params.useSolver != 4 && params.useSolver != 5)
    throw std::invalid_argument("FlowEngine.useSolver must be 0 (Gauss-Seidel) or 3 (CHOLMOD), or Talus's 4 "
                                "(multigrid) or 5 (hypre's BoomerAMG), got " +
                                std::to_string(params.useSolver));
  if (params.fluidBulkModulus < 0 || !std::isfinite(params.fluidBulkModulus))
    throw std::invalid_argument("FlowEngine.fluidBulkModulus must be >= 0 (0: incompressible)");
  const bool compressible = params.fluidBulkModulus > 0;
  if (builtTypes_ != params.bndCondIsPressure || !sameAlphaBound(alphaBuilt_, params.alphaBound))
    updateConductances(); // (a changed alphaBound is refused there: it needs a new mesh) // boundary types enter the hydraulic radii and the matrix
  else if (pointsChanged_ || compressible || storageInMatrix_)
    applyBoundaryTypes(); // the storage term follows the void volumes and dt (same pattern: the
                          // symbolic analysis is kept, only the numeric factor is redone)
  // source: fluid expelled by shrinking pores, plus the storage of the last pressures
  std::vector<double> source(p_.size());
  const std::vector<double> c = compressible ? storage() : std::vector<double>{};
  for (std::size_t i = 0; i < source.size(); ++i)
    source[i] = -dv_[i] - (extraDv_.empty() ? 0.0 : extraDv_[i]) + (compressible ? c[i] * p_[i] : 0.0);
  for (std::size_t n = 0; n < fluxPoints_.size(); ++n)
  {
    PointPressure& f = fluxPoints_[n];
    if (f.pore < 0)
      f.pore = locateInBox(*net_, f.pos);
    if (f.pore < 0)
      throw std::invalid_argument("imposeFlux: point " + std::to_string(n) + " is outside the pore network");
    source[static_cast<std::size_t>(f.pore)] -= f.value;
  }
  if (params.alphaBound >= 0)
  {
    if (!std::isfinite(params.alphaBoundValue))
      throw std::invalid_argument("FlowEngine.alphaBoundValue must be a finite pressure");
    for (std::size_t i = 0; i < p_.size(); ++i)
      if (alpha_.exteriorPores[i])
        p_[i] = params.alphaBoundValue;
  }
  else
    for (int k = 0; k < kBoundaries; ++k)
      if (params.bndCondIsPressure[static_cast<std::size_t>(k)])
        for (int pi : net_->boundaryPores[static_cast<std::size_t>(k)])
          p_[static_cast<std::size_t>(pi)] = params.bndCondValue[static_cast<std::size_t>(k)];
  for (const PointPressure& pt : points_)
    p_[static_cast<std::size_t>(pt.pore)] = pt.value;
  const PoreNetwork& net = *net_;
  if (reference_)
  {
    // Nothing fixes the pressure level: only a net source of zero has a solution (what enters
    // the closed network must leave it), and then only its level is free.
    checkClosedBalance(source);
    if (!net.periodic && std::all_of(source.begin(), source.end(), [](double s) { return s == 0; }))
    {
      p_.assign(p_.size(), params.pZero); // fluid at rest: no need to solve
      return;
    }
    p_[0] = 0;
  }
  if (net.periodic)
  {
    // the macroscopic gradient: a neighbour's image across the period is at p_j + g . shift
    for (std::size_t i = 0; i < net.pores.size(); ++i)
      for (int f = 0; f < 4; ++f)
        if (net.pores[i].throats[f] >= 0)
          source[i] += net.throats[static_cast<std::size_t>(net.pores[i].throats[f])].conductance *
                       pressureJump(net.pores[i].neighbourPeriod[f]);
  }
  if (!(params.multigridTolerance > 0 && params.multigridTolerance < 1))
    throw std::invalid_argument("FlowEngine.multigridTolerance must be in (0, 1) (a relative residual), got " +
                                std::to_string(params.multigridTolerance));
  solver_.tolerance = params.tolerance;
  solver_.multigridTolerance = params.multigridTolerance;
  solver_.relax = params.relax;
  solver_.solve(static_cast<SolverKind>(params.useSolver), p_, source);
  if (reference_)
  {
    // the level: volume-weighted mean of p - g . x equal to pZero (g . x only when periodic)
    const Vec3 g = net.periodic ? params.gradP : Vec3::Zero();
    double sum = 0;
    double volume = 0;
    for (std::size_t i = 0; i < net.pores.size(); ++i)
    {
      const double v = std::abs(net.pores[i].volume);
      sum += v * (p_[i] - g.dot(net.pores[i].centre));
      volume += v;
    }
    const double shift = (volume > 0 ? sum / volume : 0.0) - params.pZero;
    for (double& x : p_)
      x -= shift;
  }
}

void PoreFlow::checkClosedBalance(const std::vector<double>& source) const
{
  double net = 0;
  double scale = 0;
  for (const double s : source)
  {
    net += s;
    scale += std::abs(s);
  }
  // round-off of the volume rates leaves a net source of the order of 1e-16 of their sum; 1e-9
  // of it is far above that and far below any real change of the fluid's volume
  if (std::abs(net) > 1e-9 * scale)
    throw std::invalid_argument(
        "FlowEngine: the pore network is closed (no boundary imposes a pressure: bndCondIsPressure all off, no "
        "imposePressure point) and the fluid is incompressible (fluidBulkModulus = 0), but the fluid volume "
        "the pores take changes by a net " + std::to_string(-net) +
        " m^3/s (moving walls or spheres, imposeFlux, thermal expansion): it has nowhere to go. Drain a side "
        "(bndCondIsPressure[k] = True with its bndCondValue) or make the fluid compressible (fluidBulkModulus > 0)");
}

int PoreFlow::imposePressure(const Vec3& pos, double p)
{
  if (!pos.allFinite() || !std::isfinite(p))
    throw std::invalid_argument("imposePressure: non-finite position or pressure");
  points_.push_back(PointPressure{pos, p, -1});
  pointsChanged_ = true;
  return static_cast<int>(points_.size()) - 1;
}

int PoreFlow::imposeFlux(const Vec3& pos, double q)
{
  if (!pos.allFinite() || !std::isfinite(q))
    throw std::invalid_argument("imposeFlux: non-finite position or flux");
  fluxPoints_.push_back(PointPressure{pos, q, -1});
  return static_cast<int>(fluxPoints_.size()) - 1;
}

void PoreFlow::clearImposedFlux() { fluxPoints_.clear(); }

void PoreFlow::setImposedPressure(int cond, double p)
{
  if (cond < 0 || static_cast<std::size_t>(cond) >= points_.size())
    throw std::out_of_range("setImposedPressure: no imposed point " + std::to_string(cond));
  points_[static_cast<std::size_t>(cond)].value = p;
}

void PoreFlow::clearImposedPressure()
{
  points_.clear();
  pointsChanged_ = true;
}

double PoreFlow::getCellFlux(int cond) const
{
  if (cond < 0 || static_cast<std::size_t>(cond) >= points_.size() || points_[static_cast<std::size_t>(cond)].pore < 0)
    throw std::out_of_range("getCellFlux: no located imposed point " + std::to_string(cond) + " (solve first)");
  const PoreNetwork& net = network();
  const auto pi = static_cast<std::size_t>(points_[static_cast<std::size_t>(cond)].pore);
  const Pore& p = net.pores[pi];
  double q = 0;
  for (int f = 0; f < 4; ++f)
    if (p.throats[f] >= 0)
      q += facetFlux(pi, f);
  return q;
}

double PoreFlow::boundaryFlux(int k) const
{
  if (k < 0 || k >= kBoundaries)
    throw std::out_of_range("getBoundaryFlux: boundary index must be 0..5, got " + std::to_string(k));
  const PoreNetwork& net = network();
  double q = 0;
  for (int pi : net.boundaryPores[static_cast<std::size_t>(k)])
  {
    const Pore& p = net.pores[static_cast<std::size_t>(pi)];
    for (int f = 0; f < 4; ++f)
      if (p.throats[f] >= 0)
        q -= facetFlux(static_cast<std::size_t>(pi), f);
  }
  return q;
}

double PoreFlow::porePressure(const Vec3& x) const
{
  Vec3i period;
  const int pi = locatePore(network(), x, &period);
  return pi < 0 ? 0.0 : p_[static_cast<std::size_t>(pi)] + pressureJump(period);
}

double PoreFlow::samplePermeability(int lo, int hi) const
{
  const PoreNetwork& net = network();
  if (lo < 0 || hi < 0 || lo >= kBoundaries || hi >= kBoundaries || lo / 2 != hi / 2 || lo == hi)
    throw std::invalid_argument("samplePermeability: give two opposite boundaries (e.g. 2 and 3)");
  if (!params.bndCondIsPressure[static_cast<std::size_t>(lo)] || !params.bndCondIsPressure[static_cast<std::size_t>(hi)])
    throw std::invalid_argument("samplePermeability: both boundaries must have an imposed pressure");
  const int c = lo / 2;
  const double dp = params.bndCondValue[static_cast<std::size_t>(lo)] - params.bndCondValue[static_cast<std::size_t>(hi)];
  if (dp == 0)
    throw std::invalid_argument("samplePermeability: the two boundary pressures are equal");
  double area = 1;
  for (int d = 0; d < 3; ++d)
    if (d != c)
      area *= net.boundaries[static_cast<std::size_t>(2 * d + 1)].position - net.boundaries[static_cast<std::size_t>(2 * d)].position;
  const double length = net.boundaries[static_cast<std::size_t>(2 * c + 1)].position - net.boundaries[static_cast<std::size_t>(2 * c)].position;
  // Flux leaving boundary lo into the sample (getBoundaryFlux is negative there for dp > 0).
  const double q = -boundaryFlux(lo);
  return q * params.viscosity * length / (area * dp);
}

std::vector<Vec3> PoreFlow::poreVelocities() const
{
  const PoreNetwork& net = network();
  std::vector<Vec3> v(net.pores.size(), Vec3::Zero());
  constexpr int kFacetVertex0[4] = {1, 0, 0, 0};
  for (std::size_t pi = 0; pi < net.pores.size(); ++pi)
  {
    const Pore& p = net.pores[pi];
    for (int f = 0; f < 4; ++f)
    {
      if (p.throats[f] < 0)
        continue;
      Vec3 n = p.centre - net.pores[static_cast<std::size_t>(p.neighbours[f])].centre - net.shift(p.neighbourPeriod[f]);
      const double len = n.norm();
      if (len == 0)
        continue;
      n /= len;
      // the facet's position along the line of centres, as averageVelocity takes it
      const double at = (net.vertices[static_cast<std::size_t>(p.vertices[kFacetVertex0[f]])].pos - p.centre).dot(n);
      v[pi] += facetFlux(pi, f) * at * n;
    }
    if (p.volume != 0)
      v[pi] /= std::abs(p.volume);
  }
  return v;
}

Vec3 PoreFlow::averageVelocity() const
{
  // Yade's averageVelocity: over all pores, the facet fluxes times the facet positions (the
  // projection of the pore centre on the line to the neighbour's centre, through the facet's
  // first vertex), minus the pore's net flux times its centre for imposed pores, divided by the
  // total volume: the volume average of the Darcy velocity.
  const PoreNetwork& net = network();
  Vec3 sum = Vec3::Zero();
  double volume = 0;
  constexpr int kFacetVertex0[4] = {1, 0, 0, 0};
  for (std::size_t pi = 0; pi < net.pores.size(); ++pi)
  {
    const Pore& p = net.pores[pi];
    Vec3 v = Vec3::Zero();
    double total = 0;
    for (int f = 0; f < 4; ++f)
    {
      if (p.throats[f] < 0)
        continue;
      const Pore& q = net.pores[static_cast<std::size_t>(p.neighbours[f])];
      Vec3 n = p.centre - q.centre - net.shift(p.neighbourPeriod[f]);
      const double len = n.norm();
      if (len == 0)
        continue;
      n /= len;
      const Vec3 branch = net.vertices[static_cast<std::size_t>(p.vertices[kFacetVertex0[f]])].pos - p.centre;
      const Vec3 facetPoint = p.centre + branch.dot(n) * n;
      const double flux = facetFlux(pi, f);
      total += flux;
      v += flux * facetPoint;
    }
    if (imposed_[pi])
      v -= total * p.centre;
    sum += v;
    volume += std::abs(p.volume);
  }
  return volume > 0 ? Vec3(sum / volume) : Vec3::Zero();
}

double PoreFlow::pressureJump(const Vec3i& period) const
{
  return net_ && net_->periodic ? params.gradP.dot(net_->shift(period)) : 0.0;
}

double PoreFlow::facetFlux(std::size_t i, int f) const
{
  const PoreNetwork& net = *net_;
  const Pore& p = net.pores[i];
  return net.throats[static_cast<std::size_t>(p.throats[f])].conductance *
         (p_[i] - p_[static_cast<std::size_t>(p.neighbours[f])] - pressureJump(p.neighbourPeriod[f]));
}

double PoreFlow::periodicPermeability() const
{
  if (!network().periodic)
    throw std::logic_error("periodicPermeability: the network is not periodic (use samplePermeability)");
  const double g2 = params.gradP.squaredNorm();
  if (!(g2 > 0))
    throw std::invalid_argument("periodicPermeability: gradP is zero");
  return -params.viscosity * averageVelocity().dot(params.gradP) / g2;
}
} // namespace talus::flow::pore
