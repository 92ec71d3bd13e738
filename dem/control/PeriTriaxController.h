#pragma once

#include "dem/core/Engine.h"
#include "dem/base/types.h"

#include <functional>
#include <limits>

namespace talus::dem
{
class Scene;

/// Yade's PeriTriaxController: drives the diagonal of the periodic cell's velocity gradient so
/// that each axis reaches its goal, a stress (bit i of stressMask set; Love-Weber stress,
/// compression negative) or a logarithmic strain log(trsf_ii). Run it after the
/// InteractionLoop, before the NewtonIntegrator (which deforms the cell).
///
/// Stress control: without dynCell, the strain increment is the stress gap over the mean
/// contact stiffness per axis (goal - stress) A / K, smoothed as (1 - growDamping) rate + 0.8
/// previous rate; with dynCell, the cell is a mass accelerated by the stress gap with Cundall
/// damping growDamping. Rates are capped at maxStrainRate. When every axis is within tolerance
/// (relStressTol or absStressTol for stresses, 1e-6 for strains) and the unbalanced force is
/// below maxUnbalanced, doneHook is called (every step while it stays so, as in Yade).
class PeriTriaxController : public Engine
{
public:
  void run(Scene& scene) override;
  [[nodiscard]] std::string typeName() const override { return "PeriTriaxController"; }

  // parameters
  Vec3 goal = Vec3::Zero();
  int stressMask = 0;
  Vec3 maxStrainRate = Vec3::Ones();
  double maxUnbalanced = 1e-4;
  double absStressTol = 1e3;
  double relStressTol = 3e-5;
  double growDamping = 0.25;
  int globUpdate = 5;
  bool dynCell = false;
  double mass = std::numeric_limits<double>::quiet_NaN(); ///< cell mass (dynCell); NaN: total mass of the bodies
  std::function<void()> doneHook;

  // state and read-outs
  Vec3 stress = Vec3::Zero();       ///< diagonal of stressTensor
  Vec3 strain = Vec3::Zero();       ///< log of the diagonal of the cell's trsf
  Vec3 strainRate = Vec3::Zero();   ///< diagonal of velGrad
  Vec3 stiff = Vec3::Zero();        ///< mean contact stiffness per axis
  Mat3 stressTensor = Mat3::Zero(); ///< Love-Weber stress
  Vec3 prevGrow = Vec3::Zero();
  Vec3 maxBodySpan = Vec3::Zero();
  double currUnbalanced = std::numeric_limits<double>::quiet_NaN();
  double externalWork = 0;

private:
  void update(const Scene& scene);
};
} // namespace talus::dem
