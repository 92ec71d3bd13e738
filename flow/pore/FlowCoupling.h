#pragma once
// Couples the pore-scale flow to a DEM scene through the particle exchange interface only: reads
// the live spheres' positions and radii, rebuilds the pore network when due, solves the
// pressures and adds the fluid forces to this step's forces (Yade's FlowEngine in the engine
// list, before the NewtonIntegrator).
#include "dem/interface/Exchange.h"
#include "flow/pore/PoreFlow.h"

#include <array>
#include <functional>
#include <future>
#include <memory>
#include <optional>
#include <vector>

namespace talus::flow::pore
{
/// The pore flow's side of a coupled DEM step (Yade's FlowEngine as an engine): see step().
class FlowCoupling
{
public:
  /// @param exchange the scene's particle exchange (copied; the scene must outlive the coupling)
  /// @param flow the flow model, shared: Python keeps it to impose conditions and read results
  /// @throws std::invalid_argument if flow is null
  FlowCoupling(dem::ParticleExchange exchange, std::shared_ptr<PoreFlow> flow);

  /// Body receiving the force on boundary k (Yade's wallIds); -1: none. Must not be a sphere.
  std::array<dem::BodyId, kBoundaries> wallIds{-1, -1, -1, -1, -1, -1};
  /// Rebuild the pore network every this many calls (Yade's meshUpdateInterval); <= 0: never
  /// by count (Yade: a negative value never re-triangulates).
  int meshUpdateInterval = 1000;
  /// Rebuild as soon as a pore's volume changed by more than this fraction since the last mesh
  /// (Yade's defTolerance; <= 0: only every meshUpdateInterval). An inverted pore always
  /// triggers a rebuild at the end of the step, whatever the settings.
  double defTolerance = 0; // Yade 2023.02a's default: off
  /// Called after each rebuild, before the solve (Yade's blockHook): the place to impose
  /// conditions that need the new mesh.
  std::function<void()> blockHook;
  /// Build due meshes in a second thread while the old mesh and factor keep being used (Yade's
  /// multithread). Deterministic: the mesh of the positions at the end of step s (when the
  /// rebuild fell due) replaces the old one at the end of step s + backgroundSteps, waiting for
  /// the thread if it has not finished, so results never depend on thread timing. An inverted
  /// pore, spheres added or erased, or a requested rebuild still rebuild at once.
  bool multithread = false;
  /// Steps the old mesh stays in use after a background rebuild started (0: the same results
  /// as without multithread, the build merely runs in the other thread).
  int backgroundSteps = 10;
  /// The fluid forces (pressure and viscous) are computed but not added to the bodies (Yade's
  /// decoupleForces): the skeleton moves the fluid, not the other way round.
  bool decoupleForces = false;

  /// One coupling step: move the network's spheres (volume changes), solve, add the fluid
  /// forces (with the viscous options also the forces and torques between neighbouring spheres
  /// from the bodies' velocities, as Yade after its solve) to the step forces, then rebuild if due for the next step (interval, pore strain
  /// above defTolerance, a pore turned inside out; at once, before the solve, when requested or
  /// when spheres were added or erased).
  /// Periodic scenes need a periodic flow model (params.periodic, Yade's PeriodicFlowEngine):
  /// the cell size is read each step, and boundary k exists only if wallIds[k] >= 0.
  /// @throws std::invalid_argument if a wallIds entry names a sphere or a missing body, or the
  ///         scene and the flow model disagree on periodicity, or the cell is not orthorhombic
  void step();
  /// Rebuild at the next step (after moving walls or changing boundary types).
  void requestRebuild() { sinceBuild_ = -1; }

  /// The flow model: the same object throughout (a rebuild replaces its network in place).
  [[nodiscard]] const PoreFlow& flow() const { return *flow_; }
  /// The fluid forces of the last step, by body id (zero for bodies the flow does not see).
  [[nodiscard]] const std::vector<Vec3>& forces() const { return forces_; }
  /// The fluid torques of the last step (viscous shear or shear lubrication; zero without).
  [[nodiscard]] const std::vector<Vec3>& torques() const { return torques_; }
  /// Meshes built so far, the first included.
  [[nodiscard]] int rebuilds() const { return rebuilds_; }
  /// Rebuilds triggered by defTolerance or inverted pores (a subset of rebuilds()).
  [[nodiscard]] int strainRebuilds() const { return strainRebuilds_; }

  /// Insert the coupling in the scene's step (before the contact forces), every step.
  /// @param coupling the coupling; the hook holds a reference, so it lives as long as the hook
  ///        stays in the engine list
  /// @return the hook engine (set `dead` to stop the coupling)
  /// @throws std::logic_error if the engine list has no ForceResetter
  static std::shared_ptr<dem::CallbackEngine> attach(const std::shared_ptr<FlowCoupling>& coupling);

  /// A background rebuild is running or waiting to be adopted.
  [[nodiscard]] bool rebuildPending() const { return pending_.has_value(); }

private:
  /// The spheres of the scene now, and their body ids.
  std::vector<PoreSphere> liveSpheres(std::vector<dem::BodyId>& ids) const;
  void rebuild();
  /// Start building the mesh of the current positions in the other thread.
  void launchRebuild();
  /// Wait for the background mesh, put it in place of the old one, call blockHook.
  void adoptRebuild();
  /// Drop a background rebuild (waits for its thread).
  void discardRebuild();
  /// The viscous forces and torques between neighbouring spheres for the bodies' velocities,
  /// added to forces_ and torques_ (params.viscousShear, shearLubrication, normalLubrication).
  void addViscousForces();
  /// Move the network's spheres and the wall-following boundaries to the bodies' positions.
  void move();
  /// The bodies' positions of the network's spheres (sphereIds_) and the boundary positions of
  /// `net`, those following a wall body taken from it.
  void placement(const PoreNetwork& net, std::vector<Vec3>& at, std::array<double, kBoundaries>& walls) const;
  /// wallPosition of the boundaries that follow a wall body, from the body (before a build).
  void followWallBodies();
  /// A new mesh is in place: restart the interval count, count it, call blockHook.
  void rebuilt();
  /// Boundary k follows the wall body wallIds[k] (Yade: boundaryUseMaxMin false with a wall).
  [[nodiscard]] bool followsWall(int k) const;

  dem::ParticleExchange exchange_;
  std::shared_ptr<PoreFlow> flow_;
  std::vector<dem::BodyId> sphereIds_; ///< network vertex 6+i is body sphereIds_[i]
  std::vector<Vec3> forces_;
  std::vector<Vec3> torques_;
  struct PendingRebuild
  {
    std::future<std::unique_ptr<PoreFlow>> mesh;
    std::vector<dem::BodyId> sphereIds;
    int age = 0; ///< steps since it was launched
  };
  std::optional<PendingRebuild> pending_;
  int sinceBuild_ = -1;
  int rebuilds_ = 0;
  int strainRebuilds_ = 0;
};
} // namespace talus::flow::pore
