#pragma once

#include "dem/measure/Measurements.h"
#include "dem/core/Scene.h"

#include <Eigen/Dense>
#include <memory>
#include <string>
#include <vector>

namespace talus::dem
{
class Collider;
using Mat6 = Eigen::Matrix<double, 6, 6>;

/// How an RVE's DEM scene is stepped: the contact law of its only InteractionLoop (Yade's Law2
/// name) and the NewtonIntegrator's numerical damping. The RVE file holds the state; the
/// engines are rebuilt from these (a checkpoint does not store C++ engines).
struct RVEEngines
{
  std::string law = "Law2_ScGeom_FrictPhys_CundallStrack";
  double damping = 0.2;
};

/// Micro-structural state of an RVE, reported per Gauss point.
struct RVEState
{
  double porosity = 0;
  double voidRatio = 0;
  double coordination = 0; ///< 2 Nc / N
  Mat3 fabric = Mat3::Zero();
  /// Mean over the spheres of their rotation vectors since the RVE was created (rad).
  Vec3 meanRotation = Vec3::Zero();
};

/// Velocity gradient of DEM step k (0-based) of an increment `grad` over `nSteps` steps of `dt`:
/// L dt = (grad / n) (I + k / n grad)^-1, which takes the cell from (I + k/n grad) H0 to
/// (I + (k+1)/n grad) H0. (One definition, also used by talus.fem.direct's reference runs, so
/// that they apply the very same numbers.)
/// @param grad the increment's displacement gradient du/dX, relative to its start
/// @param k the DEM step within the increment, 0 <= k < nSteps
/// @param nSteps the DEM steps the increment takes
/// @param dt the DEM time step (s)
/// @return the velocity gradient L (1/s) the periodic cell follows during step k
[[nodiscard]] Mat3 subStepVelocityGradient(const Mat3& grad, int k, int nSteps, double dt);

/// A representative volume element: one periodic DEM scene owned here, with a committed state
/// (the last converged one of the finite-element Newton iterations) and a trial state. This
/// is the DEM core's interface to a continuum (FEM x DEM, fem/): a displacement gradient in,
/// stress, tangent and micro-structure out; fem/ uses the DEM through it only.
///
/// `deform(G, n)` always starts from the committed state and imposes the displacement gradient
/// G = du/dX (relative to the committed configuration) on the periodic cell over n DEM steps,
/// stretch and rotation together, so that the cell ends exactly at (I + G) H_committed: step k
/// uses the velocity gradient L_k dt = (G / n) (I + (k - 1) / n G)^-1, i.e. the displacement
/// grows linearly in the committed configuration (the seed's updated Lagrangian increment).
/// `commit()` makes the trial state the committed one; `rollback()` returns to the committed
/// state. The committed state is a copy in memory of the bodies, contacts, cell and clock.
class RVE
{
public:
  /// Take a copy of the state of a periodic scene (materials, bodies, contacts, cell, clock and
  /// the scene's settings: overlap and energy checks, energy tracking, timing);
  /// its engines are not shared, the RVE builds its own from `engines`.
  /// @param source the periodic scene copied (left as it is)
  /// @param engines the contact law and damping of the RVE's own engines
  /// @param name how errors name this RVE (a Gauss point, say)
  /// @throws std::invalid_argument naming `name` if the scene is not periodic or has no sphere,
  ///         or naming the law if `engines.law` is not a registered contact law
  RVE(const Scene& source, const RVEEngines& engines, const std::string& name = "scene");
  /// Load an RVE from a Talus checkpoint file (O.save).
  /// @param path the checkpoint file; it also names the RVE in errors
  /// @param engines the contact law and damping of the RVE's own engines
  /// @return the RVE, its committed state the file's
  /// @throws std::invalid_argument naming the file when it does not exist, is not a checkpoint
  ///         (or this build has no HDF5), is not periodic or has no sphere
  static RVE load(const std::string& path, const RVEEngines& engines);

  /// Deform from the committed state by the displacement gradient `grad` over `nSteps` steps.
  /// @param grad the displacement gradient du/dX relative to the committed configuration
  /// @param nSteps the DEM steps it is imposed over, >= 1
  /// @throws std::invalid_argument if grad is not finite, det(I + grad) <= 0 or nSteps < 1
  /// @throws std::runtime_error if a DEM step fails (the committed state is kept)
  void deform(const Mat3& grad, int nSteps);
  /// Make the trial state (the last deform's) the committed one.
  void commit();
  /// Return to the committed state; nothing to do without a trial state.
  void rollback();
  /// True when the scene holds a trial state (deform was called after the last commit/rollback).
  [[nodiscard]] bool hasTrial() const { return trial_; }

  /// Love-Weber stress (compression negative) and the contact-stiffness tangent of the current
  /// (trial or committed) state, by dem's loveWeberStress and contactStiffnessTangent.
  /// @return the stress (Pa) over the cell's volume
  [[nodiscard]] Mat3 stress() const;
  /// @param form which contact-stiffness tangent (see TangentForm)
  /// @return the 6x6 tangent (Pa) in Voigt order xx, yy, zz, yz, xz, xy
  [[nodiscard]] Mat6 tangent(TangentForm form = TangentForm::Full) const;
  /// @return porosity, void ratio, coordination, fabric and mean rotation of the current state
  [[nodiscard]] RVEState state() const;

  /// The RVE's own scene, read only (the RVE owns it; its state is the trial or committed one).
  [[nodiscard]] const Scene& scene() const { return scene_; }
  /// The name given at creation, used in error messages.
  [[nodiscard]] const std::string& name() const { return name_; }

private:
  RVE(const std::string& name) : name_(name) {}
  void setUp(const RVEEngines& engines);
  void restore(bool failed = false);

  struct Snapshot
  {
    Bodies bodies;
    Contacts contacts;
    Cell cell;
    double time = 0;
    std::int64_t iter = 0;
  };
  std::string name_;
  Scene scene_;
  Snapshot committed_;
  /// The RVE's collider and its rebuild count at the last commit: a rollback forces a new
  /// contact detection only if the collider rebuilt its candidate list during the trial
  /// (otherwise the committed list still matches the collider's reference positions).
  std::shared_ptr<Collider> collider_;
  std::int64_t committedRebuilds_ = -1;
  std::vector<Quat> initialOri_;
  bool trial_ = false;
};
} // namespace talus::dem
