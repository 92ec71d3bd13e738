#pragma once

#include "dem/core/EnergyTracker.h"
#include "dem/base/Threads.h"

#include <cstddef>
#include <cstdint>
#include <functional>
#include <utility>
#include <vector>

namespace talus::dem
{
class Scene;
class Collider;
class ContactLaw;
class InteractionLoop;
class NewtonIntegrator;
struct Contacts;

/// The usual step — ForceResetter, a collider, an InteractionLoop with one law, NewtonIntegrator
/// — in one OpenMP parallel region instead of the engines' five, with any other engines before,
/// after, or between the loop and the integrator run in their place.
///
/// Why: on the project's 2-vCPU guest a parallel region costs 3.5 µs at two threads and a barrier
/// inside one 2 µs, about 8 % of a 4 400-sphere step (docs/dem.md, Speed). Here each thread keeps
/// one range of bodies for the reset, the skin check, the force gather and the integration, so
/// those need no barrier between them. When the usual engines are alone, in an open scene
/// without clumps, each thread checks the skin of its bodies right after moving them, for the
/// next step of the same run(): such a step re-detects (when it must) before its one region,
/// which has one barrier, after the contact loop. Otherwise the skin check is made in the step,
/// with a barrier after it and, when the collider re-detects, a second region after the
/// re-detection. Engines between the loop and the integrator (force engines, couplings) run
/// after the gather, and the integration in a region of its own after them.
///
/// With energy tracked, each thread's ranges of contacts and bodies start at multiples of
/// energyBlock, the blocks the engines sum energies in, and the integration runs after the
/// imposed motions' work, in a region of its own.
///
/// The engines' own range functions do the work, item by item as their run() does, so a fused
/// step gives the same bits as the engines one by one (tests/dem/step/test_threads.py). Scenes with
/// several laws or colliders or with timing on (which times each engine) take the engines'
/// path, and so do scenes of fewer bodies than parallelLoopMinimum.
class FusedStep
{
public:
  /// Runs engine k of the scene's list as the engines' path does (timing, errors).
  using EngineRunner = std::function<void(std::size_t)>;
  /// Run one step of `scene` if its engines include the usual ones, the others through
  /// `runEngine`; false (nothing done) otherwise.
  bool run(Scene& scene, const EngineRunner& runEngine);

  std::int64_t steps = 0; ///< steps run fused (diagnostics: Scene.fusedSteps)
  /// Wall seconds spent in the other engines of fused steps (diagnostics: what the step's own
  /// work took is the rest).
  double otherEnginesSeconds = 0;

  /// Forget the skin check made ahead for the next step: the caller may move bodies before it.
  void forgetAhead() { aheadFor_ = -1; }

private:
  struct Team; ///< the threads' flags and times of one step
  /// Reset, skin check (and re-detection when due), contacts and gather; with `newton`, each
  /// thread integrates its bodies right after gathering them. `alone`: no other engine runs
  /// between this step's integration and the next step's reset, so the skin may be checked ahead.
  void forces(Scene& scene, Collider& collider, InteractionLoop& loop, NewtonIntegrator* newton, Team& team,
              bool alone);
  /// The integration alone, after the engines between the loop and the integrator.
  void integrate(Scene& scene, NewtonIntegrator& newton, Team& team);
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

  /// With energy tracked, the step's energy sums per block of contacts and of bodies (the
  /// engines' blocks: the same sums whatever the threads' ranges).
  std::vector<ContactEnergy> contactEnergy_;
  std::vector<BodyEnergy> bodyEnergy_;

  std::int64_t aheadFor_ = -1; ///< the scene.iter whose step the ahead check is for, or -1
  bool movedAhead_ = false;    ///< the ahead check: a body moved beyond half the skin
  BalancedRanges bodyRanges_;    ///< bodies per thread: reset, skin check, gather, integration
  BalancedRanges contactRanges_; ///< contacts per thread
};
} // namespace talus::dem
