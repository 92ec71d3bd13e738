#include "dem/interface/RVE.h"

#include "dem/checkpoint/Checkpoint.h"
#include "dem/contact/Collider.h"
#include "dem/laws/ContactLaw.h"
#include "dem/engines/ForceResetter.h"
#include "dem/engines/InteractionLoop.h"
#include "dem/engines/NewtonIntegrator.h"

#include <cmath>
#include <filesystem>
#include <numbers>
#include <stdexcept>

namespace talus::dem
{
namespace
{
bool isSphere(const Bodies& b, std::size_t i) { return b.alive[i] && b.shape[i] == ShapeKind::Sphere; }
} // namespace

Mat3 subStepVelocityGradient(const Mat3& grad, int k, int nSteps, double dt)
{
  const double n = nSteps;
  return (grad / n) * (Mat3::Identity() + (k / n) * grad).inverse() / dt;
}

RVE::RVE(const Scene& source, const RVEEngines& engines, const std::string& name) : name_(name), scene_(source)
{
  // Everything of the scene (a field added to Scene is copied too), but not its engines: the
  // source's are shared objects, the RVE builds its own.
  scene_.engines.clear();
  setUp(engines);
}

RVE RVE::load(const std::string& path, const RVEEngines& engines)
{
  if (!std::filesystem::exists(path))
    throw std::invalid_argument("RVE file '" + path + "' does not exist");
  if constexpr (!haveCheckpoints)
    throw std::invalid_argument("RVE file '" + path + "': this Talus was built without HDF5 and cannot read checkpoints");
  RVE rve(path);
  try
  {
    loadCheckpoint(rve.scene_, path);
  }
  catch (const CheckpointError& e)
  {
    throw std::invalid_argument("RVE file '" + path + "' is not a readable Talus checkpoint: " + e.what());
  }
  rve.setUp(engines);
  return rve;
}

void RVE::setUp(const RVEEngines& engines)
{
  if (!scene_.periodic)
    throw std::invalid_argument("RVE " + name_ + " is not periodic (an RVE is a periodic packing: O.periodic = True)");
  std::size_t spheres = 0;
  for (std::size_t i = 0; i < scene_.bodies.size(); ++i)
    spheres += isSphere(scene_.bodies, i) ? 1 : 0;
  if (spheres == 0)
    throw std::invalid_argument("RVE " + name_ + " has no sphere");
  auto loop = std::make_shared<InteractionLoop>();
  loop->laws.push_back(makeContactLaw(engines.law));
  auto integrator = std::make_shared<NewtonIntegrator>();
  integrator->damping = engines.damping;
  collider_ = std::make_shared<Collider>();
  scene_.engines = {std::make_shared<ForceResetter>(), collider_, loop, integrator};
  // The state came from elsewhere: engines must not trust any cache (as after loading a checkpoint).
  ++scene_.bodiesVersion;
  ++scene_.bodyPropertiesVersion;
  // Detect now, as the first step would: the committed contact list then matches the
  // collider's references, and a rollback before the first commit (every Newton iteration of
  // the first load step) needs no new detection.
  collider_->rebuild(scene_);
  initialOri_ = scene_.bodies.ori;
  commit();
}

void RVE::restore(bool failed)
{
  scene_.bodies = committed_.bodies;
  scene_.contacts = committed_.contacts;
  scene_.cell = committed_.cell;
  scene_.time = committed_.time;
  scene_.iter = committed_.iter;
  scene_.clearFailedStep();
  // The contact list is the committed one: valid for the collider's reference positions unless
  // the collider rebuilt during the trial (or a step failed half-way); then it must re-detect.
  if (failed || collider_->rebuilds != committedRebuilds_)
    ++scene_.bodiesVersion;
  trial_ = false;
}

void RVE::deform(const Mat3& grad, int nSteps)
{
  if (!grad.allFinite())
    throw std::invalid_argument("displacement gradient is not finite");
  const Mat3 I = Mat3::Identity();
  if (!((I + grad).determinant() > 0))
    throw std::invalid_argument("displacement gradient inverts the RVE (det(I + grad) = "
                                + std::to_string((I + grad).determinant()) + " <= 0)");
  if (nSteps < 1)
    throw std::invalid_argument("nSteps must be >= 1, got " + std::to_string(nSteps));
  if (trial_)
    restore();
  trial_ = true;
  try
  {
    for (int k = 0; k < nSteps; ++k)
    {
      scene_.cell.velGrad = subStepVelocityGradient(grad, k, nSteps, scene_.dt);
      scene_.step();
    }
  }
  catch (const std::exception& e)
  {
    restore(true);
    throw std::runtime_error("RVE " + name_ + ": DEM step failed while deforming (" + e.what()
                             + "); the last committed state was restored");
  }
  // The increment is over: the cell rests until the next call sets a new velocity gradient.
  scene_.cell.velGrad.setZero();
}

void RVE::commit()
{
  committed_ = {scene_.bodies, scene_.contacts, scene_.cell, scene_.time, scene_.iter};
  committedRebuilds_ = collider_->rebuilds;
  trial_ = false;
}

void RVE::rollback()
{
  if (trial_)
    restore();
}

Mat3 RVE::stress() const { return loveWeberStress(scene_); }

Mat6 RVE::tangent(TangentForm form) const { return contactStiffnessTangent(scene_, -1, form); }

RVEState RVE::state() const
{
  RVEState s;
  const double volume = scene_.cell.volume();
  s.porosity = 1 - sphereVolume(scene_) / volume;
  s.voidRatio = s.porosity / (1 - s.porosity);
  s.coordination = coordinationNumber(scene_);
  s.fabric = fabricTensor(scene_);
  const Bodies& b = scene_.bodies;
  std::size_t count = 0;
  for (std::size_t i = 0; i < b.size(); ++i)
  {
    if (!isSphere(b, i))
      continue;
    const Eigen::AngleAxisd turn(b.ori[i] * initialOri_[i].conjugate());
    // The angle-axis of a unit quaternion has angle in [0, 2 pi]; take the shorter turn.
    const double angle = turn.angle() > std::numbers::pi ? turn.angle() - 2 * std::numbers::pi : turn.angle();
    s.meanRotation += angle * turn.axis();
    ++count;
  }
  s.meanRotation /= static_cast<double>(count);
  return s;
}
} // namespace talus::dem
