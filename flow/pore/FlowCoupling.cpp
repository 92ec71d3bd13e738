#include "flow/pore/FlowCoupling.h"

#include <stdexcept>
#include <string>

namespace talus::flow::pore
{
FlowCoupling::FlowCoupling(dem::ParticleExchange exchange, std::shared_ptr<PoreFlow> flow)
    : exchange_(exchange), flow_(std::move(flow))
{
  if (!flow_)
    throw std::invalid_argument("FlowCoupling: no flow model");
}

bool FlowCoupling::followsWall(int k) const
{
  return wallIds[static_cast<std::size_t>(k)] >= 0 && !flow_->params.boundaryUseMaxMin[static_cast<std::size_t>(k)];
}

void FlowCoupling::placement(const PoreNetwork& net, std::vector<Vec3>& at, std::array<double, kBoundaries>& walls) const
{
  const auto pos = exchange_.positions();
  at.resize(sphereIds_.size());
  for (std::size_t i = 0; i < sphereIds_.size(); ++i)
    at[i] = pos[static_cast<std::size_t>(sphereIds_[i])];
  for (int k = 0; k < kBoundaries; ++k)
  {
    const Boundary& b = net.boundaries[static_cast<std::size_t>(k)];
    walls[static_cast<std::size_t>(k)] =
        followsWall(k) ? pos[static_cast<std::size_t>(wallIds[static_cast<std::size_t>(k)])][b.coordinate] : b.position;
  }
}

void FlowCoupling::move()
{
  std::vector<Vec3> at;
  std::array<double, kBoundaries> walls{};
  placement(flow_->network(), at, walls);
  flow_->moveVertices(at, walls, exchange_.dt());
}

void FlowCoupling::followWallBodies()
{
  const auto pos = exchange_.positions();
  for (int k = 0; k < kBoundaries; ++k)
    if (followsWall(k))
      flow_->params.wallPosition[static_cast<std::size_t>(k)] = pos[static_cast<std::size_t>(wallIds[static_cast<std::size_t>(k)])][k / 2];
}

void FlowCoupling::rebuilt()
{
  sinceBuild_ = 0;
  ++rebuilds_;
  if (blockHook)
    blockHook();
}

std::vector<PoreSphere> FlowCoupling::liveSpheres(std::vector<dem::BodyId>& ids) const
{
  const auto pos = exchange_.positions();
  const auto radius = exchange_.radii();
  std::vector<PoreSphere> spheres;
  ids.clear();
  for (std::size_t i = 0; i < pos.size(); ++i)
  {
    const auto id = static_cast<dem::BodyId>(i);
    if (!exchange_.isSphere(id))
      continue;
    spheres.push_back(PoreSphere{pos[i], radius[i], id});
    ids.push_back(id);
  }
  return spheres;
}

void FlowCoupling::rebuild()
{
  discardRebuild();
  followWallBodies();
  flow_->build(liveSpheres(sphereIds_));
  rebuilt();
}

void FlowCoupling::launchRebuild()
{
  followWallBodies();
  PendingRebuild job;
  std::vector<PoreSphere> spheres = liveSpheres(job.sphereIds);
  // the copy and the snapshot are the thread's own: nothing it reads changes meanwhile
  job.mesh = std::async(std::launch::async, [fresh = flow_->detachedCopy(), spheres = std::move(spheres)]() mutable {
    fresh->build(spheres);
    fresh->prepareSolver();
    return std::move(fresh);
  });
  pending_ = std::move(job);
}

void FlowCoupling::adoptRebuild()
{
  PendingRebuild job = std::move(*pending_);
  pending_.reset();
  std::unique_ptr<PoreFlow> fresh = job.mesh.get(); // rethrows what the build threw
  sphereIds_ = std::move(job.sphereIds);
  std::vector<Vec3> at;
  std::array<double, kBoundaries> walls{};
  placement(fresh->network(), at, walls);
  flow_->adopt(std::move(fresh), at, walls);
  rebuilt();
}

void FlowCoupling::discardRebuild()
{
  if (!pending_)
    return;
  if (pending_->mesh.valid())
    pending_->mesh.wait();
  pending_.reset();
}

void FlowCoupling::step()
{
  if (exchange_.periodic() != flow_->params.periodic)
    throw std::invalid_argument(exchange_.periodic() ? "FlowEngine: the scene is periodic: use PeriodicFlowEngine"
                                                     : "PeriodicFlowEngine: the scene is not periodic: use FlowEngine");
  if (flow_->params.periodic)
  {
    // the cell as it is now (it may deform); Yade's PeriodicFlowEngine has boundaries only where
    // a wall is named, the other axes being periodic
    const dem::Mat3& h = exchange_.cell().hSize;
    if (!(h - dem::Mat3(h.diagonal().asDiagonal())).isZero(0))
      throw std::invalid_argument("PeriodicFlowEngine: the periodic cell is sheared or rotated (hSize not "
                                  "diagonal); only orthorhombic cells are supported");
    flow_->params.cellSize = h.diagonal();
    for (int k = 0; k < kBoundaries; ++k)
      flow_->params.hasBoundary[static_cast<std::size_t>(k)] = wallIds[static_cast<std::size_t>(k)] >= 0;
  }
  const std::size_t nBodies = exchange_.positions().size();
  for (int k = 0; k < kBoundaries; ++k)
  {
    const dem::BodyId id = wallIds[static_cast<std::size_t>(k)];
    if (id < 0)
      continue;
    if (static_cast<std::size_t>(id) >= nBodies)
      throw std::invalid_argument("FlowEngine.wallIds[" + std::to_string(k) + "] = " + std::to_string(id) +
                                  ": no such body");
    if (exchange_.isSphere(id))
      throw std::invalid_argument("FlowEngine.wallIds[" + std::to_string(k) + "] = " + std::to_string(id) +
                                  " is a sphere, not a wall");
  }
  if (backgroundSteps < 0)
    throw std::invalid_argument("FlowEngine.backgroundSteps must be >= 0");
  // Spheres added or erased since the last mesh: the network no longer matches the bodies.
  std::size_t live = 0;
  for (std::size_t i = 0; i < nBodies; ++i)
    live += exchange_.isSphere(static_cast<dem::BodyId>(i)) ? 1 : 0;
  // the step first: a compressible fluid's storage term enters the system the build sets up
  if (exchange_.dt() > 0)
    flow_->setTimeStep(exchange_.dt());
  // A requested rebuild, or spheres added or erased, need a new mesh before this solve. A due
  // rebuild (interval, strain, an inverted pore) is done after it instead: the old mesh still
  // gives this step's volume changes, so the fluid never loses a step of support (remeshing
  // first would leave the step without a volume-change source: the whole load jumps to the
  // skeleton for one step, a jolt in a consolidating sample). An inverted pore's change is
  // counted with its sign, so the pores' changes still add up to the sample's; the mesh is
  // replaced before the next step.
  if (sinceBuild_ < 0 || live != sphereIds_.size())
    rebuild();
  else
    move();
  ++sinceBuild_;
  flow_->solve();
  const std::vector<Vec3> f = flow_->vertexForces();
  forces_.assign(nBodies, Vec3::Zero());
  for (std::size_t i = 0; i < sphereIds_.size(); ++i)
    forces_[static_cast<std::size_t>(sphereIds_[i])] = f[kBoundaries + i];
  for (int k = 0; k < kBoundaries; ++k)
    if (wallIds[static_cast<std::size_t>(k)] >= 0)
      forces_[static_cast<std::size_t>(wallIds[static_cast<std::size_t>(k)])] += f[static_cast<std::size_t>(k)];
  torques_.assign(nBodies, Vec3::Zero());
  if (flow_->params.any())
    addViscousForces();
  if (!decoupleForces)
  {
    auto out = exchange_.stepForces();
    auto outTorque = exchange_.stepTorques();
    for (std::size_t i = 0; i < nBodies; ++i)
    {
      out[i] += forces_[i];
      outTorque[i] += torques_[i];
    }
  }
  const bool inverted = flow_->invertedPores() > 0;
  const bool strained = inverted || (defTolerance > 0 && flow_->maxVolumetricStrain() > defTolerance);
  if (pending_ && inverted)
  {
    // the old mesh is no longer valid: no waiting for the background one
    rebuild();
    ++strainRebuilds_;
  }
  else if (pending_)
  {
    if (++pending_->age >= backgroundSteps)
      adoptRebuild();
  }
  else if ((meshUpdateInterval > 0 && sinceBuild_ >= meshUpdateInterval) || strained)
  {
    strainRebuilds_ += strained ? 1 : 0;
    if (multithread && !inverted)
    {
      launchRebuild();
      if (backgroundSteps == 0)
        adoptRebuild();
    }
    else
      rebuild();
  }
}

void FlowCoupling::addViscousForces()
{
  const auto vel = exchange_.velocities();
  const auto angVel = exchange_.angularVelocities();
  std::vector<Vec3> v(sphereIds_.size());
  std::vector<Vec3> w(sphereIds_.size());
  for (std::size_t i = 0; i < sphereIds_.size(); ++i)
  {
    v[i] = vel[static_cast<std::size_t>(sphereIds_[i])];
    w[i] = angVel[static_cast<std::size_t>(sphereIds_[i])];
  }
  flow_->computeViscousForces(v, w, exchange_.dt());
  const SphereLubrication& lub = flow_->lubrication();
  for (std::size_t i = 0; i < sphereIds_.size(); ++i)
  {
    const auto id = static_cast<std::size_t>(sphereIds_[i]);
    forces_[id] += lub.shearForces()[i] + lub.normalForces()[i];
    torques_[id] += lub.shearTorques()[i];
  }
}

std::shared_ptr<dem::CallbackEngine> FlowCoupling::attach(const std::shared_ptr<FlowCoupling>& coupling)
{
  // the hook owns the coupling: it lives as long as the engine list holds the hook
  return coupling->exchange_.addHook(dem::ParticleExchange::HookPoint::BeforeForces, [coupling] { coupling->step(); });
}
} // namespace talus::flow::pore
