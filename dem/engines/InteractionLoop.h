#pragma once

#include "dem/laws/ContactLaw.h"
#include "dem/core/Engine.h"
#include "dem/laws/IntrCallback.h"

#include <memory>
#include <vector>

namespace talus::dem
{
/// Contact forces of a step (Yade's InteractionLoop): updates the geometry of every candidate
/// pair, gives each new contact to the most specific law that handles its materials, lets each
/// law compute its forces, then sums forces and torques per body in a fixed order.
class InteractionLoop : public Engine
{
public:
  void run(Scene& scene) override;
  [[nodiscard]] std::string typeName() const override { return "InteractionLoop"; }
  /// Contacts per contact with one law and no callbacks, else serial (computeContacts, whose
  /// loops are parallel); the gather per body.
  [[nodiscard]] Stages stages() const override;

  std::vector<std::shared_ptr<ContactLaw>> laws;
  /// Yade's InteractionLoop.callbacks (called for every real contact after the forces).
  std::vector<std::shared_ptr<IntrCallback>> callbacks;

  // The pieces of run() for the step's scheduler, which runs them in its own parallel regions.
  /// The checks run() makes before touching the contacts.
  /// @throws std::runtime_error without laws, with more than 255, or (single law) with
  ///         materials or shapes the law cannot handle
  void prepare(Scene& scene);
  /// The contacts stage as one serial call (after prepare): every contact's geometry and force,
  /// law by law, the growth's energy, the overlap check and the callbacks.
  /// @throws std::runtime_error for a contact no law handles or one overlapping too much
  void computeContacts(Scene& scene);
  /// Add the forces and moments of the contacts of bodies [first, last) to those bodies, each
  /// body's contacts in index order (the sums do not depend on the thread count).
  /// @param first first body id of the share
  /// @param last one past the last; bodies added since the last detection are skipped (no
  ///        contacts yet)
  /// @param reset each body's force and torque become its permanent ones (ForceResetter) plus
  ///        its contacts', in the same pass, instead of the contacts' being added to them
  void gatherIn(Scene& scene, std::int64_t first, std::int64_t last, bool reset = false) const;
  /// The error message for a contact overlapping beyond scene.maxOverlapRatio.
  /// @param c the contact, its penetration that of this step
  /// @return the message: step, body ids, overlap as a fraction of the smaller radius, the time
  ///         step and the contact's and P-wave critical steps
  static std::string overlapReport(const Scene& scene, const Contact& c);
  /// A step had contact c overlapping beyond scene.maxOverlapRatio: throw its report, or, when
  /// scene.overlapStops is false, count the step and keep the first report.
  /// @param c the contact overlapping too much
  /// @throws std::runtime_error (overlapReport's message) if scene.overlapStops
  static void overlapFound(Scene& scene, const Contact& c);

private:
  void assignLaw(Contact& c, ContactExtra* x, const Scene& scene) const;
  /// With a single law: check once per material count that it handles every material pair.
  void checkMaterials(const Scene& scene);
  /// With a single law: check once per change of the bodies that its model applies to the
  /// contacts their shapes can make (spheres, Potential Blocks, Potential Particles; a mixed
  /// scene needs a law for each).
  void checkShapes(const Scene& scene);
  /// Several laws: geometry and law assignment in one pass, then each law's forces.
  void computeWithSeveralLaws(Scene& scene) const;
  /// Add every contact's force and moment to its two bodies, body by body in a fixed order,
  /// so the sums do not depend on the number of threads.
  void sumForcesPerBody(Scene& scene);
  /// The contacts' state when one of the laws may leave moments (rolling and twisting
  /// resistance) for the gather to add to the torques, else null.
  const ContactExtra* contactMoments(const Contacts& contacts) const;
  std::size_t checkedMaterials_ = 0;
  std::int64_t checkedBodiesVersion_ = -1;
  BalancedRanges gatherRanges_; ///< the gather's bodies per thread
};

/// Book into growthWork the part of the elastic energy of the contacts that became real in this
/// pass of `loop` that the radii's growth since the last pass (EnergyTracker::grownBy) made:
/// spheres grown into each other overlap by the growth at once, the energy of that overlap is the
/// growth's work, not the dynamics' (a contact that motion alone would have made real keeps the
/// energy of its overlap without the growth, as any new contact). Clears grownBy.
/// @param loop the loop whose laws' contacts are looked at (after its contacts pass)
void addGrownContactsEnergy(Scene& scene, const InteractionLoop& loop);
} // namespace talus::dem
