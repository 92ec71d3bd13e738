#include "dem/engines/NewtonIntegrator.h"
#include "dem/engines/SphereIntegrationBatch.h"

#include "dem/core/Clump.h"
#include "dem/core/Domain.h"
#include "dem/core/Scene.h"
#include "dem/base/Threads.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

namespace talus::dem
{
namespace
{
/// Cundall's damping of one acceleration component, given the mid-step velocity estimate.
inline double damped(double accel, double vel, double dt, double damping)
{
  const double v = vel + 0.5 * dt * accel;
  const double s = accel * v;
  // sign(s) without branches: the sign of a resting packing's accelerations is a coin flip, which
  // a branch predictor cannot learn.
  return accel * (1.0 - damping * (static_cast<double>(s > 0) - static_cast<double>(s < 0)));
}

/// Turn an orientation by the rotation vector w (angle |w| about w / |w|). Per-step angles are
/// tiny, so the quaternion's cos(angle/2) and sin(angle/2)/angle come from their Taylor series
/// (exact to round-off below 1e-3 rad) instead of trigonometric calls.
inline Quat rotated(const Quat& q, const Vec3& w)
{
  const double angle2 = w.squaredNorm();
  if (angle2 == 0)
    return q;
  double c, s; // cos(angle/2) and sin(angle/2) / angle
  if (angle2 < 1e-6)
  {
    c = 1 - angle2 / 8 + angle2 * angle2 / 384;
    s = 0.5 - angle2 / 48 + angle2 * angle2 / 3840;
  }
  else
  {
    const double angle = std::sqrt(angle2);
    c = std::cos(0.5 * angle);
    s = std::sin(0.5 * angle) / angle;
  }
  return (Quat(c, s * w[0], s * w[1], s * w[2]) * q).normalized();
}

/// A body moved by forces along a free DOF needs a positive mass (inertia) there: a zero one, from a
/// material of density 0 as Yade's scripts give walls, would make the step divide by zero.
void requirePositive(const Scene& scene, std::size_t i, const char* what, double value)
{
  if (std::isfinite(value) && value > 0)
    return;
  const Material& m = scene.materials[static_cast<std::size_t>(scene.bodies.material[i])];
  throw std::invalid_argument("body " + std::to_string(i) + " is dynamic but its " + what + " is " + std::to_string(value)
                              + " (material '" + m.label + "', density " + std::to_string(m.density)
                              + "): give the material a positive density (or the body its own: b.state.mass, "
                                "b.state.inertia), or make the body non-dynamic "
                                "(b.dynamic = False) or block its free DOFs (b.state.blockedDOFs)");
}
/// Book into `block` the work that imposed motions do on the bodies [first, last) over the step
/// about to be integrated (forces of this step, velocities the integrator is about to apply).
/// For each body, the force and torque on it times the imposed part of its velocity: with
/// homoDeform, the affine field L x and its spin of every dynamic body (cellPower, the power of
/// the cell's field); the whole velocity of a non-dynamic body; the blocked components of a
/// dynamic body's (fluctuating) velocity (kinematicWork). The cell's field is taken as the mean
/// of the previous and the current step's, as gravity's work is taken over the mean velocity; a
/// kinematic body's velocity as it is now (the previous one is not kept). A body touches only
/// its own entries of the tracker's memory (sized by prepare), so ranges may run in parallel.
void addImposedMotionWorkIn(Scene& scene, std::int64_t first, std::int64_t last, BodyEnergy& block)
{
  const Bodies& b = scene.bodies;
  const Cell& cell = scene.cell;
  const double dt = scene.dt;
  const bool homogeneous = scene.periodic && cell.homoDeform;
  const Mat3& L = cell.velGrad;
  const Mat3& previousL = cell.prevVelGrad;
  const Vec3 meanSpin = 0.5 * (spin(L) + spin(previousL));
  EnergyTracker& tracker = scene.energy;
  // The mean of an imposed displacement over this step and the previous one; remembers this one.
  auto meanImposed = [dt](Vec3& previous, const Vec3& velocity) {
    const Vec3 now = velocity * dt;
    const Vec3 mean = previous.allFinite() ? Vec3(0.5 * (previous + now)) : now;
    previous = now;
    return mean;
  };
  // Split over processes, a ghost is booked by its owner (its copies still remember its imposed
  // displacement, their velocity being the owner's: a ghost that becomes its process's own at a
  // re-detection takes it along); a body every process holds (a wall) by each of them, with the
  // force of its own contacts, which add up to the body's.
  BodyEnergy uncounted;
  for (auto i = static_cast<std::size_t>(first); i < static_cast<std::size_t>(last); ++i)
  {
    if (!b.alive[i] || b.clumpId[i] >= 0) // a member's force acts on its clump
      continue;
    BodyEnergy& into = scene.domain && !scene.domain->owns(i) ? uncounted : block;
    Vec3 force = b.force[i], torque = b.torque[i];
    if (b.shape[i] == ShapeKind::Clump)
      addClumpMemberForces(b, i, force, torque);
    if (!b.dynamic[i])
    {
      into.kinematicWork += force.dot(meanImposed(tracker.previousDisplacement[i], b.vel[i]))
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
      into.cellPower += force.dot(field) + torque.dot(meanSpin);
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
        into.kinematicWork += force[d] * displacement[d];
      if (blocked & (8u << d))
        into.kinematicWork += torque[d] * rotation[d];
    }
  }
}
} // namespace

void NewtonIntegrator::refreshInverses(const Scene& scene)
{
  const Bodies& b = scene.bodies;
  invMass_.assign(b.size(), Vec3::Zero());
  invInertia_.assign(b.size(), Vec3::Zero());
  mode_.assign(b.size(), 0);
  hasClumps_ = false;
  for (std::size_t i = 0; i < b.size(); ++i)
  {
    if (!b.alive[i])
      continue;
    // A ghost (a copy of another process's body, Domain::owns) takes its owner's new state
    // after the step: moving it here would be wasted work.
    if ((mask > 0 && (b.groupMask[i] & mask) == 0) || (scene.domain && !scene.domain->owns(i)))
    {
      mode_[i] = Masked;
      continue;
    }
    if (b.clumpId[i] >= 0)
      mode_[i] = Member;
    else if (b.shape[i] == ShapeKind::Clump)
    {
      mode_[i] = ClumpBody;
      hasClumps_ = true;
    }
    // Fully blocked rotations keep their angular velocity: the spherical path does that.
    if (b.aspherical(i) && b.dynamic[i] && (b.blockedDofs[i] & (DofRX | DofRY | DofRZ)) != (DofRX | DofRY | DofRZ))
      mode_[i] |= Aspherical;
    if (!b.dynamic[i])
      continue;
    const bool integrated = b.clumpId[i] < 0; // members move with their clump
    for (int d = 0; d < 3; ++d)
    {
      if (!(b.blockedDofs[i] & (1u << d)))
      {
        if (integrated)
          requirePositive(scene, i, "mass", b.mass[i]);
        invMass_[i][d] = 1.0 / b.mass[i];
      }
      if (!(b.blockedDofs[i] & (8u << d)))
      {
        if (integrated)
          requirePositive(scene, i, "inertia", b.inertia[i][d]);
        invInertia_[i][d] = 1.0 / b.inertia[i][d];
      }
    }
  }
  seenBodiesVersion_ = scene.bodiesVersion;
  seenPropertiesVersion_ = scene.bodyPropertiesVersion;
  seenMask_ = mask;
}

namespace
{
/// dQ/dt of orientation Q turning at angular velocity w given in the body frame (Yade's DotQ).
Quat dotQ(const Vec3& w, const Quat& q)
{
  return Quat((-q.x() * w[0] - q.y() * w[1] - q.z() * w[2]) / 2, (q.w() * w[0] - q.z() * w[1] + q.y() * w[2]) / 2,
              (q.z() * w[0] + q.w() * w[1] - q.x() * w[2]) / 2, (-q.y() * w[0] + q.x() * w[1] + q.w() * w[2]) / 2);
}

Quat plus(const Quat& a, double s, const Quat& b) { return Quat(a.coeffs() + s * b.coeffs()); }

/// Gravity's work and the damping's dissipation of one translation step from velocity vOld to
/// vNew: the forces' work over the mean velocity, which is exactly the change of 1/2 m v^2 that
/// they cause in the leap-frog scheme. a and undamped: the acceleration with and without damping.
inline void bookTranslation(double mass, const Vec3& g, const Vec3& a, const Vec3& undamped, const Vec3& vOld,
                            const Vec3& vNew, double dt, double& gravWork, double& damp)
{
  const Vec3 vMean = 0.5 * (vOld + vNew);
  gravWork -= mass * g.dot(vMean) * dt;
  damp -= mass * (a - undamped).dot(vMean) * dt;
}

/// The damping's dissipation of one rotation step about principal axes (diagonal inertia):
/// the work of the damping's part of the angular acceleration over the mean angular velocity.
inline double rotationDamping(const Vec3& inertia, const Vec3& alpha, const Vec3& undamped, const Vec3& omegaOld,
                              const Vec3& omegaNew, double dt)
{
  return -(alpha - undamped).cwiseProduct(inertia).dot(0.5 * (omegaOld + omegaNew)) * dt;
}
} // namespace

template <bool Track>
void NewtonIntegrator::integrateRigid(Bodies& b, std::size_t i, const Vec3& force, const Vec3& torque, double dt,
                                      double& gravWork, double& damp) const
{
  if (b.dynamic[i])
  {
    const std::uint8_t blocked = b.blockedDofs[i];
    Vec3 g = Vec3::Zero();
    for (int d = 0; d < 3; ++d)
      if (!(blocked & (1u << d)))
        g[d] = gravity[d];
    Vec3 a = force.cwiseProduct(invMass_[i]);
    if (dampGravity)
      a += g;
    const Vec3 undamped = dampGravity ? a : Vec3(a + g);
    const double bodyDamping = b.damped[i] ? damping : 0.0; // Yade's State.isDamped
    if (bodyDamping != 0)
      for (int d = 0; d < 3; ++d)
        a[d] = damped(a[d], b.vel[i][d], dt, bodyDamping);
    if (!dampGravity)
      a += g;
    const Vec3 vOld = b.vel[i];
    b.vel[i] += a * dt;
    if constexpr (Track)
      bookTranslation(b.mass[i], g, a, undamped, vOld, b.vel[i], dt, gravWork, damp);
    if (mode_[i] & Aspherical)
    {
      // Torque with blocked axes removed and Cundall's damping on the current angular velocity
      // (Yade's cundallDamp1st), then Yade's leapfrogAsphericalRotate.
      Vec3 M = torque;
      for (int d = 0; d < 3; ++d)
        if (blocked & (8u << d))
          M[d] = 0;
      const Vec3 undampedM = M;
      if (bodyDamping != 0)
        for (int d = 0; d < 3; ++d)
        {
          const double s = M[d] * b.angVel[i][d];
          M[d] *= 1 - bodyDamping * (static_cast<double>(s > 0) - static_cast<double>(s < 0));
        }
      const Vec3 omegaOld = b.angVel[i];
      Quat& q = b.ori[i];
      const Mat3 A = q.conjugate().toRotationMatrix(); // world to body frame
      const Vec3 wn = (A * (b.angMom[i] + dt / 2 * M)).cwiseQuotient(b.inertia[i]);
      const Quat qHalf = plus(q, dt / 2, dotQ(wn, q));
      b.angMom[i] += dt * M;
      const Vec3 wHalf = (A * b.angMom[i]).cwiseQuotient(b.inertia[i]);
      q = plus(q, dt, dotQ(wHalf, qHalf));
      b.angVel[i] = q * wHalf; // as Yade: with the quaternion before normalisation
      q.normalize();
      // 1/2 L.w changes by w.dL = w.M dt: the damping's part of M over the mean (world) angular
      // velocity. Not exact as for translation: the scheme itself conserves the rotational energy
      // of a body tumbling off its principal axes only to first order in dt.
      if constexpr (Track)
        damp -= (M - undampedM).dot(0.5 * (omegaOld + b.angVel[i])) * dt;
      b.pos[i] += b.vel[i] * dt;
      return;
    }
    Vec3 alpha = torque.cwiseProduct(invInertia_[i]);
    const Vec3 undampedAlpha = alpha, omegaOld = b.angVel[i];
    if (bodyDamping != 0)
      for (int d = 0; d < 3; ++d)
        alpha[d] = damped(alpha[d], b.angVel[i][d], dt, bodyDamping);
    b.angVel[i] += alpha * dt;
    if constexpr (Track)
      damp += rotationDamping(b.inertia[i], alpha, undampedAlpha, omegaOld, b.angVel[i], dt);
  }
  b.pos[i] += b.vel[i] * dt;
  b.ori[i] = rotated(b.ori[i], b.angVel[i] * dt);
}

void NewtonIntegrator::prepare(Scene& scene)
{
  if (scene.bodiesVersion != seenBodiesVersion_ || scene.bodyPropertiesVersion != seenPropertiesVersion_
      || mask != seenMask_)
    refreshInverses(scene);
  if (scene.energy.enabled)
  {
    const Vec3 unknown = Vec3::Constant(std::numeric_limits<double>::quiet_NaN());
    scene.energy.previousDisplacement.resize(scene.bodies.size(), unknown);
    scene.energy.previousRotation.resize(scene.bodies.size(), unknown);
  }
}

void NewtonIntegrator::run(Scene& scene)
{
  prepare(scene);
  addPeriodicImageWork(scene);
  finish(scene, scene.energy.enabled ? integrate<true>(scene) : integrate<false>(scene));
  if (scene.domain) // split over processes: the ghosts take their owners' new state
    scene.domain->afterIntegration(scene);
}

std::int64_t NewtonIntegrator::integrateIn(Scene& scene, std::int64_t first, std::int64_t last,
                                           BodyEnergy* energyBlocks) const
{
  const auto n = static_cast<std::int64_t>(scene.bodies.size());
  std::int64_t bad = n;
  if (!energyBlocks)
  {
    double unused = 0;
    bad = integrateRange<false>(scene, first, last, unused, unused);
  }
  else
    for (std::int64_t start = first; start < last; start += energyBlock)
    {
      BodyEnergy& block = energyBlocks[start / energyBlock];
      const std::int64_t end = std::min(last, start + energyBlock);
      addImposedMotionWorkIn(scene, start, end, block);
      bad = std::min(bad, integrateRange<true>(scene, start, end, block.gravWork, block.damp));
    }
  return bad < n ? bad : -1;
}

void NewtonIntegrator::addEnergy(Scene& scene, const std::vector<BodyEnergy>& blocks)
{
  for (const BodyEnergy& block : blocks)
  {
    scene.energy.gravWork += block.gravWork;
    scene.energy.nonviscDamp += block.damp;
    scene.energy.kinematicWork += block.kinematicWork;
    scene.energy.velGradWork += block.cellPower * scene.dt;
  }
}

void NewtonIntegrator::finish(Scene& scene, std::int64_t firstBad)
{
  if (firstBad >= 0)
    throw std::runtime_error("step " + std::to_string(scene.iter) + ": body " + std::to_string(firstBad)
                             + " has a non-finite force or torque; the run diverged (time step "
                             + std::to_string(scene.dt) + ", P-wave estimate " + std::to_string(scene.pWaveTimeStep())
                             + ")");
  if (scene.periodic)
    scene.cell.integrate(scene.dt);
}

template <bool Track>
std::int64_t NewtonIntegrator::integrateRange(Scene& scene, std::int64_t first, std::int64_t last,
                                              double& gravWorkSum, double& dampSum) const
{
  Bodies& b = scene.bodies;
  const double dt = scene.dt;
  // In a deforming periodic cell with homoDeform, a velocity is the affine field L x (with the
  // field's spin for rotations) plus the fluctuation that forces act on. The fluctuation is
  // recovered with the previous step's L at the previous position x - v dt, so that positions
  // follow x <- (I + L dt) x + v' dt exactly as the cell does.
  const bool homogeneous = scene.periodic && scene.cell.homoDeform;
  const Mat3 L = scene.cell.velGrad, previousL = scene.cell.prevVelGrad;
  const Vec3 w = spin(L), previousW = spin(previousL);
  const auto n = static_cast<std::int64_t>(b.size());
  // One body; false if its force or torque is not finite. Tracking energy, the work of the
  // step's force is taken over the mean of the old and new (fluctuating) velocities, which is
  // exactly the change of kinetic energy it causes in the leap-frog scheme.
  auto one = [&](std::size_t i, double& gravWork, double& damp) -> bool {
    if (!b.alive[i])
      return true;
    if (mode_[i] != 0)
    {
      // Clumps and aspherical bodies: the rare path.
      if (mode_[i] & (Member | Masked))
        return true;
      Vec3 f = b.force[i], t = b.torque[i];
      if (mode_[i] & ClumpBody)
        addClumpMemberForces(b, i, f, t);
      if (b.dynamic[i] && (!f.allFinite() || !t.allFinite()))
        return false;
      // As for spheres below: forces act on the fluctuation, the affine field (at the centre)
      // and its spin are added back. An aspherical body's angular momentum is its fluctuation's.
      const bool affine = homogeneous && b.dynamic[i];
      Vec3 field = Vec3::Zero();
      if (affine)
      {
        b.vel[i] -= previousL * (b.pos[i] - dt * b.vel[i]);
        b.angVel[i] -= previousW;
        field = L * b.pos[i];
      }
      integrateRigid<Track>(b, i, f, t, dt, gravWork, damp);
      if (affine)
      {
        b.vel[i] += field;
        b.pos[i] += field * dt;
        b.angVel[i] += w;
        b.ori[i] = rotated(b.ori[i], w * dt);
      }
      if (mode_[i] & ClumpBody)
        moveClumpMembers(b, i);
      return true;
    }
    if (b.dynamic[i])
    {
      if (!b.force[i].allFinite() || !b.torque[i].allFinite())
        return false;
      Vec3 v = b.vel[i], omega = b.angVel[i];
      if (homogeneous)
      {
        v -= previousL * (b.pos[i] - dt * b.vel[i]);
        omega -= previousW;
      }
      // Blocked DOFs have a zero inverse mass (or inertia) and no gravity: their velocity stays.
      const std::uint8_t blocked = b.blockedDofs[i];
      Vec3 a = b.force[i].cwiseProduct(invMass_[i]);
      Vec3 alpha = b.torque[i].cwiseProduct(invInertia_[i]);
      // Built whole, not component by component: a vector stored in parts and then loaded
      // whole misses the store-to-load forwarding, which took a quarter of the integration.
      const Vec3 g((blocked & 1u) != 0 ? 0.0 : gravity[0], (blocked & 2u) != 0 ? 0.0 : gravity[1],
                   (blocked & 4u) != 0 ? 0.0 : gravity[2]);
      if (dampGravity)
        a += g;
      const Vec3 undamped = dampGravity ? a : Vec3(a + g), undampedAlpha = alpha;
      const double bodyDamping = b.damped[i] ? damping : 0.0; // Yade's State.isDamped
      if (bodyDamping != 0)
        for (int d = 0; d < 3; ++d)
        {
          a[d] = damped(a[d], v[d], dt, bodyDamping);
          alpha[d] = damped(alpha[d], omega[d], dt, bodyDamping);
        }
      if (!dampGravity)
        a += g;
      const Vec3 vOld = v, omegaOld = omega;
      v += a * dt;
      omega += alpha * dt;
      if constexpr (Track)
      {
        bookTranslation(b.mass[i], g, a, undamped, vOld, v, dt, gravWork, damp);
        damp += rotationDamping(b.inertia[i], alpha, undampedAlpha, omegaOld, omega, dt);
      }
      if (homogeneous)
      {
        v += L * b.pos[i];
        omega += w;
      }
      b.vel[i] = v;
      b.angVel[i] = omega;
    }
    b.pos[i] += b.vel[i] * dt;
    b.ori[i] = rotated(b.ori[i], b.angVel[i] * dt);
    return true;
  };
  // Four free spheres at a time through the lanes of integrateSphereBatch where the processor
  // has them (the same bits), the other bodies one by one; without energy to sum in order, the
  // order is free: a body writes only its own state.
  const bool batched = !Track && sphereIntegrationAvailable();
  const AffineField field{L, previousL, w, previousW};
  const SphereStepParameters lanes{invMass_.data(), invInertia_.data(), gravity, dampGravity, damping, dt,
                                   homogeneous ? &field : nullptr};
  auto plain = [&](std::size_t i) {
    return b.alive[i] && mode_[i] == 0 && b.dynamic[i] && b.blockedDofs[i] == 0 && b.force[i].allFinite()
           && b.torque[i].allFinite();
  };
  std::int64_t bad = n;
  for (std::int64_t k = first; k < last; ++k)
  {
    const auto i = static_cast<std::size_t>(k);
    if (batched && k + sphereIntegrationWidth <= last && plain(i) && plain(i + 1) && plain(i + 2) && plain(i + 3))
    {
      const unsigned turnLeft = integrateSphereBatch(b, i, lanes);
      for (std::size_t j = 0; j < sphereIntegrationWidth; ++j)
        if (turnLeft & (1U << j))
          b.ori[i + j] = rotated(b.ori[i + j], b.angVel[i + j] * dt);
      k += sphereIntegrationWidth - 1;
      continue;
    }
    if (!one(i, gravWorkSum, dampSum))
      bad = std::min(bad, k);
  }
  return bad;
}

template <bool Track>
std::int64_t NewtonIntegrator::integrate(Scene& scene) const
{
  const auto n = static_cast<std::int64_t>(scene.bodies.size());
  std::int64_t firstBad = n;
  if constexpr (Track)
  {
    // Bodies in fixed blocks, each block's sums added in order.
    const std::int64_t blocks = (n + energyBlock - 1) / energyBlock;
    std::vector<BodyEnergy> energy(static_cast<std::size_t>(blocks));
#pragma omp parallel for schedule(static) reduction(min : firstBad) if (n >= parallelLoopMinimum)
    for (std::int64_t blk = 0; blk < blocks; ++blk)
    {
      BodyEnergy& block = energy[static_cast<std::size_t>(blk)];
      const std::int64_t start = blk * energyBlock, end = std::min(n, start + energyBlock);
      addImposedMotionWorkIn(scene, start, end, block);
      firstBad = std::min(firstBad, integrateRange<true>(scene, start, end, block.gravWork, block.damp));
    }
    addEnergy(scene, energy);
  }
  else
  {
    auto firstIn = [&](std::int64_t first, std::int64_t last) {
      double unused = 0;
      return integrateRange<false>(scene, first, last, unused, unused);
    };
    firstBad = balancedFor(ranges_, n, n, firstIn, [](std::int64_t a, std::int64_t c) { return std::min(a, c); });
  }
  return firstBad < n ? firstBad : -1;
}

void addPeriodicImageWork(Scene& scene)
{
  if (!scene.energy.enabled || !scene.periodic)
    return;
  const Cell& cell = scene.cell;
  const Mat3 meanL = 0.5 * (cell.velGrad + cell.prevVelGrad);
  double power = 0;
  // Split over processes, a contact across two of them is held by both: counted by one.
  for (const Contact& c : scene.contacts.list)
    if (c.real && c.cellDist != Eigen::Vector3i::Zero()
        && countsContact(scene.domain.get(), static_cast<std::size_t>(c.id1), static_cast<std::size_t>(c.id2)))
      power += c.force.dot(meanL * cell.shift(c.cellDist));
  scene.energy.velGradWork += power * scene.dt;
}
} // namespace talus::dem
