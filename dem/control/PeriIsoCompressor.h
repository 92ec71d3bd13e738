#pragma once

#include "dem/core/Engine.h"
#include "dem/base/types.h"

#include <functional>
#include <vector>

namespace talus::dem
{
class Scene;

/// Yade's PeriIsoCompressor: compresses (or dilates) the periodic cell until each of `stresses`
/// is reached in turn with the unbalanced force below maxUnbalanced, then calls doneHook (once,
/// after the last). Run it after the InteractionLoop, before the NewtonIntegrator.
///
/// Its stress is Yade's own measure, not the Love-Weber stress: per axis, the sum over contacts
/// of the magnitude of the contact force's component, over the cell's face area (a larger
/// number than the mean stress of the packing: Yade's randomDensePack asks for -1e8 with it and
/// gets about -7e6 Pa of mean stress). Every globalUpdateInt steps it is recomputed with the
/// mean isotropic contact stiffness K = (kn + 2 ks) / 3; in between it is predicted from K.
/// The cell grows per step by 1e-4 (goal - stress) A / K (Yade's empirical factor), at most
/// maxDisplPerStep (default 1e-2 charLen), and never below 2.1 times the largest sphere.
/// keepProportions: one homothetic growth from the averages of the three axes; otherwise each
/// axis on its own. A stress is reached within 0.5 %.
class PeriIsoCompressor : public Engine
{
public:
  void run(Scene& scene) override;
  [[nodiscard]] std::string typeName() const override { return "PeriIsoCompressor"; }

  // parameters
  std::vector<double> stresses;
  double charLen = -1;         ///< characteristic length; <= 0: mean size of body 0's bounding box
  double maxSpan = -1;         ///< largest sphere diameter; <= 0: found at the first step
  double maxUnbalanced = 1e-4;
  int globalUpdateInt = 20;
  double maxDisplPerStep = -1; ///< < 0: 1e-2 charLen
  bool keepProportions = true;
  std::function<void()> doneHook;

  // state and read-outs
  std::size_t state = 0;       ///< index of the stress being reached
  Vec3 sigma = Vec3::Zero();   ///< the stress measure above, per axis (compression negative)
  double avgStiffness = -1;
  double currUnbalanced = -1;
};
} // namespace talus::dem
