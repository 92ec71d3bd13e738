#pragma once

#include "dem/contact/ContactGeometry.h"
#include "dem/core/Cell.h"
#include "dem/core/Contacts.h"
#include "dem/core/EnergyTracker.h"
#include "dem/core/Material.h"
#include "dem/core/PairParameter.h"
#include "dem/base/Threads.h"

#include <algorithm>
#include <deque>
#include <functional>
#include <memory>
#include <string>
#include <vector>

namespace talus::dem
{
class Scene;

/// A contact model: how a contact's physics is set from the two materials when it becomes
/// real (Yade's Ip2 functor) and how forces follow from its kinematics (Yade's Law2 functor).
///
/// Each model is one file in dem/laws/, registered by name with TALUS_REGISTER_CONTACT_LAW;
/// adding one edits no other file. `computeForces` is called once per step and loops over the
/// contacts itself, so there is no virtual call per contact.
class ContactLaw
{
public:
  ContactLaw() = default;
  ContactLaw(const ContactLaw&) = delete;
  ContactLaw& operator=(const ContactLaw&) = delete;
  virtual ~ContactLaw() = default;

  /// Yade's Law2 name, e.g. "Law2_ScGeom_FrictPhys_CundallStrack".
  [[nodiscard]] virtual std::string typeName() const = 0;
  /// Yade's Ip2 name that creates this law's physics, e.g. "Ip2_FrictMat_FrictMat_FrictPhys".
  [[nodiscard]] virtual std::string physicsName() const = 0;
  /// 0 if the law cannot handle this material pair; otherwise a specificity (higher wins).
  /// @param m1, m2 the two bodies' materials, either order
  /// @return 0, or the specificity (a law for these material types exactly beats a general one)
  [[nodiscard]] virtual int handles(const Material& m1, const Material& m2) const = 0;
  /// Whether the law's model applies to contacts of this geometry (in an InteractionLoop with
  /// several laws, a contact goes to the most specific law among those that do): by default
  /// the spheres' contacts (with spheres, walls, facets, boxes); the Potential Blocks' and
  /// Particles' laws take their own.
  /// @param kind the contact's geometry kind
  /// @return whether this law computes such contacts
  [[nodiscard]] virtual bool handlesGeometry(ContactGeometryKind kind) const
  {
    return kind == ContactGeometryKind::SphereSphere || kind == ContactGeometryKind::WallSphere
           || kind == ContactGeometryKind::FacetSphere || kind == ContactGeometryKind::BoxSphere;
  }
  /// The law keeps state in Contacts::extra (which is then allocated and kept aligned).
  [[nodiscard]] virtual bool needsExtra() const = 0;
  /// The law may leave moments (ContactExtra's momentBending, momentTwist) on its contacts, which
  /// the gather of forces per body adds to the bodies' torques; a law that never does spares the
  /// gather a read of each contact's state.
  [[nodiscard]] virtual bool keepsMoments() const = 0;
  /// Set the physics (stiffness, damping, friction) of a contact that just became real; `x` is
  /// its ContactExtra (null unless needsExtra()).
  /// @param c the new contact (geometry set, ids and law index assigned)
  /// @param x its ContactExtra, or null
  virtual void initialize(Contact& c, ContactExtra* x, const Scene& scene) const = 0;
  /// Set c.force of every real contact whose c.law == lawIndex (geometry already updated).
  /// @param lawIndex this law's index in its InteractionLoop's `laws`
  virtual void computeForces(Scene& scene, std::uint8_t lawIndex) = 0;
  /// The law is the only one of its InteractionLoop: update the geometry of every candidate
  /// pair, initialise new contacts and compute forces, in one pass over the contacts.
  /// @return the index of the first contact overlapping more than scene.maxOverlapRatio of its
  /// smaller radius, or -1
  virtual std::int64_t computeAll(Scene& scene) = 0;
  /// computeAll's work on the contacts [first, last) only, for a caller that runs the loop in its
  /// own parallel region (the step scheduler) and calls stepDone() after the last range;
  /// Contacts::extra must already be aligned when needsExtra().
  /// @param energyBlocks null: no energy tracking; else `first` is a multiple of energyBlock
  /// and what contact k dissipates is added to energyBlocks[k / energyBlock] (the blocks of
  /// computeAll, so the sums do not depend on how the contacts are split)
  /// @param first, last the contacts [first, last) of the list
  /// @return the index of the first contact of the range overlapping too much, or the number
  /// of contacts
  virtual std::int64_t computeAllIn(Scene& scene, std::int64_t first, std::int64_t last,
                                    ContactEnergy* energyBlocks) = 0;
  /// Called once per step before any contact is processed (the law may look at the scene's
  /// materials and align Contacts::extra).
  virtual void prepare(Scene& /*scene*/) {}
  /// Called once per step after the law's contacts were processed (one-shot settings reset).
  virtual void stepDone() {}
  /// Elastic energy stored in the real contacts whose c.law == lawIndex.
  /// @param lawIndex this law's index in its InteractionLoop's `laws`
  /// @return the energy (J)
  [[nodiscard]] virtual double elasticEnergy(const Scene& scene, std::uint8_t lawIndex) const = 0;
  /// Of the contacts of this law that became real this step, the part of their elastic energy
  /// that the growth of their bodies' radii (grownBy, per body id) put in: E(u) - E(max(u - g, 0)),
  /// u the penetration and g the growth of the pair (see addGrownContactsEnergy).
  /// @param lawIndex this law's index in its InteractionLoop's `laws`
  /// @param grownBy the radius growth (m) per body id since the last contacts pass
  /// @return the energy (J)
  [[nodiscard]] virtual double grownElasticEnergy(const Scene& scene, std::uint8_t lawIndex,
                                                  const std::vector<double>& grownBy) const = 0;

