#include "dem/impose/KinematicEngines.h"

#include "dem/base/Interpolation.h"
#include "dem/core/Scene.h"

#include <cmath>
#include <stdexcept>
#include <string>

namespace talus::dem
{
namespace
{
Vec3 unit(const Vec3& axis, const std::string& engine, const char* name)
{
  const double n = axis.norm();
  if (!(n > 0) || !std::isfinite(n))
    throw std::invalid_argument(engine + ": " + name + " must be a non-zero finite vector");
  return axis / n;
}
} // namespace

void KinematicEngine::run(Scene& scene)
{
  const std::vector<BodyId> rows = scene.rowsActedOn(ids, typeName() + (label.empty() ? "" : " '" + label + "'"));
  for (const BodyId row : rows)
  {
    scene.bodies.vel[static_cast<std::size_t>(row)].setZero();
    scene.bodies.angVel[static_cast<std::size_t>(row)].setZero();
  }
  apply(scene, rows);
}

void CombinedKinematicEngine::apply(Scene& scene, const std::vector<BodyId>& bodies)
{
  for (const auto& engine : comb)
    if (!engine->dead)
      engine->apply(scene, bodies);
}

void TranslationEngine::apply(Scene& scene, const std::vector<BodyId>& bodies)
{
  const Vec3 v = velocity * unit(translationAxis, typeName(), "translationAxis");
  for (BodyId id : bodies)
    scene.bodies.vel[static_cast<std::size_t>(id)] += v;
}

void RotationEngine::apply(Scene& scene, const std::vector<BodyId>& bodies)
{
  const Vec3 axis = unit(rotationAxis, typeName(), "rotationAxis");
  const double dt = scene.dt;
  const Quat q(Eigen::AngleAxisd(angularVelocity * dt, axis));
  Bodies& b = scene.bodies;
  for (BodyId id : bodies)
  {
    const auto i = static_cast<std::size_t>(id);
    b.angVel[i] += axis * angularVelocity;
    if (rotateAroundZero)
    {
      const Vec3 l = b.pos[i] - zeroPoint;
      b.vel[i] += (q * l + zeroPoint - b.pos[i]) / dt;
    }
  }
}

void HarmonicMotionEngine::apply(Scene& scene, const std::vector<BodyId>& bodies)
{
  const Vec3 w = 2 * M_PI * f;
  const Vec3 v = -((w * scene.time + fi).array().sin() * A.array() * w.array()).matrix();
  for (BodyId id : bodies)
    scene.bodies.vel[static_cast<std::size_t>(id)] += v;
}

void HelixEngine::apply(Scene& scene, const std::vector<BodyId>& bodies)
{
  angleTurned += angularVelocity * scene.dt;
  const Vec3 v = linearVelocity * unit(rotationAxis, typeName(), "rotationAxis");
  for (BodyId id : bodies)
    scene.bodies.vel[static_cast<std::size_t>(id)] += v;
  rotateAroundZero = true; // as Yade: a helix always orbits its axis
  RotationEngine::apply(scene, bodies);
}

void InterpolatingHelixEngine::apply(Scene& scene, const std::vector<BodyId>& bodies)
{
  angularVelocity = interpolate(times, angularVelocities, scene.time, wrap, typeName());
  linearVelocity = angularVelocity * slope;
  HelixEngine::apply(scene, bodies);
}
} // namespace talus::dem
