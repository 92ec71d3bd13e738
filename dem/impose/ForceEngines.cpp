#include "dem/impose/ForceEngines.h"

#include "dem/base/Interpolation.h"
#include "dem/core/Scene.h"

#include <chrono>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <iostream>
#include <regex>
#include <stdexcept>
#include <string>

namespace talus::dem
{
void ForceEngine::addToBodies(Scene& scene, const Vec3& f) const
{
  for (const BodyId row : scene.rowsActedOn(ids, typeName() + (label.empty() ? "" : " '" + label + "'")))
    scene.bodies.force[static_cast<std::size_t>(row)] += f;
}

void ForceEngine::run(Scene& scene) { addToBodies(scene, force); }

void InterpolatingDirectedForceEngine::run(Scene& scene)
{
  const double n = direction.norm();
  if (!(n > 0) || !std::isfinite(n))
    throw std::invalid_argument(typeName() + ": direction must be a non-zero finite vector");
  direction /= n;
  force = interpolate(times, magnitudes, scene.time, wrap, typeName()) * direction;
  addToBodies(scene, force);
}

void HarmonicForceEngine::run(Scene& scene)
{
  const Vec3 w = 2 * M_PI * f;
  force = ((w * scene.time + fi).array().sin() * A.array()).matrix();
  addToBodies(scene, force);
}

void GravityEngine::run(Scene& scene)
{
  if (warnOnce)
  {
    warnOnce = false;
    std::cerr << typeName() << " is deprecated, consider using Newton::gravity instead (unless gravitational energy "
              << "has to be tracked - not implemented with the newton attribute).\n";
  }
  Bodies& b = scene.bodies;
  const bool track = scene.energy.enabled;
  double work = 0;
  for (std::size_t i = 0; i < b.size(); ++i)
  {
    if (!b.alive[i] || b.shape[i] == ShapeKind::Clump || (mask != 0 && (b.groupMask[i] & mask) == 0))
      continue;
    b.force[i] += gravity * b.mass[i];
    // The energy comes in from outside: its work counts negative, as Yade books it (split over
    // processes, by the process that counts the body).
    if (track && countsBody(scene.domain.get(), i))
      work -= gravity.dot(b.vel[i]) * b.mass[i] * scene.dt;
  }
  scene.energy.gravWork += work;
}

namespace
{
/// The "(x,y)" an hdaps sysfs file holds.
Eigen::Vector2i readHdaps(const std::string& path)
{
  std::ifstream file(path);
  if (!file.is_open())
    throw std::runtime_error("HdapsGravityEngine: unable to open file " + path);
  std::string text;
  std::getline(file, text);
  std::smatch match;
  if (!std::regex_match(text, match, std::regex(R"(\(([0-9+-]+),([0-9+-]+)\).*)")))
    throw std::runtime_error("HdapsGravityEngine: error parsing data from " + path + " (\"" + text + "\")");
  return {std::stoi(match[1].str()), std::stoi(match[2].str())};
}
} // namespace

void HdapsGravityEngine::run(Scene& scene)
{
  if (!calibrated)
  {
    calibrate = readHdaps(hdapsDir + "/calibrate");
    calibrated = true;
  }
  const double now = std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
  if (now - lastReading_ > 1e-3 * msecUpdate)
  {
    const Eigen::Vector2i a = readHdaps(hdapsDir + "/position") - calibrate;
    lastReading_ = now;
    for (int k = 0; k < 2; ++k)
      if (std::abs(a[k] - accel[k]) > updateThreshold)
        accel[k] = a[k];
    const Quat tilt = Quat(Eigen::AngleAxisd(0.5 * accel[0] * M_PI / 180, -Vec3::UnitY()))
                      * Quat(Eigen::AngleAxisd(0.5 * accel[1] * M_PI / 180, -Vec3::UnitX()));
    gravity = tilt * zeroGravity;
  }
  GravityEngine::run(scene);
}
} // namespace talus::dem
