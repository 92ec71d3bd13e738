#pragma once

#include "dem/engines/CallbackEngine.h"
#include "dem/core/Scene.h"

#include <cmath>
#include <functional>
#include <memory>
#include <span>
#include <stdexcept>
#include <string>

namespace talus::dem
{
/// The particle exchange interface: everything a coupling (VANS fluid, pore flow, OpenFOAM,
/// FEM x DEM) may do with the DEM core, and nothing more.
///
/// - read particle state as arrays indexed by body id (spans over the core's own storage, no
///   copies; valid until bodies are added): positions, velocities, angular velocities, radii,
///   masses, and which ids are live spheres; the contact list, read only;
/// - read and write the bodies' heat (temperature, heat capacity, conductivity, expansion
///   coefficient: Yade's ThermalState), one value per body id, NaN where not given;
/// - change the spheres' radii (`growSpheres`: thermal expansion);
/// - apply forces and torques: `persistentForces()` keeps a value until the coupling changes it
///   (Yade's permanent forces), `stepForces()` is this step's accumulator, reset by the
///   ForceResetter, to be added to from a hook placed after it;
/// - hook into the step: `addHook` inserts an engine calling the coupling at a chosen point,
///   every `period` steps.
///
/// Couplings hold a ParticleExchange, never the Scene itself.
class ParticleExchange
{
public:
  /// Where in the step a hook runs.
  enum class HookPoint
  {
    BeforeForces, ///< after the ForceResetter, before contact forces: add fluid forces here
    AfterForces,  ///< after contact forces, before integration: read this step's total forces
    AfterStep,    ///< after integration: read the new positions and velocities
  };

  /// @param scene the scene exchanged with; it must outlive this object
  explicit ParticleExchange(Scene& scene) : scene_(scene) {}

  /// Per body id: positions (m), velocities (m/s), angular velocities (rad/s), radii (m, 0 for
  /// shapes other than spheres) and masses (kg); valid until bodies are added.
  [[nodiscard]] std::span<const Vec3> positions() const { return scene_.bodies.pos; }
  [[nodiscard]] std::span<const Vec3> velocities() const { return scene_.bodies.vel; }
  [[nodiscard]] std::span<const Vec3> angularVelocities() const { return scene_.bodies.angVel; }
  [[nodiscard]] std::span<const double> radii() const { return scene_.bodies.radius; }
  [[nodiscard]] std::span<const double> masses() const { return scene_.bodies.mass; }
  /// True for ids that are live spheres (the particles couplings act on).
  /// @param id any id (out of range: false)
  /// @return whether it is a live sphere
  [[nodiscard]] bool isSphere(BodyId id) const
  {
    const auto i = static_cast<std::size_t>(id);
    return i < scene_.bodies.size() && scene_.bodies.alive[i] && scene_.bodies.shape[i] == ShapeKind::Sphere;
  }

  /// Per body id, writable: temperature (K or °C, as the user's values), specific heat capacity
  /// (J/(kg K)), conductivity (W/(m K)) and linear thermal expansion coefficient (1/K). NaN where
  /// not given: a heat model gives its defaults to those of the bodies it covers, and every
  /// component reads and changes the same values (a coupling heating the particles, output).
  /// @return spans over the core's storage, one entry per body id, valid until bodies are added
  [[nodiscard]] std::span<double> temperatures() { return scene_.bodies.temperature; }
  [[nodiscard]] std::span<double> heatCapacities() { return scene_.bodies.heatCapacity; }
  [[nodiscard]] std::span<double> conductivities() { return scene_.bodies.conductivity; }
  [[nodiscard]] std::span<double> thermalExpansions() { return scene_.bodies.thermalExpansion; }
  [[nodiscard]] std::span<const double> temperatures() const { return scene_.bodies.temperature; }
  [[nodiscard]] std::span<const double> heatCapacities() const { return scene_.bodies.heatCapacity; }
  [[nodiscard]] std::span<const double> conductivities() const { return scene_.bodies.conductivity; }
  [[nodiscard]] std::span<const double> thermalExpansions() const { return scene_.bodies.thermalExpansion; }

