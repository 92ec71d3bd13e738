#pragma once

#include "dem/Threads.h"

#include <cstdint>

namespace talus::dem
{
class Scene;

/// The usual step — ForceResetter, Collider, InteractionLoop with one law, NewtonIntegrator and
/// no other engine — in one OpenMP parallel region instead of the engines' five.
///
/// Why: on the project's 2-vCPU guest a parallel region costs 3.5 µs at two threads and a barrier
/// inside one 2 µs, about 8 % of a 4 400-sphere step (docs/dem.md, Speed). Here each thread keeps
/// one range of bodies for the reset, the skin check, the force gather and the integration, so
/// those need no barrier between them. In an open scene without clumps, each thread checks the
/// skin of its bodies right after moving them, for the next step of the same run(): such a step
/// re-detects (when it must) before its one region, which has one barrier, after the contact
/// loop. Otherwise the skin check is made in the step, with a barrier after it and, when the
/// collider re-detects, a second region after the re-detection.
///
/// The engines' own range functions do the work, item by item as their run() does, so a fused
/// step gives the same bits as the engines one by one (tests/dem/test_threads.py). Scenes with
/// other engines, several laws, energy tracking or timing (which times each engine) take the
/// engines' path, and so do scenes of fewer bodies than parallelLoopMinimum.
class FusedStep
{
public:
  /// Run one step of `scene` if its engines are the usual ones; false (nothing done) otherwise.
  bool run(Scene& scene);

  std::int64_t steps = 0; ///< steps run fused (diagnostics: Scene.fusedSteps)

  /// Forget the skin check made ahead for the next step: the caller may move bodies before it.
  void forgetAhead() { aheadFor_ = -1; }

private:
  std::int64_t aheadFor_ = -1; ///< the scene.iter whose step the ahead check is for, or -1
  bool movedAhead_ = false;    ///< the ahead check: a body moved beyond half the skin
  BalancedRanges bodyRanges_;    ///< bodies per thread: reset, skin check, gather, integration
  BalancedRanges contactRanges_; ///< contacts per thread
};
} // namespace talus::dem