  /// Parameters of the law and of its physics functor (Yade's Ip2/Law2 attributes), by name.
  /// @param name Yade's attribute name (one of parameterNames())
  /// @param value the new value
  /// @throws std::invalid_argument naming the law and the parameter if it has no such one or
  ///         the value is out of range
  virtual void setParameter(const std::string& name, double value);
  /// @param name Yade's attribute name (one of parameterNames())
  /// @return its current value
  /// @throws std::invalid_argument naming the law and the parameter if it has no such one
  [[nodiscard]] virtual double parameter(const std::string& name) const;
  /// A parameter of the physics functor given per pair of materials (Yade's MatchMaker).
  /// @param name Yade's attribute name
  /// @param value the values per material pair and the fallback
  /// @throws std::invalid_argument naming the law and the parameter if it takes none such
  virtual void setPairParameter(const std::string& name, const PairParameter& value);
  /// Names accepted by setParameter.
  [[nodiscard]] virtual std::vector<std::string> parameterNames() const { return {}; }

protected:
  [[noreturn]] void unknownParameter(const std::string& name) const;
};

/// What a law's per-contact force function may read besides the contact.
struct StepContext
{
  const Bodies& bodies;
  const std::deque<Material>& materials;
  const Cell* cell; ///< the periodic cell, null if space is not periodic
  double dt;
  ContactExtra* extra; ///< Contacts::extra (index = contact index), null unless the law needs it
  double maxOverlapRatio = 0; ///< Scene::maxOverlapRatio (<= 0: no check; overlapsTooMuch)
  /// The cell's near images, made once for the laws' AVX2 lanes (none without a cell).
  CellImages images = CellImages(cell);
};

/// 1/2 kn u^2 + 1/2 Fs^2/ks: the energy of a contact's linear springs, the normal one compressed
/// by u. Taken from the compression rather than from the last normal force (the same after a force
/// pass) so that it follows radii changed at fixed positions (growParticles) at once.
/// @param compression the normal spring's compression u (m)
/// @return the energy (J)
inline double springEnergy(const Contact& c, double compression)
{
  return 0.5 * c.kn * compression * compression + (c.ks > 0 ? 0.5 * c.shearForce.squaredNorm() / c.ks : 0.0);
}

/// True if a real contact overlaps more than `ratio` (> 0) of its smaller reference radius.
/// A contact without force at that overlap (no stiffness: a material of young 0, which Yade's
/// scripts give to bodies that only show something) cannot blow up and is let through, as is one
/// between two bodies that forces do not move (a fixed floor box in fixed bed spheres).
/// @param ratio scene.maxOverlapRatio (<= 0: no check)
/// @return whether the contact must be reported
inline bool overlapsTooMuch(const Contact& c, double ratio, const Bodies& b)
{
  return ratio > 0 && c.penetration > ratio * std::min(c.refR1, c.refR2) && c.force != Vec3::Zero()
         && (b.dynamic[static_cast<std::size_t>(c.id1)] || b.dynamic[static_cast<std::size_t>(c.id2)]);
}

/// Follows whether a contact list's records are so mixed between real contacts and candidates
/// that the contact loop's branch on `real` would often be mispredicted: then the loop queues
/// sphere pairs without that branch (ContactLawKernel::firstBadIn's RealMixed), a few stores a
/// record more. Where the branch is predictable (a dense bed's records are nearly all real)
/// those stores are the dearer: docs/dem.md, "Speed", the drum and the silo.
class RealMix
{
public:
  /// Measure the list's share of real records again if the list changed since (a re-detection,
  /// a removal) or every stepsBetween steps (contacts begin and end between re-detections: a
  /// periodic cell compacted may keep its list for thousands of steps). Called before a step's
  /// contacts: the flags are then those the last pass left, not those of a list just detected
  /// (all candidates).
  void follow(const Contacts& contacts)
  {
    if (contacts.version == version_ && ++steps_ < stepsBetween)
      return;
    version_ = contacts.version;
    steps_ = 0;
    const double real = contacts.list.empty() ? 0.0
                                              : static_cast<double>(contacts.countReal())
                                                    / static_cast<double>(contacts.list.size());
    mixed_ = real >= fewestReal && real < mostReal;
  }
  [[nodiscard]] bool mixed() const { return mixed_; }

private:
  /// The shares of real records the queues without the branch take. Measured (one thread,
  /// alternating with the branch): the drum (0.21-0.46 real) and the silo (0.50-0.56) gain, the
  /// dense bed (0.97-1) and the periodic RVE (0.58-0.83) lose, the RVE's candidates on a
  /// jittered lattice in a pattern the predictor learns. Below a tenth real, the branch is
  /// seldom missed again.
  static constexpr double fewestReal = 0.1, mostReal = 0.6;
  /// A pass over the records' first lines, a small share of so many steps' work.
  static constexpr int stepsBetween = 100;
  std::uint64_t version_ = 0; ///< the Contacts::version measured
  int steps_ = 0;             ///< steps since the measure
  bool mixed_ = false;
};

/// Base of the concrete laws: the loops over contacts, calling the law's inline
/// `template <bool Track> void force(Contact&, std::size_t k, const StepContext&, ContactEnergy&) const`
/// (k: the contact's index; energies dissipated are added to the last argument when Track) and
/// `double elastic(const Contact&, const ContactExtra*) const` (no virtual call per contact).
/// A law that keeps state in Contacts::extra declares `static constexpr bool usesExtra = true`;
/// every law declares `geometryUsesExtra` (the contact geometry reads or turns that state: a
/// bond, moments, an overlap's area) and `keepsMomentState` (its contacts may carry moments).
template <class Law>
class ContactLawKernel : public ContactLaw
{
public:
  static constexpr bool usesExtra = false;
  [[nodiscard]] bool needsExtra() const override { return Law::usesExtra; }
  [[nodiscard]] bool keepsMoments() const override { return Law::keepsMomentState; }
  void prepare(Scene& scene) override;
  void computeForces(Scene& scene, std::uint8_t lawIndex) override;
  std::int64_t computeAll(Scene& scene) override;
  std::int64_t computeAllIn(Scene& scene, std::int64_t first, std::int64_t last, ContactEnergy* energyBlocks) override;
  [[nodiscard]] double elasticEnergy(const Scene& scene, std::uint8_t lawIndex) const override;
  [[nodiscard]] double grownElasticEnergy(const Scene& scene, std::uint8_t lawIndex,
                                          const std::vector<double>& grownBy) const override;

private:
  template <bool Track>
  std::int64_t loopAll(Scene& scene);
  template <bool Track, bool RealMixed = false>
  std::int64_t firstBadIn(Scene& scene, const StepContext& step, std::int64_t first, std::int64_t last,
                          ContactEnergy& energy) const;
  template <bool Track>
  void loopForces(Scene& scene, std::uint8_t lawIndex);
  BalancedRanges ranges_; ///< computeAll's contacts per thread
  RealMix realMix_;       ///< how computeAll's and computeAllIn's loops queue sphere pairs
};

/// Make Contacts::extra as long as the contact list (allocating it on first use).
/// @throws std::logic_error if it exists with another length
void alignContactExtra(Contacts& contacts);

/// Register a contact law factory under its Law2 name (and optional aliases).
/// @param names the names it is made by (a name registered again takes the new factory)
/// @param factory makes a new law with its default parameters
/// @return true (so that the registration can initialise a constant: TALUS_REGISTER_CONTACT_LAW)
bool registerContactLaw(const std::vector<std::string>& names, std::function<std::unique_ptr<ContactLaw>()> factory);
/// Create a registered contact law.
/// @param name a registered name
/// @return a new law, owned by the caller
/// @throws std::invalid_argument listing the known names
std::unique_ptr<ContactLaw> makeContactLaw(const std::string& name);
/// Names of every registered contact law.
/// @return the names, sorted
std::vector<std::string> contactLawNames();
} // namespace talus::dem

/// Register contact law class TYPE under the given names (first: Yade's Law2 name).
#define TALUS_REGISTER_CONTACT_LAW(TYPE, ...)                                                                    \
  namespace                                                                                                      \
  {                                                                                                              \
  const bool registered_##TYPE                                                                                   \
      = ::talus::dem::registerContactLaw({__VA_ARGS__}, [] { return std::make_unique<TYPE>(); });                \
  }
