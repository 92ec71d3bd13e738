#pragma once

#include "dem/core/ContactExtra.h"
#include "dem/base/HugePageAllocator.h"
#include "dem/base/types.h"

#include <cstdint>
#include <functional>
#include <vector>

namespace talus::dem
{
/// Which geometry routine a contact uses (decided once, when the pair is first detected).
enum class ContactGeometryKind : std::uint8_t
{
  SphereSphere,
  WallSphere,  ///< id1 is the wall, as in Yade
  FacetSphere, ///< id1 is the facet, as in Yade
  BoxSphere,   ///< id1 is the box, as in Yade
  BlockBlock,  ///< two Potential Blocks (Yade's Ig2_PB_PB_ScGeom)
  WallBlock,   ///< id1 is the wall, id2 a Potential Block
  ParticleParticle, ///< two Potential Particles (Yade's Ig2_PP_PP_ScGeom)
  WallParticle,     ///< id1 is the wall, id2 a Potential Particle
};

/// One candidate pair within the collider's skin, with its persistent contact state.
///
/// A pair is "real" (Yade's isReal) while the shapes overlap; a real contact keeps its shear
/// force from step to step, rotated with the contact frame (Yade's ScGeom). Plain data: the
/// contact array is flat and copied, sorted and merged by value.
///
/// Layout: one record is four cache lines, aligned on a line. The first line holds everything
/// the per-body force gather reads (the flags, the force and the contact point), and what the
/// collider's candidate test of a separated pair reads (ids, kind, real), so those two passes,
/// which visit the records out of order or mostly skip them, touch one line per record. Large
/// packings are limited by memory traffic, not arithmetic: the lines a pass reads set the cost
/// per particle-step of a large bed (docs/dem.md, "Measurements behind the code").
struct alignas(64) Contact
{
  BodyId id1 = -1, id2 = -1;
  ContactGeometryKind kind = ContactGeometryKind::SphereSphere;
  bool real = false;   ///< the shapes overlap (Yade's isReal)
  bool fresh = false;  ///< became real this step: the contact law sets its physics
  std::uint8_t law = 0; ///< index of the contact law (in the InteractionLoop) that handles it
  // Result of the step: force on body 2, applied at the contact point (body 1 gets the
  // opposite); torques follow from the lever arms when forces are summed per body.
  Vec3 force = Vec3::Zero();
  Vec3 contactPoint = Vec3::Zero();

  // Geometry (ScGeom): normal points from body 1 to body 2.
  Vec3 normal = Vec3::Zero();
  double penetration = 0;
  double refR1 = 0, refR2 = 0; ///< reference radii for stiffness and incident velocity
  Vec3 shearIncrement = Vec3::Zero();

  // Physics (FrictPhys / ViscElPhys), set when the contact becomes real.
  double kn = 0, ks = 0, cn = 0, cs = 0, tanPhi = 0;
  Vec3 normalForce = Vec3::Zero(); ///< force on body 2, normal part (elastic + viscous)
  Vec3 shearForce = Vec3::Zero();  ///< force on body 2, tangential elastic part (history)

  /// Periodic scenes: body 2 interacts through its image shifted by hSize * cellDist
  /// (Cell::shift; zero without periodicity).
  Eigen::Vector3i cellDist = Eigen::Vector3i::Zero();

  /// Forget all history (the shapes separated).
  void reset()
  {
    real = false;
    fresh = false;
    normalForce.setZero();
    shearForce.setZero();
    force.setZero();
  }
};
static_assert(sizeof(Contact) == 256, "a contact record is four cache lines (see the layout note)");

/// Storage of the contact records and of their richer state: rebuilt at re-detections, so
/// backed by huge pages where the kernel allows (HugePageAllocator).
using ContactList = std::vector<Contact, HugePageAllocator<Contact>>;
using ContactExtraList = std::vector<ContactExtra, HugePageAllocator<ContactExtra>>;

/// The contact list, kept sorted by (id1, id2), plus a per-body index to gather forces.
///
/// Forces are summed per body in a fixed order (body by body, over its contacts in list order),
/// never with atomics, so results do not depend on the number of threads.
struct Contacts
{
  ContactList list;
  /// CSR: contacts of body b are entries [start[b], start[b+1]) of `entries`; an entry is
  /// (contact index << 1) | side, side 0 for id1 and 1 for id2.
  std::vector<std::int64_t> start;
  std::vector<std::int64_t> entries;
  /// State of the richer contact models (ContactExtra), entry k for contact k: empty unless a
  /// law that needs it runs (it sizes it on first use, the collider then keeps it aligned).
  /// Code that removes contacts goes through removeIf, which compacts both.
  ContactExtraList extra;

  /// Remove the contacts `doomed` selects, with their entries of `extra` (compacting the list
  /// alone would hand each later contact the state of another pair), then rebuild the index.
  /// @param doomed true for a contact to remove
  /// @param bodyCount the scene's body count, for the index
  void removeIf(const std::function<bool(const Contact&)>& doomed, std::size_t bodyCount);
  /// The records of `extra` (entry k for contact k).
  /// @return the first record, or null when no law keeps any
  /// @throws std::logic_error if `extra` is not aligned with the list (a contact would read
  ///         another pair's state)
  [[nodiscard]] ContactExtra* extraState();
  [[nodiscard]] const ContactExtra* extraState() const;

  /// Rebuild the per-body index after the list changed, and give the list a new `version`.
  /// @param bodyCount the scene's body count (slots, erased bodies included)
  void index(std::size_t bodyCount);
  /// A number no other list state has had, in any Contacts (a copy keeps it with the list it
  /// copies): what is derived from the list stays valid while it is unchanged. 0 before the
  /// first index().
  std::uint64_t version = 0;
  /// Number of real contacts.
  [[nodiscard]] std::size_t countReal() const;
  /// Number of bodies the per-body index covers (those present at the last index()).
  [[nodiscard]] std::int64_t indexedBodies() const
  {
    return start.empty() ? 0 : static_cast<std::int64_t>(start.size()) - 1;
  }
};
} // namespace talus::dem