  /// The contact list, read only (pairs, overlaps, forces): for exchanges through the contacts,
  /// such as heat conduction between particles.
  [[nodiscard]] const Contacts& contacts() const { return scene_.contacts; }

  /// Add `change[i]` to the radius of each live sphere i (one value per body id, the others
  /// ignored) at fixed positions and masses (thermal expansion: Yade keeps the mass). The next
  /// contact pass sees the new overlaps; contacts are re-detected with the new sizes.
  /// @param change one radius change (m) per body id
  /// @throws std::invalid_argument for a size mismatch or a radius that would not stay positive
  void growSpheres(std::span<const double> change)
  {
    Bodies& b = scene_.bodies;
    if (change.size() != b.size())
      throw std::invalid_argument("growSpheres: " + std::to_string(change.size()) + " radius changes for " +
                                  std::to_string(b.size()) + " bodies");
    bool changed = false;
    for (std::size_t i = 0; i < b.size(); ++i) // checked first: a refusal changes nothing
      if (isSphere(static_cast<BodyId>(i)) && change[i] != 0)
      {
        if (!(b.radius[i] + change[i] > 0) || !std::isfinite(change[i]))
          throw std::invalid_argument("growSpheres: sphere " + std::to_string(i) + " of radius " +
                                      std::to_string(b.radius[i]) + " cannot change by " + std::to_string(change[i]));
        changed = true;
      }
    if (!changed)
      return;
    for (std::size_t i = 0; i < b.size(); ++i)
      if (isSphere(static_cast<BodyId>(i)))
        b.radius[i] += change[i];
    ++scene_.bodiesVersion;
  }

  /// Per body id, writable: the persistent force and torque (N, N m; kept until changed) and
  /// this step's accumulators (reset by the ForceResetter from the persistent ones).
  /// @return spans over the core's storage, one entry per body id, valid until bodies are added
  [[nodiscard]] std::span<Vec3> persistentForces() { return scene_.bodies.extForce; }
  [[nodiscard]] std::span<Vec3> persistentTorques() { return scene_.bodies.extTorque; }
  [[nodiscard]] std::span<Vec3> stepForces() { return scene_.bodies.force; }
  [[nodiscard]] std::span<Vec3> stepTorques() { return scene_.bodies.torque; }

  /// The clock: simulated time (s), time step (s), step count; the periodic cell, if any.
  [[nodiscard]] double time() const { return scene_.time; }
  [[nodiscard]] double dt() const { return scene_.dt; }
  [[nodiscard]] std::int64_t iter() const { return scene_.iter; }
  [[nodiscard]] bool periodic() const { return scene_.periodic; }
  [[nodiscard]] const Cell& cell() const { return scene_.cell; }

  /// Insert a hook engine calling `f` every `period` steps at `point` (remove it by setting its
  /// `dead`).
  /// @param point where in the step: after the ForceResetter, or before or after the
  ///        NewtonIntegrator
  /// @param f the coupling's call
  /// @param period steps between two calls, from the first step on
  /// @return the hook engine, already in the scene's engine list
  /// @throws std::logic_error if the engine list lacks the anchor engine
  std::shared_ptr<CallbackEngine> addHook(HookPoint point, std::function<void()> f, std::int64_t period = 1)
  {
    auto hook = std::make_shared<CallbackEngine>();
    hook->callback = std::move(f);
    hook->iterPeriod = period;
    hook->initRun = true;
    auto& engines = scene_.engines;
    auto find = [&](const std::string& type) {
      for (std::size_t k = 0; k < engines.size(); ++k)
        if (engines[k]->typeName() == type)
          return k;
      throw std::logic_error("cannot place a coupling hook: the engine list has no " + type);
    };
    std::size_t at = 0;
    switch (point)
    {
    case HookPoint::BeforeForces: at = find("ForceResetter") + 1; break;
    case HookPoint::AfterForces: at = find("NewtonIntegrator"); break;
    case HookPoint::AfterStep: at = find("NewtonIntegrator") + 1; break;
    }
    engines.insert(engines.begin() + static_cast<std::ptrdiff_t>(at), hook);
    return hook;
  }

private:
  Scene& scene_;
};
} // namespace talus::dem
