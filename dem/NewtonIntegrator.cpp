#include "dem/NewtonIntegrator.h"
#include "dem/Scene.h"

#include "dem/Threads.h"

#include <algorithm>
#include <cmath>
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
  return accel * (1.0 - damping * (s > 0 ? 1.0 : (s < 0 ? -1.0 : 0.0)));
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
} // namespace

void NewtonIntegrator::refreshInverses(const Scene& scene)
{
  const Bodies& b = scene.bodies;
  invMass_.assign(b.size(), Vec3::Zero());
  invInertia_.assign(b.size(), Vec3::Zero());
  for (std::size_t i = 0; i < b.size(); ++i)
  {
    if (!b.alive[i] || !b.dynamic[i])
      continue;
    for (int d = 0; d < 3; ++d)
    {
      if (!(b.blockedDofs[i] & (1u << d)))
        invMass_[i][d] = 1.0 / b.mass[i];
      if (!(b.blockedDofs[i] & (8u << d)))
        invInertia_[i][d] = 1.0 / b.inertia[i][d];
    }
  }
  seenBodiesVersion_ = scene.bodiesVersion;
  seenPropertiesVersion_ = scene.bodyPropertiesVersion;
}

namespace
{
/// Rotation rate (axial vector) of the antisymmetric part of a velocity gradient.
Vec3 spin(const Mat3& L) { return 0.5 * Vec3(L(2, 1) - L(1, 2), L(0, 2) - L(2, 0), L(1, 0) - L(0, 1)); }
} // namespace

void NewtonIntegrator::run(Scene& scene)
{
  if (scene.bodiesVersion != seenBodiesVersion_ || scene.bodyPropertiesVersion != seenPropertiesVersion_)
    refreshInverses(scene);
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
  std::int64_t firstBad = n;
#pragma omp parallel for if (n >= parallelLoopMinimum) schedule(static) reduction(min : firstBad)
  for (std::int64_t k = 0; k < n; ++k)
  {
    const auto i = static_cast<std::size_t>(k);
    if (!b.alive[i])
      continue;
    if (b.dynamic[i])
    {
      if (!b.force[i].allFinite() || !b.torque[i].allFinite())
      {
        firstBad = std::min(firstBad, k);
        continue;
      }
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
      for (int d = 0; d < 3; ++d)
        if (!(blocked & (1u << d)))
          a[d] += gravity[d];
      if (damping != 0)
        for (int d = 0; d < 3; ++d)
        {
          a[d] = damped(a[d], v[d], dt, damping);
          alpha[d] = damped(alpha[d], omega[d], dt, damping);
        }
      v += a * dt;
      omega += alpha * dt;
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
  }
  if (firstBad < n)
    throw std::runtime_error("step " + std::to_string(scene.iter) + ": body " + std::to_string(firstBad)
                             + " has a non-finite force or torque; the run diverged (time step " + std::to_string(dt)
                             + ", P-wave estimate " + std::to_string(scene.pWaveTimeStep()) + ")");
  if (scene.periodic)
    scene.cell.integrate(dt);
}
} // namespace talus::dem
