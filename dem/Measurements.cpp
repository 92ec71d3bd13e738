#include "dem/Measurements.h"

#include "dem/NewtonIntegrator.h"
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
    if (!b.alive[i] || !b.dynamic[i])
      continue;
    const double f = (b.force[i] + b.mass[i] * gravity).norm();
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

Vec3 sceneGravity(const Scene& scene)
{
  for (const auto& e : scene.engines)
    if (const auto* newton = dynamic_cast<const NewtonIntegrator*>(e.get()))
      return newton->gravity;
  return Vec3::Zero();
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
    const auto i2 = static_cast<std::size_t>(c.id2);
    // A wall or facet has no centre: its branch vector is the sphere's distance to it along the
    // normal, so that in equilibrium the stress of a walled sample equals wall force over area.
    const Vec3 branch = c.kind == ContactGeometryKind::SphereSphere
                            ? Vec3(b.pos[i2] + c.shift2 - b.pos[static_cast<std::size_t>(c.id1)])
                            : Vec3(c.normal * (b.radius[i2] - c.penetration));
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
