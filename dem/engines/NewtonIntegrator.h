#pragma once

#include "dem/core/Bodies.h"
#include "dem/core/EnergyTracker.h"
#include "dem/core/Engine.h"
#include "dem/base/Threads.h"
#include "dem/base/types.h"

#include <cstdint>
#include <vector>

namespace talus::dem
{
/// Leap-frog integration of Newton's and Euler's equations (Yade's NewtonIntegrator).
///
/// For each dynamic body: a = F/m + g, then Cundall's non-viscous damping on each component,
/// a_i <- a_i (1 - damping sign(a_i (v_i + a_i dt/2))) (gravity is damped too, as in Yade);
/// v += a dt; x += v dt. Rotation of spheres: the same with torque / inertia, and the
/// orientation turned by the rotation vector omega dt. Blocked DOFs keep their velocity.
/// Non-dynamic bodies move with their imposed velocities. A body whose `damped` flag is 0
/// (Yade's State.isDamped = False) is not damped.
///
/// Clumps: the forces and torques of the members are added to the clump's (in member order),
/// the clump is integrated and its members are placed rigidly. Aspherical bodies (clumps, boxes)
/// rotate by Yade's exactAsphericalRot: the world angular momentum is integrated with the
/// (damped) torque and the orientation follows from the angular velocity in the principal frame,
/// a mid-step predictor for the quaternion (Yade's leapfrogAsphericalRotate, reproduced exactly).
class NewtonIntegrator : public Engine
{
public:
  void run(Scene& scene) override;
  [[nodiscard]] std::string typeName() const override { return "NewtonIntegrator"; }
  /// The integration, per body.
  [[nodiscard]] Stages stages() const override { return Stages{}.with(StagePoint::Integration, Grain::PerBody); }

  Vec3 gravity = Vec3::Zero();
  double damping = 0.2; ///< Yade's default
  bool dampGravity = true; ///< false: gravity is added after the damping, which leaves it whole (Yade's)
  /// Positive: only the bodies whose group mask shares a bit with it move; the others keep
  /// their position, orientation and velocities (Yade's NewtonIntegrator.mask; default -1: all).
  int mask = -1;

  // The pieces of run() for the step's scheduler, which runs the loop in its own parallel regions.
  /// Refresh what the step reads of the bodies if they changed; tracking energy, size the
  /// tracker's memory of the bodies' imposed displacements.
  void prepare(Scene& scene);
  /// Integrate the bodies [first, last) (after prepare; a region's threads take disjoint ranges).
  /// @param first first body id; a multiple of energyBlock when tracking energy
  /// @param last one past the last body id
  /// @param energyBlocks null: no energy tracking; else `first` is a multiple of energyBlock and
  /// body i's terms (gravity's work, the damping's dissipation, the imposed motions' work over
  /// the step) are added to energyBlocks[i / energyBlock] (run()'s blocks)
  /// @return the first body of the range with a non-finite force or torque, or -1 (the caller
  ///         hands the smallest over all ranges to finish)
  std::int64_t integrateIn(Scene& scene, std::int64_t first, std::int64_t last, BodyEnergy* energyBlocks) const;
  /// Add the blocks' energies to the scene's tracker, in block order (as run() does).
  /// @param blocks the energy terms per block of energyBlock bodies, filled by integrateIn
  static void addEnergy(Scene& scene, const std::vector<BodyEnergy>& blocks);
  /// After every range: stop the run if a body had a non-finite force (firstBad >= 0), else move
  /// the periodic cell.
  /// @param firstBad the smallest integrateIn result over all ranges that found a bad body, or -1
  /// @throws std::runtime_error naming the body, the time step and the P-wave estimate
  void finish(Scene& scene, std::int64_t firstBad);
  /// A clump sums its members' forces and moves them: bodies other than its own (after prepare).
  [[nodiscard]] bool hasClumps() const { return hasClumps_; }

private:
  // 1/m and 1/I of every body (0 where blocked or not dynamic), refreshed when bodies change,
  // so the step multiplies instead of dividing.
  void refreshInverses(const Scene& scene);
  /// The step for every body; Track: accumulate gravity's work and the damping's dissipation.
  /// @return the first body with a non-finite force or torque, or -1
  template <bool Track>
  std::int64_t integrate(Scene& scene) const;
  /// The bodies [first, last); the first with a non-finite force or torque, or the body count.
  template <bool Track>
  std::int64_t integrateRange(Scene& scene, std::int64_t first, std::int64_t last, double& gravWorkSum,
                              double& dampSum) const;
  /// One clump or aspherical body (the rare path, out of the sphere loop); Track: add gravity's
  /// work and the damping's dissipation to gravWork and damp.
  template <bool Track>
  void integrateRigid(Bodies& b, std::size_t i, const Vec3& force, const Vec3& torque, double dt, double& gravWork,
                      double& damp) const;
  std::vector<Vec3> invMass_, invInertia_;
  /// Per body: 0 for the plain path, else Mode bits.
  enum Mode : std::uint8_t
  {
    Member = 1,     ///< clump member: moved by its clump
    ClumpBody = 2,  ///< sums its members' forces and moves them
    Aspherical = 4, ///< exact rotation of an aspherical body
    Masked = 8,     ///< left out by `mask`
  };
  std::vector<std::uint8_t> mode_;
  bool hasClumps_ = false;
  std::int64_t seenBodiesVersion_ = -1, seenPropertiesVersion_ = -1;
  int seenMask_ = -1;
  mutable BalancedRanges ranges_; ///< bodies per thread (their timing only)
};

/// Book the work that the cell's motion does on the contacts with a periodic image over the step
/// about to be integrated: L H c times the force on body 2 of each (the image moves with the
/// cell), L the mean of the previous and the current step's velocity gradient, into
/// velGradWork. The bodies' share of the imposed motions' work is the integration's (its energy
/// blocks, integrateIn); both before the cell is integrated (finish).
/// @param scene a periodic scene tracking energy (nothing is booked otherwise)
void addPeriodicImageWork(Scene& scene);
} // namespace talus::dem
