#pragma once

#include "dem/base/Threads.h"
#include "dem/contact/Collider.h"
#include "dem/core/EnergyTracker.h"
#include "dem/core/Stage.h"
#include "dem/step/ContactShares.h"
#include "dem/step/GatherAhead.h"

#include <array>
#include <cstdint>
#include <vector>

namespace talus::dem
{
class Scene;
class ContactLaw;
class InteractionLoop;
class NewtonIntegrator;

/// The shared stages of a step (StepPlan): reset, skin check, detection, contacts, gather and
/// integration in as few OpenMP parallel regions as the plan allows.
///
/// Why: a parallel region costs a few microseconds at two threads and a barrier inside one
/// about half as much, a noticeable part of a step of a few thousand spheres (docs/dem.md,
/// Speed). Each thread keeps one range of bodies for the reset, the skin check, the gather and
/// the integration, so those need no barrier between them; the contacts need one before the
/// gather. The step's flows (the counts are StepPlan's):
/// - alone (no serial stage, an open scene without clumps, serial): each thread checks the skin
///   of its bodies right after moving them, for the next step of the same run; a step then
///   re-detects (when it must) before its one region, which has one barrier, after the contacts;
/// - with serial stages: the skin check in the region, a barrier after it and, when the
///   collider re-detects, a second region after the re-detection;
/// - distributed, or contacts as a serial call (several laws, callbacks): a region for the reset
///   and the skin check, then, between regions, the reduction over processes, the migration
///   and re-detection, the serial contacts, then a region for the rest;
/// - serial stages between the gather and the integration, or energy tracked: the integration
///   in a region of its own after them (and after the imposed motions' work).
/// Per-body stages take the rows [0, scene.ownedBodies()); detection and contacts all rows.
///
/// The engines' own range functions do the work, item by item as their run() does, so the
/// step gives the same bits whatever the threads (tests/dem/step/test_threads.py). Scenes of
/// fewer bodies and contacts than parallelLoopMinimum run the same regions with one thread.
class SharedRegions
{
public:
  /// The engines whose range functions run the shared stages.
  struct Engines
  {
    Collider& collider;
    InteractionLoop& loop;
    NewtonIntegrator& newton;
  };
  /// What the forces' regions include (from the plan).
  struct Flow
  {
    bool reset = true;            ///< the reset (else it ran in a region of its own before)
    bool contactsInRegion = true; ///< the contacts split among the threads (else one serial call)
    bool integrate = true;        ///< each thread integrates its bodies right after gathering them
    /// No other engine runs between this step's integration and the next step's reset: the
    /// skin may be checked ahead.
    bool alone = false;
  };
  /// Start a step's shared stages.
  void begin(const Scene& scene);
  /// The reset alone, before the serial stages between it and the skin check.
  void reset(Scene& scene);
  /// Reset, skin check (and re-detection when due), contacts, gather and integration, as `flow` says.
  /// @param engines the plan's collider, loop and integrator, prepared for this step
  /// @param flow which of the stages the regions include (from the plan)
  /// @throws std::runtime_error as the engines' run() would: a contact overlapping too much
  ///         (scene.overlapStops), a body with a non-finite force
  void forces(Scene& scene, const Engines& engines, Flow flow);
  /// The integration alone, after the serial stages between the gather and the integration.
  /// @param newton the plan's integrator
  /// @throws std::runtime_error for a body with a non-finite force or torque (NewtonIntegrator::finish)
  void integrate(Scene& scene, NewtonIntegrator& newton);
  /// After a step's shared stages: the stages' times, and the threads' ranges balanced by the
  /// time each took.
  void stepDone();
  /// Forget the skin check made ahead for the next step: the caller may move bodies before it.
  void forgetAhead() { aheadFor_ = -1; }

