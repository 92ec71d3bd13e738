#pragma once

#include "dem/core/Engine.h"
#include "dem/impose/SampleOperations.h"
#include "dem/base/types.h"

#include <array>
#include <cstdint>

namespace talus::dem
{
class Scene;

/// The six walls of a triaxial cell, in Yade's order (indices into wall ids, stresses, ...).
enum TriaxialWall
{
  Left,
  Right,
  Bottom,
  Top,
  Back,
  Front
};

/// Yade's TriaxialStressController: six walls around a box of spheres, each axis servo-controlled
/// to a stress or a strain rate (stressMask bit 1, 2, 4 for x, y, z; goal1..3; tension positive).
/// Walls are Talus's infinite planes (wall(pos, axis)) by id, in Yade's order: left/right (x),
/// bottom/top (y), back/front (z), standing where Yade's box walls have their inner faces (as
/// aabbWalls puts them): the distances between planes are the sample's sizes, and `thickness`
/// (Yade's box thickness, subtracted there from the distances between box centres) is only
/// kept for scripts that read it. Run it after the InteractionLoop, before
/// the NewtonIntegrator (which moves the walls at the velocities set here).
///
/// Stress control: each wall moves by (force gap) / (sum of its contact stiffnesses), capped
/// at max_vel (shared between axes by box size) x dt, smoothed as (1 - stressDamping) x that
/// + 0.8 x the previous move. Strain-rate control: the wall velocity relaxes to goal x size / 2
/// with strainDamping. internalCompaction: walls stay, the spheres grow (by at most
/// maxMultiplier per radiusControlInterval steps, finalMaxMultiplier once the mean stress
/// exceeds the goal) until the mean stress reaches the goal.
///
/// The walls' forces, their stiffnesses and the spheres' volume are exact sums (dem/base/ExactSum.h)
/// over the walls' contacts and the spheres: split over processes (each holding the walls and
/// computing their contacts with its own spheres) the shares add up to the bits of one process,
/// so every process moves the walls alike, as one process would.
class TriaxialStressController : public Engine
{
public:
  void run(Scene& scene) override;
  [[nodiscard]] std::string typeName() const override { return "TriaxialStressController"; }

  /// Stresses, strains, sizes from the walls' positions and forces now (collective when the
  /// scene is split over processes).
  void computeStressStrain(const Scene& scene);

  // parameters (Yade's names and defaults)
  std::array<int, 6> wallIds{0, 1, 2, 3, 4, 5}; ///< left, right, bottom, top, back, front
  std::array<bool, 6> wallActivated{true, true, true, true, true, true};
  double goal1 = 0, goal2 = 0, goal3 = 0;
  unsigned stressMask = 7;
  bool internalCompaction = true;
  double maxMultiplier = 1.001;
  double finalMaxMultiplier = 1.00001;
  double max_vel = 1;
  double stressDamping = 0.25;
  double strainDamping = 0.99;
  double thickness = -1;
  unsigned stiffnessUpdateInterval = 10;
  unsigned radiusControlInterval = 10;
  unsigned computeStressStrainInterval = 10;
  bool updatePorosity = false;

  // read-outs and state
  std::array<Vec3, 6> stress{}; ///< mean stress vector on each wall (tension positive)
  std::array<Vec3, 6> force{};
  std::array<double, 6> stiffness{};
  std::array<Vec3, 6> previousTranslation{};
  Vec3 strain = Vec3::Zero(); ///< log(size / size0) per axis, extension positive
  double volumetricStrain = 0, meanStress = 0, porosity = 0, boxVolume = 0, particlesVolume = 0;
  double width = 0, height = 0, depth = 0, width0 = 0, height0 = 0, depth0 = 0;
  double externalWork = 0, previousStress = 0, previousMultiplier = 1;
  bool first = true;

  /// Inward unit normals of the six walls, in Yade's order.
  static const std::array<Vec3, 6> normal;

protected:
  /// The walls' rows (split over processes every process holds them, at rows of its own).
  /// @throws std::invalid_argument naming the wall for an id that is not a wall on its axis
  [[nodiscard]] std::array<std::size_t, 6> wallRows(const Scene& scene) const;

private:
  /// The walls' forces, and with `withStiffness` their stiffnesses into `stiffness`, and with
  /// `withVolume` the dynamic spheres' volume into particlesVolume: exact sums over the walls'
  /// contacts and the spheres, over every process (collective when split).
  [[nodiscard]] std::array<Vec3, 6> wallForces(const Scene& scene, const std::array<std::size_t, 6>& rows,
                                               bool withStiffness, bool withVolume);
  void stressStrainFrom(const Scene& scene, const std::array<std::size_t, 6>& rows,
                        const std::array<Vec3, 6>& forces);
  void controlExternalStress(Scene& scene, std::size_t row, int wall, const Vec3& wallForce, const Vec3& resultantForce,
                             double maxVelocity);
};

} // namespace talus::dem
