#pragma once

#include "dem/Bodies.h"
#include "dem/Contacts.h"
#include "dem/Engine.h"
#include "dem/Material.h"

#include <cstdint>
#include <memory>
#include <vector>

namespace talus::dem
{
/// A DEM simulation (Yade's Scene / Omega): bodies, materials, contacts, engines, clock.
class Scene
{
public:
  Bodies bodies;
  std::vector<Material> materials;
  Contacts contacts;
  std::vector<std::shared_ptr<Engine>> engines;

  double dt = 1e-8;       ///< time step
  double time = 0;        ///< simulated time
  std::int64_t iter = 0;  ///< completed steps
  /// Incremented whenever bodies are added or erased, so the collider knows to re-detect.
  std::int64_t bodiesVersion = 0;

  /// Add a material after checking it; returns its index.
  int addMaterial(const Material& material);
  /// Add a sphere with mass and inertia from its material's density.
  /// @throws std::invalid_argument naming the offending value (radius, centre, material)
  BodyId addSphere(const Vec3& center, double radius, int material);
  /// Add an infinite wall x[axis] = position, interacting on side `sense` (-1, 0, +1); fixed.
  BodyId addWall(double position, int axis, int sense, int material);
  /// Remove a body; its id is not reused, its contacts disappear at the next collider run.
  void erase(BodyId id);

  /// Run all engines once and advance the clock.
  void step();

  /// Yade's PWaveTimeStep: min over spheres of r sqrt(density / young).
  [[nodiscard]] double pWaveTimeStep() const;

  /// @throws std::out_of_range naming the id if it is not a live body
  void checkBody(BodyId id) const;
};
} // namespace talus::dem
