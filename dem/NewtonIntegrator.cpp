#include "dem/NewtonIntegrator.h"

#include "dem/Scene.h"

#include <cmath>

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

/// Turn an orientation by the rotation vector w (angle |w| about w / |w|).
inline Quat rotated(const Quat& q, const Vec3& w)
{
  const double angle = w.norm();
  if (angle == 0)
    return q;
  return (Quat(Eigen::AngleAxisd(angle, w / angle)) * q).normalized();
}
} // namespace

void NewtonIntegrator::run(Scene& scene)
{
  Bodies& b = scene.bodies;
  const double dt = scene.dt;
  const auto n = static_cast<std::int64_t>(b.size());
#pragma omp parallel for schedule(static)
  for (std::int64_t k = 0; k < n; ++k)
  {
    const auto i = static_cast<std::size_t>(k);
    if (!b.alive[i])
      continue;
    if (b.dynamic[i])
    {
      const std::uint8_t blocked = b.blockedDofs[i];
      for (int d = 0; d < 3; ++d)
      {
        if (blocked & (1u << d))
          continue;
        double a = b.force[i][d] / b.mass[i] + gravity[d];
        if (damping != 0)
          a = damped(a, b.vel[i][d], dt, damping);
        b.vel[i][d] += a * dt;
      }
      for (int d = 0; d < 3; ++d)
      {
        if (blocked & (8u << d))
          continue;
        double a = b.torque[i][d] / b.inertia[i][d];
        if (damping != 0)
          a = damped(a, b.angVel[i][d], dt, damping);
        b.angVel[i][d] += a * dt;
      }
    }
    b.pos[i] += b.vel[i] * dt;
    b.ori[i] = rotated(b.ori[i], b.angVel[i] * dt);
  }
}
} // namespace talus::dem
