#pragma once

#include "dem/Threads.h"

#include <cstdint>
#include <utility>
#include <vector>

namespace talus::dem
{
class Scene;
class ContactLaw;
struct Contacts;

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
  /// The contacts of thread `thread` of `threads` (see boundaryRuns_); the first bad one's
  /// index, or the contact count.
  std::int64_t computeContacts(Scene& scene, ContactLaw& law, int thread, int threads);
  /// boundaryRuns_ for the current contact list.
  void findBoundaryRuns(const Contacts& contacts);

  /// The contacts of each wall, facet or box (runs of the list, each sorted by the sphere's id)
  /// are computed by the threads that integrate their spheres, not by whichever thread's range
  /// of the list they fall in: they lie at the list's end when the boundary was created last,
  /// and the last thread then read the state of the other threads' spheres along the boundary,
  /// whose next integration had to wait for those cache lines (Yade's speed-test scene: steps
  /// 4 % shorter at two threads). Empty beyond maxBoundaryRuns runs (a large mesh): then every
  /// thread takes one contiguous range of the list.
  std::vector<std::pair<std::int64_t, std::int64_t>> boundaryRuns_;
  std::int64_t boundaryContacts_ = 0; ///< contacts in boundaryRuns_
  std::uint64_t runsVersion_ = 0;     ///< the Contacts::version boundaryRuns_ was found for
  static constexpr std::size_t maxBoundaryRuns = 64;

  std::int64_t aheadFor_ = -1; ///< the scene.iter whose step the ahead check is for, or -1
  bool movedAhead_ = false;    ///< the ahead check: a body moved beyond half the skin
  BalancedRanges bodyRanges_;    ///< bodies per thread: reset, skin check, gather, integration
  BalancedRanges contactRanges_; ///< contacts per thread
};
} // namespace talus::dem