  /// Wall seconds of each stage in the last step (the longest thread's time inside regions,
  /// barrier waits included), when scene.timingEnabled.
  std::array<double, stagePoints> stageSeconds{};
  int regions = 0, barriers = 0; ///< entered in the last step (diagnostics, tests)

private:
  /// Each thread's flags and times of one step, a cache line apiece (they are written during it).
  struct Team
  {
    struct alignas(64) Member
    {
      Collider::Displacements moved, movedAhead;
      std::int64_t badContact = -1, badBody = -1;
      double bodySeconds = 0, contactSeconds = 0;
      std::array<double, stagePoints> stage{}; ///< with timing: seconds per stage
      double mark = 0;                         ///< with timing: when the last stage ended
    };
    std::array<Member, BalancedRanges::maxThreads> members{};
    int used = 1;        ///< threads that worked
    bool timing = false; ///< scene.timingEnabled
    /// The smallest index the threads report through `field`, -1 if none.
    [[nodiscard]] std::int64_t first(std::int64_t Member::*field) const;
    /// With timing: the time since member m's last lap goes to `point`.
    void lap(Member& m, StagePoint point) const;
  };
  /// The skin check's state through a step.
  struct Skin
  {
    Collider::SkinCheck check;        ///< around the current references
    bool checkAhead = false;          ///< this step's integration checks the skin for the next step
    bool checkNow = false;            ///< the first region checks the skin
    bool moved = false;               ///< the check in the region calls for a re-detection
    Collider::Displacements measured; ///< that check, all threads together
  };
  /// The region's work of each thread after the skin check: contacts (with `law`; the bodies
  /// they complete gathered as they go, GatherAhead), a barrier, then its bodies: the rest of
  /// the gather, and with `flow.integrate` integrate and check ahead.
  void contactsThenBodies(Scene& scene, const Engines& engines, ContactLaw* law, Flow flow, const Skin& skin,
                          const Collider::SkinCheck& ahead, int thread, int threads);
  /// The bodies are gathered as the contacts stage goes (GatherAhead), their reset with them.
  static bool gathersAhead(const Scene& scene, const ContactLaw* law, Flow flow);
  /// Each thread's reset (with flow.reset) and skin check; in one region with the rest when
  /// `rest` (and the skin did not call for a re-detection).
  void resetAndCheck(Scene& scene, const Engines& engines, ContactLaw* law, Flow flow, Skin& skin, bool rest);
  /// The skin check's verdict over the threads (and processes), then the re-detection when due.
  void settleSkin(Scene& scene, const Engines& engines, ContactLaw* law, Skin& skin);
  /// The contact list changed: aligned richer state, boundary runs, energy blocks.
  void listChanged(Scene& scene, ContactLaw* law);
  /// Re-detect now: a new contact list, new references (timed as the detection stage).
  void redetect(Scene& scene, Collider& collider, ContactLaw* law, Skin& skin);
  /// Add the seconds since `start` to a stage run between regions (with timing).
  void serialLap(StagePoint point, double start);
  /// After the contacts: the law's step end, their energy, the first overlap's report.
  void contactsDone(Scene& scene, const Engines& engines, ContactLaw* law);
  /// After the integration: a body's non-finite force, the ahead check, the ghosts' update.
  void integrationDone(Scene& scene, const Engines& engines, const Skin& skin);
  /// Before the integration: the integrator's view of the bodies and, with energy tracked, one
  /// energy block per energyBlock owned bodies.
  void prepareIntegration(Scene& scene, NewtonIntegrator& newton);
  /// With energy tracked, the integration's energy blocks and the periodic images' work into
  /// the tracker (before the cell moves).
  void bodyEnergyDone(Scene& scene);
  /// Enter a parallel region running body(thread, threads) on every thread of the team.
  template <class Body>
  void region(Scene& scene, const Body& body);

  ContactShares contactShares_;
  GatherAhead gatherAhead_;
  /// With energy tracked, the step's energy sums per block of contacts and of bodies (the
  /// engines' blocks: the same sums whatever the threads' ranges).
  std::vector<ContactEnergy> contactEnergy_;
  std::vector<BodyEnergy> bodyEnergy_;

  Team team_;                  ///< the step running's
  std::int64_t aheadFor_ = -1; ///< the scene.iter whose step the ahead check is for, or -1
  bool movedAhead_ = false;    ///< the ahead check: a body moved beyond half the skin
  BalancedRanges bodyRanges_;  ///< bodies per thread: reset, skin check, gather, integration
};
} // namespace talus::dem
