#include "dem/control/ServoPIDController.h"

#include "dem/core/Domain.h"
#include "dem/core/Scene.h"
#include "dem/measure/Measurements.h"

#include <array>
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
    // Summed exactly: a wall, facet or box (held by every process when the scene is split) by
    // its contacts, whose shares over the processes give one process's bits; any other body
    // (on the one process owning it) by its force.
    std::array<ExactSum, 3> sum;
    for (const BodyId id : bodies)
    {
      const auto i = static_cast<std::size_t>(id);
      const ShapeKind shape = scene.bodies.shape[i];
      if (shape == ShapeKind::Wall || shape == ShapeKind::Facet || shape == ShapeKind::Box)
        addContactForce(scene, i, sum);
      else
        for (std::size_t d = 0; d < 3; ++d)
          sum[d] += scene.bodies.force[i][static_cast<Eigen::Index>(d)];
    }
    sumExactly(scene.domain.get(), sum);
    const Vec3 force = Vec3(sum[0].value(), sum[1].value(), sum[2].value()).cwiseProduct(axis);
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
