#include "dem/core/Bodies.h"

#include <limits>

namespace talus::dem
{
const char* shapeName(ShapeKind kind)
{
  switch (kind)
  {
  case ShapeKind::Sphere: return "Sphere";
  case ShapeKind::Wall: return "Wall";
  case ShapeKind::Facet: return "Facet";
  case ShapeKind::Box: return "Box";
  case ShapeKind::Clump: return "Clump";
  case ShapeKind::PotentialBlock: return "PotentialBlock";
  case ShapeKind::PotentialParticle: return "PotentialParticle";
  }
  return "?";
}

std::optional<ShapeKind> shapeKindNamed(std::string_view name)
{
  // Every kind from the first to the last enumerator (PotentialParticle: keep it the last).
  for (int k = 0; k <= static_cast<int>(ShapeKind::PotentialParticle); ++k)
    if (name == shapeName(static_cast<ShapeKind>(k)))
      return static_cast<ShapeKind>(k);
  return std::nullopt;
}

BodyId Bodies::append(ShapeKind kind, int shapeIdx, int materialId)
{
  const auto id = static_cast<BodyId>(pos.size());
  pos.emplace_back(Vec3::Zero());
  vel.emplace_back(Vec3::Zero());
  angVel.emplace_back(Vec3::Zero());
  ori.emplace_back(Quat::Identity());
  angMom.emplace_back(Vec3::Zero());
  force.emplace_back(Vec3::Zero());
  torque.emplace_back(Vec3::Zero());
  extForce.emplace_back(Vec3::Zero());
  extTorque.emplace_back(Vec3::Zero());
  mass.push_back(0.0);
  inertia.emplace_back(Vec3::Zero());
  radius.push_back(0.0);
  shape.push_back(kind);
  shapeIndex.push_back(shapeIdx);
  material.push_back(materialId);
  blockedDofs.push_back(0);
  dynamic.push_back(1);
  damped.push_back(1);
  alive.push_back(1);
  clumpId.push_back(-1);
  groupMask.push_back(1);
  for (std::vector<double>* heat : {&temperature, &heatCapacity, &conductivity, &thermalExpansion})
    heat->push_back(std::numeric_limits<double>::quiet_NaN());
  return id;
}

void Bodies::setAngularVelocity(std::size_t i, const Vec3& w)
{
  angVel[i] = w;
  const Mat3 R = ori[i].toRotationMatrix();
  angMom[i] = R * inertia[i].cwiseProduct(R.transpose() * w);
}
} // namespace talus::dem
