#pragma once

#include "dem/ContactGeometry.h"
#include "dem/Contacts.h"
#include "dem/Material.h"

#include <algorithm>
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
  [[nodiscard]] virtual int handles(const Material& m1, const Material& m2) const = 0;
  /// Set the physics (stiffness, damping, friction) of a contact that just became real.
  virtual void initialize(Contact& c, const Scene& scene) const = 0;
  /// Set c.force of every real contact whose c.law == lawIndex (geometry already updated).
  virtual void computeForces(Scene& scene, std::uint8_t lawIndex) = 0;
  /// The law is the only one of its InteractionLoop: update the geometry of every candidate
  /// pair, initialise new contacts and compute forces, in one pass over the contacts.
  /// @return the index of the first contact overlapping more than scene.maxOverlapRatio of its
  /// smaller radius, or -1
  virtual std::int64_t computeAll(Scene& scene) = 0;
};

/// What a law's per-contact force function may read besides the contact.
struct StepContext
{
  const Bodies& bodies;
  const Cell* cell; ///< the periodic cell, null if space is not periodic
  double dt;
};

/// True if a real contact overlaps more than `ratio` (> 0) of its smaller reference radius.
inline bool overlapsTooMuch(const Contact& c, double ratio)
{
  return ratio > 0 && c.penetration > ratio * std::min(c.refR1, c.refR2);
}

/// Base of the concrete laws: the loops over contacts, calling the law's inline
/// `void force(Contact&, const StepContext&) const` (no virtual call per contact).
template <class Law>
class ContactLawKernel : public ContactLaw
{
public:
  void computeForces(Scene& scene, std::uint8_t lawIndex) override;
  std::int64_t computeAll(Scene& scene) override;
};

/// Register a contact law factory under its Law2 name (and optional aliases).
bool registerContactLaw(const std::vector<std::string>& names, std::function<std::unique_ptr<ContactLaw>()> factory);
/// Create a registered contact law. @throws std::invalid_argument listing the known names
std::unique_ptr<ContactLaw> makeContactLaw(const std::string& name);
/// Names of every registered contact law.
std::vector<std::string> contactLawNames();
} // namespace talus::dem

/// Register contact law class TYPE under the given names (first: Yade's Law2 name).
#define TALUS_REGISTER_CONTACT_LAW(TYPE, ...)                                                                    \
  namespace                                                                                                      \
  {                                                                                                              \
  const bool registered_##TYPE                                                                                   \
      = ::talus::dem::registerContactLaw({__VA_ARGS__}, [] { return std::make_unique<TYPE>(); });                \
  }
