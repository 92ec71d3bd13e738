#include "dem/Energy.h"
#include "dem/Clump.h"
#include "dem/InteractionLoop.h"
#include "dem/Scene.h"
#include "dem/Threads.h"

#include <cmath>
#include <cstdio>
#include <limits>
#include <stdexcept>
#include <string>


namespace talus::dem
{
namespace
{
/// {1/2 m v^2, 1/2 w.I w} of body i; zero for a body whose energy is not counted.
std::pair<double, double> bodyKinetic(const Scene& scene, std::size_t i)
{
  const Bodies& b = scene.bodies;
  // clump members move with their clump, whose energy is the rigid body's
  if (!b.alive[i] || !b.dynamic[i] || b.clumpId[i] >= 0)
    return {0.0, 0.0};
  // With homoDeform the velocities carry the field of the step just made (prevVelGrad once the
  // cell has moved) at the positions it was applied to, x - v dt: the fluctuation is what is
  // left, exactly as the integrator recovers it.
  const bool homogeneous = scene.periodic && scene.cell.homoDeform;
  const Mat3& L = scene.cell.prevVelGrad;
  const Vec3 v = homogeneous ? Vec3(b.vel[i] - L * (b.pos[i] - scene.dt * b.vel[i])) : b.vel[i];
  const Vec3 omega = homogeneous ? Vec3(b.angVel[i] - spin(L)) : b.angVel[i];
  // principal moments: the angular velocity in the principal (body) frame
  const Vec3 bodyOmega = b.aspherical(i) ? Vec3(b.ori[i].conjugate() * omega) : omega;
  return {0.5 * b.mass[i] * v.squaredNorm(), 0.5 * bodyOmega.dot(b.inertia[i].cwiseProduct(bodyOmega))};
}
} // namespace

std::pair<double, double> kineticEnergyParts(const Scene& scene)
{
  std::pair<double, double> total{0.0, 0.0};
  for (std::size_t i = 0; i < scene.bodies.size(); ++i)
  {
    const auto [translational, rotational] = bodyKinetic(scene, i);
    total.first += translational;
    total.second += rotational;
  }
  return total;
}

std::vector<double> bodyKineticEnergies(const Scene& scene)
{
  std::vector<double> energies(scene.bodies.size());
  for (std::size_t i = 0; i < energies.size(); ++i)
  {
    const auto [translational, rotational] = bodyKinetic(scene, i);
    energies[i] = translational + rotational;
  }
  return energies;
}

double kineticEnergy(const Scene& scene)
{
  const auto n = static_cast<std::int64_t>(scene.bodies.size());
  const std::int64_t blocks = (n + energyBlock - 1) / energyBlock;
  std::vector<double> sums(static_cast<std::size_t>(blocks), 0.0);
#pragma omp parallel for schedule(static) if (n >= parallelLoopMinimum)
  for (std::int64_t blk = 0; blk < blocks; ++blk)
  {
    double sum = 0;
    for (std::int64_t k = blk * energyBlock, end = std::min(n, k + energyBlock); k < end; ++k)
    {
      const auto [translational, rotational] = bodyKinetic(scene, static_cast<std::size_t>(k));
      sum += translational + rotational;
    }
    sums[static_cast<std::size_t>(blk)] = sum;
  }
  double total = 0;
  for (double s : sums)
    total += s;
  return total;
}

double elasticPotential(const Scene& scene)
{
  double total = 0;
  for (const auto& engine : scene.engines)
    if (const auto* loop = dynamic_cast<const InteractionLoop*>(engine.get()); loop && !loop->dead)
      for (std::size_t k = 0; k < loop->laws.size(); ++k)
        total += loop->laws[k]->elasticEnergy(scene, static_cast<std::uint8_t>(k));
  return total;
}

void addGrownContactsEnergy(Scene& scene, const InteractionLoop& loop)
{
  EnergyTracker& e = scene.energy;
  e.grownBy.resize(scene.bodies.size(), 0.0); // bodies added since the growth did not grow
  for (std::size_t k = 0; k < loop.laws.size(); ++k)
    e.growthWork -= loop.laws[k]->grownElasticEnergy(scene, static_cast<std::uint8_t>(k), e.grownBy);
  e.grownBy.clear();
}

void addImposedMotionWork(Scene& scene)
{
  const Bodies& b = scene.bodies;
  const Cell& cell = scene.cell;
  const double dt = scene.dt;
  const bool homogeneous = scene.periodic && cell.homoDeform;
  const Mat3& L = cell.velGrad;
  const Mat3& previousL = cell.prevVelGrad;
  const Vec3 meanSpin = 0.5 * (spin(L) + spin(previousL));
  EnergyTracker& tracker = scene.energy;
  const Vec3 unknown = Vec3::Constant(std::numeric_limits<double>::quiet_NaN());
  tracker.previousDisplacement.resize(b.size(), unknown);
  tracker.previousRotation.resize(b.size(), unknown);
  // The mean of an imposed displacement over this step and the previous one; remembers this one.
  auto meanImposed = [dt](Vec3& previous, const Vec3& velocity) {
    const Vec3 now = velocity * dt;
    const Vec3 mean = previous.allFinite() ? Vec3(0.5 * (previous + now)) : now;
    previous = now;
    return mean;
  };
  double cellWork = 0, kinematicWork = 0; // power of the cell's field; work of the imposed motions
  for (std::size_t i = 0; i < b.size(); ++i)
  {
    if (!b.alive[i] || b.clumpId[i] >= 0) // a member's force acts on its clump
      continue;
    Vec3 force = b.force[i], torque = b.torque[i];
    if (b.shape[i] == ShapeKind::Clump)
      addClumpMemberForces(b, i, force, torque);
    if (!b.dynamic[i])
    {
      kinematicWork += force.dot(meanImposed(tracker.previousDisplacement[i], b.vel[i]))
                       + torque.dot(meanImposed(tracker.previousRotation[i], b.angVel[i]));
      continue;
    }
    Vec3 fluctuation = b.vel[i], angularFluctuation = b.angVel[i];
    if (homogeneous)
    {
      // the field at this step's and the previous step's displacement (the integrator's
      // previous position x - v dt), averaged
      const Vec3 previousPosition = b.pos[i] - dt * b.vel[i];
      const Vec3 field = 0.5 * (L * b.pos[i] + previousL * previousPosition);
      cellWork += force.dot(field) + torque.dot(meanSpin);
      fluctuation -= previousL * previousPosition;
      angularFluctuation -= spin(previousL);
    }
    const std::uint8_t blocked = b.blockedDofs[i];
    if (blocked == 0)
      continue;
    const Vec3 displacement = meanImposed(tracker.previousDisplacement[i], fluctuation);
    const Vec3 rotation = meanImposed(tracker.previousRotation[i], angularFluctuation);
    for (int d = 0; d < 3; ++d)
    {
      if (blocked & (1u << d))
        kinematicWork += force[d] * displacement[d];
      if (blocked & (8u << d))
        kinematicWork += torque[d] * rotation[d];
    }
  }
  // A contact with a periodic image: the image moves with the cell, H c changing by L H c dt
  // (with or without homoDeform). The force on body 2 is the contact's.
  if (scene.periodic)
  {
    const Mat3 meanL = 0.5 * (L + previousL);
    for (const Contact& c : scene.contacts.list)
      if (c.real && c.cellDist != Eigen::Vector3i::Zero())
        cellWork += c.force.dot(meanL * cell.shift(c.cellDist));
  }
  tracker.velGradWork += cellWork * dt;
  tracker.kinematicWork += kinematicWork;
}

void checkEnergyGrowth(Scene& scene)
{
  EnergyTracker& e = scene.energy;
  const double kinetic = kineticEnergy(scene), elastic = elasticPotential(scene);
  const double terms[] = {kinetic, elastic, e.gravWork, e.nonviscDamp, e.plastDissip, e.viscDamp, e.velGradWork, e.kinematicWork, e.growthWork};
  double total = 0, flowed = 0;
  for (double t : terms)
  {
    total += t;
    flowed += std::abs(t);
  }
  if (std::isnan(e.growthReference))
  {
    e.growthReference = total;
    return;
  }
  const double growth = total - e.growthReference;
  if (!(growth > scene.maxEnergyGrowth * flowed))
    return;
  // the body that gained the most: the largest kinetic energy
  const Bodies& b = scene.bodies;
  std::size_t fastest = 0;
  double most = -1;
  for (std::size_t i = 0; i < b.size(); ++i)
    if (b.alive[i] && b.dynamic[i])
      if (const double k = b.mass[i] * b.vel[i].squaredNorm(); k > most)
      {
        most = k;
        fastest = i;
      }
  char message[512];
  std::snprintf(message, sizeof message,
                "step %lld: the total energy grew by %.3g (%.1f%% of the %.3g that flowed, limit %.0f%%, "
                "O.maxEnergyGrowth): the run is unstable; body %zu moves fastest (%.3g m/s). The time step %.3g "
                "is too large: P-wave estimate %.3g",
                static_cast<long long>(scene.iter), growth, 100 * growth / flowed, flowed, 100 * scene.maxEnergyGrowth,
                fastest, b.vel[fastest].norm(), scene.dt, scene.pWaveTimeStep());
  std::string text = message;
  if (const double contact = scene.contactTimeStep(); std::isfinite(contact))
    text += ", stiffest contact's critical step about " + std::to_string(contact);
  throw std::runtime_error(text);
}
} // namespace talus::dem
