#include "dem/control/ThreeDTriaxialEngine.h"

#include "dem/impose/SampleOperations.h"
#include "dem/core/Scene.h"

#include <cmath>

namespace talus::dem
{
void ThreeDTriaxialEngine::run(Scene& scene)
{
  if (firstRun)
  {
    if (updateFrictionAngle)
      setContactFriction(scene, frictionAngleDegree * M_PI / 180.0);
    // the sizes of the previous step (zero on the very first: the controller then takes them)
    height0 = height;
    depth0 = depth;
    width0 = width;
    for (std::size_t axis = 0; axis < 3; ++axis)
      wallActivated[2 * axis] = wallActivated[2 * axis + 1] = stressControl[axis];
    firstRun = false;
  }
  const double sizes[3] = {width, height, depth};
  Bodies& b = scene.bodies;
  for (int axis = 0; axis < 3; ++axis)
  {
    double& rate = currentStrainRate[axis];
    if (rate != strainRate[axis])
      rate += (strainRate[axis] - rate) * (1 - strainRateDamping);
    // Under stress control Yade sets a velocity cap here that the controller then overwrites:
    // only the strain-controlled axes move from here.
    if (stressControl[static_cast<std::size_t>(axis)])
      continue;
    Vec3 step = Vec3::Zero();
    step[axis] = 0.5 * rate * sizes[axis] * scene.dt;
    b.pos[static_cast<std::size_t>(wallIds[static_cast<std::size_t>(2 * axis)])] += step;
    b.pos[static_cast<std::size_t>(wallIds[static_cast<std::size_t>(2 * axis + 1)])] -= step;
  }
  TriaxialStressController::run(scene);
}

} // namespace talus::dem
