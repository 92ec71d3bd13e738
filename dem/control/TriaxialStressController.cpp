#include "dem/control/TriaxialStressController.h"

#include "dem/base/ExactSum.h"
#include "dem/core/Domain.h"
#include "dem/core/Scene.h"
#include "dem/measure/Measurements.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace talus::dem
{
namespace
{
const char* const wallNames[6] = {"wall_left_id", "wall_right_id", "wall_bottom_id", "wall_top_id", "wall_back_id", "wall_front_id"};
constexpr int wallAxis[6] = {0, 0, 1, 1, 2, 2};

double sign(double x) { return x > 0 ? 1.0 : (x < 0 ? -1.0 : 0.0); }
} // namespace

const std::array<Vec3, 6> TriaxialStressController::normal{Vec3(1, 0, 0), Vec3(-1, 0, 0), Vec3(0, 1, 0),
                                                           Vec3(0, -1, 0), Vec3(0, 0, 1), Vec3(0, 0, -1)};

std::array<std::size_t, 6> TriaxialStressController::wallRows(const Scene& scene) const
{
  std::array<std::size_t, 6> rows{};
  for (int w = 0; w < 6; ++w)
  {
    const BodyId id = wallIds[static_cast<std::size_t>(w)];
    const std::string which = std::string("TriaxialStressController: ") + wallNames[w] + " = " + std::to_string(id);
    // By the ids the user gave: split over processes, every process holds the walls at rows of its own.
    const std::int64_t row = scene.domain ? scene.domain->rowOf(id) : id;
    if (row == Domain::elsewhere)
      throw std::invalid_argument(which + " must be a wall normal to axis " + std::to_string(wallAxis[w])
                                  + " (a body every process holds)");
    if (row < 0 || static_cast<std::size_t>(row) >= scene.bodies.size() || !scene.bodies.alive[static_cast<std::size_t>(row)])
      throw std::invalid_argument(which + " is not a body of the scene");
    const auto i = static_cast<std::size_t>(row);
    if (scene.bodies.shape[i] != ShapeKind::Wall
        || scene.bodies.walls[static_cast<std::size_t>(scene.bodies.shapeIndex[i])].axis != wallAxis[w])
      throw std::invalid_argument(which + " must be a wall normal to axis " + std::to_string(wallAxis[w]));
    rows[static_cast<std::size_t>(w)] = i;
  }
  return rows;
}

std::array<Vec3, 6> TriaxialStressController::wallForces(const Scene& scene, const std::array<std::size_t, 6>& rows,
                                                         bool withStiffness, bool withVolume)
{
  // 18 force components, 6 stiffnesses, the volume
  std::array<ExactSum, 25> sums;
  for (std::size_t w = 0; w < 6; ++w)
    addContactForce(scene, rows[w], std::span<ExactSum, 3>(sums.data() + 3 * w, 3), withStiffness ? &sums[18 + w] : nullptr);
  const Bodies& b = scene.bodies;
  if (withVolume)
    for (std::size_t i = 0; i < b.size(); ++i)
      if (b.alive[i] && b.dynamic[i] && b.shape[i] == ShapeKind::Sphere && countsBody(scene.domain.get(), i))
        sums[24] += 4. / 3. * M_PI * std::pow(b.radius[i], 3);
  sumExactly(scene.domain.get(), std::span<ExactSum>(sums.data(), withStiffness || withVolume ? sums.size() : 18));
  std::array<Vec3, 6> forces;
  for (std::size_t w = 0; w < 6; ++w)
  {
    forces[w] = Vec3(sums[3 * w].value(), sums[3 * w + 1].value(), sums[3 * w + 2].value());
    if (withStiffness)
      stiffness[w] = sums[18 + w].value();
  }
  if (withVolume)
    particlesVolume = sums[24].value();
  return forces;
}

void TriaxialStressController::computeStressStrain(const Scene& scene)
{
  const std::array<std::size_t, 6> rows = wallRows(scene); // also called from Python, with ids that may not be walls
  stressStrainFrom(scene, rows, wallForces(scene, rows, false, false));
}

void TriaxialStressController::stressStrainFrom(const Scene& scene, const std::array<std::size_t, 6>& rows,
                                                const std::array<Vec3, 6>& forces)
{
  const Bodies& b = scene.bodies;
  auto at = [&](int w) { return b.pos[rows[static_cast<std::size_t>(w)]][wallAxis[w]]; };
  height = at(Top) - at(Bottom);
  width = at(Right) - at(Left);
  depth = at(Front) - at(Back);
  if (height0 == 0)
    height0 = height;
  if (width0 == 0)
    width0 = width;
  if (depth0 == 0)
    depth0 = depth;
  strain = Vec3(std::log(width / width0), std::log(height / height0), std::log(depth / depth0));
  volumetricStrain = strain.sum();
  const double invArea[3] = {1. / (height * depth), 1. / (width * depth), 1. / (width * height)};
  meanStress = 0;
  for (int w = 0; w < 6; ++w)
  {
    const auto k = static_cast<std::size_t>(w);
    force[k] = forces[k];
    // The force of the spheres on a wall, over its area; the sign makes tension positive.
    const double side = (w % 2 == 0) ? 1.0 : -1.0;
    stress[k] = side * force[k] * invArea[wallAxis[w]];
    meanStress += stress[k].dot(side * normal[k]);
  }
  meanStress /= 6.;
}

void TriaxialStressController::controlExternalStress(Scene& scene, std::size_t row, int wall, const Vec3& f,
                                                     const Vec3& resultantForce, double maxVelocity)
{
  const auto k = static_cast<std::size_t>(wall);
  double translation = normal[k].dot(f - resultantForce);
  if (translation != 0)
  {
    if (stiffness[k] != 0)
      translation = std::min(std::abs(translation / stiffness[k]), maxVelocity * scene.dt) * sign(translation);
    else
      translation = maxVelocity * sign(translation) * scene.dt;
  }
  // steady motion with the fluctuations damped
  previousTranslation[k] = (1 - stressDamping) * translation * normal[k] + 0.8 * previousTranslation[k];
  externalWork += previousTranslation[k].dot(f);
  scene.bodies.vel[row] = previousTranslation[k] / scene.dt;
}

void TriaxialStressController::run(Scene& scene)
{
  const std::array<std::size_t, 6> rows = wallRows(scene);
  if (thickness < 0)
    thickness = 0; // Yade reads it from its box walls; Talus's walls are planes
  Bodies& b = scene.bodies;
  // The planes stand where Yade's boxes have their inner faces: the distance between two
  // planes is Yade's distance between box centres minus the thickness.
  auto position = [&](int w) { return b.pos[rows[static_cast<std::size_t>(w)]][wallAxis[w]]; };
  height = position(Top) - position(Bottom);
  width = position(Right) - position(Left);
  depth = position(Front) - position(Back);
  if (!(height > 0 && width > 0 && depth > 0))
    throw std::runtime_error("TriaxialStressController: the walls do not enclose a box (width " + std::to_string(width)
                             + ", height " + std::to_string(height) + ", depth " + std::to_string(depth) + ")");
  boxVolume = height * width * depth;
  // What this step reads of the walls' contacts and the spheres, in one sum (over the processes
  // when split: every process decides alike from the step number and the state it shares).
  const bool withVolume = first || updatePorosity;
  const bool withStiffness = scene.iter % std::max(stiffnessUpdateInterval, 1u) == 0 || scene.iter < 100;
  const bool radiusControl = scene.iter % std::max(radiusControlInterval, 1u) == 0;
  const bool stressStrain = scene.iter % std::max(computeStressStrainInterval, 1u) == 0 || (internalCompaction && radiusControl);
  std::array<Vec3, 6> forces{};
  if (withVolume || withStiffness || stressStrain || !internalCompaction)
    forces = wallForces(scene, rows, withStiffness, withVolume);
  first = false;
  updatePorosity = false;
  const double perimeter = height + width + depth;
  const double maxVel[3] = {3 * width / perimeter * max_vel, 3 * height / perimeter * max_vel, 3 * depth / perimeter * max_vel};
  porosity = (boxVolume - particlesVolume) / boxVolume;
  if (stressStrain)
    stressStrainFrom(scene, rows, forces);

  if (!internalCompaction)
  {
    const double goals[3] = {goal1, goal2, goal3};
    const double sizes[3] = {width, height, depth};
    const double areas[3] = {height * depth, width * depth, width * height};
    for (int w = 0; w < 6; ++w)
    {
      const auto k = static_cast<std::size_t>(w);
      const int axis = wallAxis[w];
      Vec3& v = b.vel[rows[k]];
      if (!wallActivated[k])
      {
        v.setZero();
        continue;
      }
      if (stressMask & (1u << axis))
      {
        Vec3 target = Vec3::Zero();
        target[axis] = goals[axis] * areas[axis] * (w % 2 == 0 ? 1.0 : -1.0);
        controlExternalStress(scene, rows[k], w, forces[k], target, maxVel[axis]);
      }
      else
      {
        // relax towards the velocity giving strain rate goal (each wall moves half of it)
        v[axis] += (-normal[k][axis] * 0.5 * goals[axis] * sizes[axis] - v[axis]) * (1 - strainDamping);
        externalWork += v.dot(forces[k]) * scene.dt;
      }
    }
  }
  else
  {
    for (int w = 0; w < 6; ++w)
      b.vel[rows[static_cast<std::size_t>(w)]].setZero();
    if (radiusControl)
    {
      const int axes = bool(stressMask & 1) + bool(stressMask & 2) + bool(stressMask & 4);
      if (axes == 0)
        throw std::invalid_argument("TriaxialStressController: internalCompaction needs a stress goal (stressMask > 0)");
      const double goal = (bool(stressMask & 1) * goal1 + bool(stressMask & 2) * goal2 + bool(stressMask & 4) * goal3) / axes;
      if (std::abs(goal) <= std::abs(meanStress))
        maxMultiplier = finalMaxMultiplier;
      if (meanStress == 0)
        previousMultiplier = maxMultiplier;
      else if (goal < 0) // compression: grow while the mean stress is below the goal in magnitude
        previousMultiplier = 1. + (goal - meanStress) / goal * (maxMultiplier - 1.);
      else
        previousMultiplier = 1. + (meanStress - goal) / goal * (maxMultiplier - 1.);
      previousStress = meanStress;
      particlesVolume *= std::pow(previousMultiplier, 3);
      growParticles(scene, previousMultiplier, true, true);
    }
  }
}

} // namespace talus::dem
