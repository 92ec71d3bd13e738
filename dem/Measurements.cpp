#include "dem/Measurements.h"

#include "dem/Clump.h"
#include "dem/Scene.h"

#include <cmath>
#include <limits>
#include <stdexcept>

namespace talus::dem
{
double unbalancedForce(const Scene& scene, const Vec3& gravity, bool useMaxForce)
{
  const Bodies& b = scene.bodies;
  double sumBodies = 0, maxBody = 0;
  std::size_t bodies = 0;
  for (std::size_t i = 0; i < b.size(); ++i)
  {
    // A clump counts once, with its members' forces; its members do not count alone.
    if (!b.alive[i] || !b.dynamic[i] || b.clumpId[i] >= 0)
      continue;
    Vec3 force = b.force[i], torque = Vec3::Zero();
    if (b.shape[i] == ShapeKind::Clump)
      addClumpMemberForces(b, i, force, torque);
    const double f = (force + b.mass[i] * gravity).norm();
    sumBodies += f;
    maxBody = std::max(maxBody, f);
    ++bodies;
  }
  double sumContacts = 0;
  std::size_t contacts = 0;
  for (const Contact& c : scene.contacts.list)
    if (c.real)
    {
      sumContacts += c.force.norm();
      ++contacts;
    }
  if (contacts == 0 || sumContacts == 0 || bodies == 0)
    return std::numeric_limits<double>::quiet_NaN();
  const double meanContact = sumContacts / static_cast<double>(contacts);
  return (useMaxForce ? maxBody : sumBodies / static_cast<double>(bodies)) / meanContact;
}

Mat3 loveWeberStress(const Scene& scene, double volume)
{
  if (volume <= 0)
  {
    if (!scene.periodic)
      throw std::invalid_argument("getStress: give the volume of the sample (the scene is not periodic)");
    volume = scene.cell.volume();
  }
  const Bodies& b = scene.bodies;
  Mat3 sum = Mat3::Zero();
  for (const Contact& c : scene.contacts.list)
  {
    if (!c.real)
      continue;
    const Vec3 branch = b.pos[static_cast<std::size_t>(c.id2)] + c.shift2 - b.pos[static_cast<std::size_t>(c.id1)];
    sum += c.force * branch.transpose();
  }
  return -sum / volume;
}

double coordinationNumber(const Scene& scene, bool skipFree)
{
  const Bodies& b = scene.bodies;
  std::vector<int> count(b.size(), 0);
  for (const Contact& c : scene.contacts.list)
    if (c.real)
    {
      ++count[static_cast<std::size_t>(c.id1)];
      ++count[static_cast<std::size_t>(c.id2)];
    }
  double contacts = 0, spheres = 0;
  for (std::size_t i = 0; i < b.size(); ++i)
    if (b.alive[i] && b.shape[i] == ShapeKind::Sphere && (!skipFree || count[i] > 0))
    {
      contacts += count[i];
      spheres += 1;
    }
  return spheres > 0 ? contacts / spheres : 0.0;
}

Mat3 fabricTensor(const Scene& scene)
{
  Mat3 sum = Mat3::Zero();
  double n = 0;
  for (const Contact& c : scene.contacts.list)
    if (c.real && c.kind == ContactGeometryKind::SphereSphere)
    {
      sum += c.normal * c.normal.transpose();
      n += 1;
    }
  return n > 0 ? Mat3(sum / n) : Mat3::Zero();
}

double sphereVolume(const Scene& scene)
{
  const Bodies& b = scene.bodies;
  double v = 0;
  for (std::size_t i = 0; i < b.size(); ++i)
    if (b.alive[i] && b.shape[i] == ShapeKind::Sphere)
      v += 4.0 / 3.0 * M_PI * b.radius[i] * b.radius[i] * b.radius[i];
  return v;
}
} // namespace talus::dem
