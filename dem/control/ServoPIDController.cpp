#include "dem/control/ServoPIDController.h"

#include "dem/core/Scene.h"

#include <cmath>
#include <stdexcept>

namespace talus::dem
{
void ServoPIDController::apply(Scene& scene, const std::vector<BodyId>& bodies)
{
  if (iterPrevStart < 0 || scene.iter - iterPrevStart >= iterPeriod)
  {
    const double length = axis.norm();
    if (!(length > 0) || !std::isfinite(length))
      throw std::invalid_argument("ServoPIDController: axis must be a non-zero finite vector");
    axis /= length;
    Vec3 force = Vec3::Zero();
    for (BodyId id : bodies)
      force += scene.bodies.force[static_cast<std::size_t>(id)];
    force = force.cwiseProduct(axis);
    errorCur = force.norm() - target;
    const double pTerm = errorCur * kP;
    iTerm += errorCur * kI;
    const double dTerm = (errorCur - errorPrev) * kD;
    errorPrev = errorCur;
    curVel = pTerm + iTerm + dTerm;
    if (std::abs(curVel) > std::abs(maxVelocity))
      curVel *= std::abs(maxVelocity) / std::abs(curVel);
    iterPrevStart = scene.iter;
    current = force;
  }
  translationAxis = axis;
  velocity = curVel;
  TranslationEngine::apply(scene, bodies);
}
} // namespace talus::dem
