#pragma once

#include <cstddef>
#include <span>

namespace talus::dem
{
class Scene;

/// How a scene is split over processes, as the step and the measurements see it. A serial
/// scene has none (Scene::domain is null) and every call site then does what it always did;
/// dem/distributed/ provides the MPI one. The step calls the domain at fixed points (its
/// communication stages) so that no engine calls MPI itself; measurements call its reductions so
/// that a script reads global answers on every process.
class Domain
{
public:
  virtual ~Domain() = default;

  /// Rows [0, ownedBodies) of the scene's bodies are this process's; the rows after them are
  /// ghosts, read-only copies of bodies other processes own. Resetting forces, gathering them and
  /// integrating touch owned rows only; detection and contacts see all rows.
  virtual std::size_t ownedBodies(const Scene& scene) const = 0;

  /// The skin check's answer for the whole run: true on every process when any needs a
  /// re-detection (all processes re-detect together).
  virtual bool anyProcess(bool local) const = 0;

  /// Before the collider re-detects: bodies that left this process's region move to their new
  /// owner with their contacts' state, and the ghost layer is rebuilt (rebalancing when due).
  /// @throws std::runtime_error naming the body when one moved further than the ghost layer allows
  virtual void beforeDetection(Scene& scene) = 0;

  /// After the integration: every ghost takes its owner's new state.
  virtual void afterIntegration(Scene& scene) = 0;

  /// Element-wise sums over processes, in place (energies, unbalanced force, stresses).
  virtual void sum(std::span<double> values) const = 0;

  /// The smallest value over processes (critical time steps).
  virtual double min(double value) const = 0;
};
} // namespace talus::dem
