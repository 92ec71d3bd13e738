#include "dem/impose/SampleOperations.h"

#include "dem/core/Clump.h"
#include "dem/core/Domain.h"
#include "dem/measure/Energy.h"
#include "dem/core/Scene.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

namespace talus::dem
{
void growParticles(Scene& scene, double multiplier, bool updateMass, bool dynamicOnly)
{
  Bodies& b = scene.bodies;
  // A clump grows as one rigid body, homothetically about its centroid, when the clump itself
  // passes the dynamic test; its members follow it whatever their own flags (Yade tests each
  // member and the clump separately, which can grow the members of a clump whose mass it keeps).
  auto passes = [&](std::size_t i) { return b.alive[i] && (!dynamicOnly || b.dynamic[i]); };
  auto grows = [&](std::size_t i) {
    return b.shape[i] == ShapeKind::Sphere && (b.clumpId[i] >= 0 ? passes(static_cast<std::size_t>(b.clumpId[i])) : passes(i));
  };
  // Nothing grows, whatever the multiplier, when no body passes, as in Yade (a
  // TriaxialStressController compacting fixed spheres towards a goal of 0 asks for -inf).
  bool any = false;
  for (std::size_t i = 0; i < b.size() && !any; ++i)
    any = grows(i) || (b.shape[i] == ShapeKind::Clump && passes(i));
  // Split over processes, every process scales the member offsets of every growing clump in its
  // clump table, whether it holds the clump or not: a process the clump moves to later places
  // its members by its own table. Each clump's owner decides whether it grows (-1 per growing
  // clump's shape, and last whether any body grows anywhere, in one reduction).
  std::vector<double> growing;
  if (scene.domain)
  {
    growing.assign(b.clumps.size() + 1, 0.0);
    for (std::size_t i = 0; i < b.size(); ++i)
      if (b.shape[i] == ShapeKind::Clump && scene.domain->owns(i) && passes(i))
        growing[static_cast<std::size_t>(b.shapeIndex[i])] = -1;
    growing.back() = any ? -1 : 0;
    scene.domain->min(growing);
    any = growing.back() < 0;
  }
  if (!any)
    return;
  if (!(multiplier > 0 && std::isfinite(multiplier)))
    throw std::invalid_argument("growParticles: the multiplier must be positive and finite, got " + std::to_string(multiplier));
  const bool track = scene.energy.enabled;
  const double before = track ? kineticEnergy(scene) + elasticPotential(scene) : 0.0;
  // How far each member's centre moves: (multiplier - 1) times its offset from the centroid.
  std::vector<Vec3> moved(b.size(), Vec3::Zero());
  std::vector<std::uint8_t> held(b.clumps.size(), 0); // the clumps this process holds (their offsets scaled below)
  for (std::size_t i = 0; i < b.size(); ++i)
  {
    if (b.shape[i] == ShapeKind::Clump && b.alive[i])
      held[static_cast<std::size_t>(b.shapeIndex[i])] = 1;
    if (b.shape[i] == ShapeKind::Clump && passes(i))
    {
      ClumpShape& clump = b.clumps[static_cast<std::size_t>(b.shapeIndex[i])];
      for (std::size_t k = 0; k < clump.members.size(); ++k)
      {
        clump.relPos[k] *= multiplier;
        const auto m = static_cast<std::size_t>(clump.members[k]);
        moved[m] = b.pos[i] + b.ori[i] * clump.relPos[k] - b.pos[m];
      }
      // Its mass and principal moments as a homothetic body's (the principal axes stay); the
      // members' own are only the sum's parts, scaled below like any sphere's.
      if (updateMass)
      {
        b.mass[i] *= std::pow(multiplier, 3);
        b.inertia[i] *= std::pow(multiplier, 5);
      }
      moveClumpMembers(b, i);
      continue;
    }
    if (!grows(i))
      continue;
    if (updateMass)
    {
      b.mass[i] *= std::pow(multiplier, 3);
      b.inertia[i] *= std::pow(multiplier, 5);
    }
    b.radius[i] *= multiplier;
  }
  for (std::size_t k = 0; scene.domain && k < b.clumps.size(); ++k)
    if (growing[k] < 0 && !held[k])
      for (Vec3& offset : b.clumps[k].relPos)
        offset *= multiplier;
  for (Contact& c : scene.contacts.list)
  {
    if (!c.real)
      continue;
    const auto i1 = static_cast<std::size_t>(c.id1), i2 = static_cast<std::size_t>(c.id2);
    // Every contact geometry's penetration is a radius minus a distance (or a sum of radii minus
    // the distance of the centres): at fixed positions it grows by the growth of the radii, as
    // the next geometry update will find, so the elastic energy is the new state's at once.
    if (grows(i1))
    {
      c.penetration += b.radius[i1] * (1 - 1 / multiplier);
      c.refR1 = b.radius[i1];
    }
    if (grows(i2))
    {
      c.penetration += b.radius[i2] * (1 - 1 / multiplier);
      c.refR2 = b.radius[i2];
    }
    // Clump members also move apart. Between two spheres the normal is the line of centres, so
    // the new distance is exact; against a plane (wall, facet face, box face) the moved distance
    // along the normal is exact, elsewhere (edges, corners) to first order in the displacement.
    const Vec3 approach = moved[i2] - moved[i1];
    if (approach != Vec3::Zero())
    {
      if (c.kind == ContactGeometryKind::SphereSphere)
      {
        const double distance = b.radius[i1] + b.radius[i2] - c.penetration; // of the centres, grown radii
        c.penetration = b.radius[i1] + b.radius[i2] - (distance * c.normal + approach).norm();
      }
      else
        c.penetration -= approach.dot(c.normal);
    }
    c.kn *= multiplier;
    c.ks *= multiplier;
  }
  ++scene.bodyPropertiesVersion;
  ++scene.bodiesVersion; // the radii changed: re-detect contacts with the new sizes
  // The energy the growth put in: nothing moved, the state functions jumped.
  if (track)
  {
    scene.energy.growthWork += before - (kineticEnergy(scene) + elasticPotential(scene));
    std::vector<double>& grownBy = scene.energy.grownBy;
    grownBy.resize(b.size(), 0.0);
    for (std::size_t i = 0; i < b.size(); ++i)
      if (b.alive[i] && grows(i))
        grownBy[i] += b.radius[i] * (1 - 1 / multiplier);
  }
}

void setContactFriction(Scene& scene, double angle)
{
  if (!(angle >= 0 && angle < M_PI / 2))
    throw std::invalid_argument("setContactFriction: the angle must be in [0, pi/2) radians, got " + std::to_string(angle));
  Bodies& b = scene.bodies;
  std::vector<bool> dynamicMaterial(scene.materials.size(), false);
  for (std::size_t i = 0; i < b.size(); ++i)
    if (b.alive[i] && b.dynamic[i])
      dynamicMaterial[static_cast<std::size_t>(b.material[i])] = true;
  for (std::size_t m = 0; m < scene.materials.size(); ++m)
    if (dynamicMaterial[m])
      scene.materials[m].frictionAngle = angle;
  for (Contact& c : scene.contacts.list)
    if (c.real)
      c.tanPhi = std::tan(std::min(scene.materials[static_cast<std::size_t>(b.material[static_cast<std::size_t>(c.id1)])].frictionAngle,
                                   scene.materials[static_cast<std::size_t>(b.material[static_cast<std::size_t>(c.id2)])].frictionAngle));
}
} // namespace talus::dem
