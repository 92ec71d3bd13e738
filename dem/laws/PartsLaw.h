#pragma once

// A contact law composed at compile time from parts (dem/laws/parts/): the physics set when a
// contact is made (Yade's Ip2), the relative motion its parts read, a normal spring, a damping,
// a tangential and a moments part, each a struct of inline functions, so that one law's loop
// over its contacts makes no virtual call. The parts that keep per-contact state declare it
// once in core/ContactExtra.h; the parts and the physics that take parameters declare them once
// (parts/Parameters.h).
#include "dem/laws/ContactLawKernel.h"
#include "dem/laws/parts/Damping.h"
#include "dem/laws/parts/Moments.h"
#include "dem/laws/parts/Motion.h"
#include "dem/laws/parts/Normal.h"
#include "dem/laws/parts/Parameters.h"
#include "dem/laws/parts/Tangential.h"

#include <cmath>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <vector>

namespace talus::dem
{
namespace detail
{
/// Whether the contact geometry needs a part's state (PartsLaw::geometryUsesExtra).
template <class Part>
constexpr bool geometryReads()
{
  if constexpr (requires { Part::stateForForcesOnly; })
    return Part::usesExtra && !Part::stateForForcesOnly;
  else
    return Part::usesExtra;
}
} // namespace detail

/// The law made of Physics, Normal, Damping, Tangential, Moments and Motion; Names gives Yade's
/// Law2 name (`static constexpr const char* law`).
///
/// Physics (the Ip2 part) has `static constexpr const char* ip2` (its Yade name) and `usesExtra`,
/// `int handles(const Material&, const Material&) const` and
/// `void initialize(Contact&, ContactExtra*, const Scene&) const` (stiffnesses, friction and
/// its part state of a new contact); optionally `bool handlesGeometry(ContactGeometryKind)
/// const` (the contacts of other shapes than spheres'), declared parameters (parts/Parameters.h)
/// and parameters of its own, by name (each taking `unknown`, a function that throws naming the
/// law and the parameter): `std::vector<std::string> parameterNames() const`,
/// `void setParameter(name, double, unknown)`, `double parameter(name, unknown) const`,
/// `void setPairParameter(name, const PairParameter&, unknown)`, `void stepDone()` (one-shot
/// settings, report what failed while contacts were made) and
/// `void beforeForce(Contact&, ContactExtra&, const StepContext&) const` (what the physics sets
/// again at every step: a bond on an existing contact, stiffnesses that follow the contact's
/// area). A part may have `void initialize(Contact&, ContactExtra*, const Scene&)
/// const` too (its state of a new contact, after the physics'); the parts' declared parameters
/// are the law's.
/// For a contact: the Motion of the bodies at the contact, the normal part's elastic force (the
/// contact may end there), the damping part's normal force (it sets c.normalForce and returns
/// the signed force the shear strength is taken from), then the tangential part's shear force
/// and the moments; the elastic energy is the normal, tangential and moments parts'.
template <class Names, class Physics, class Normal, class Damping, class Tangential, class Moments = parts::NoMoments,
          class Motion = parts::NoMotion>
class PartsLaw final
    : public ContactLawKernel<PartsLaw<Names, Physics, Normal, Damping, Tangential, Moments, Motion>>
{
public:
  static constexpr bool usesExtra = Physics::usesExtra || Normal::usesExtra || Damping::usesExtra
                                    || Tangential::usesExtra || Moments::usesExtra;
  /// Whether the contact geometry needs the state: a part's state counts unless the part
  /// declares `stateForForcesOnly` (stiffnesses or damping ratios its own force reads: no bond
  /// that keeps the contact, no moment that turns with it, no overlap's area). Hertz-Mindlin's
  /// contacts thus take the geometry of the stateless laws, spheres' fast path included.
  static constexpr bool geometryUsesExtra = detail::geometryReads<Physics>() || detail::geometryReads<Normal>()
                                            || detail::geometryReads<Damping>() || detail::geometryReads<Tangential>()
                                            || detail::geometryReads<Moments>();
  /// Only the moments part leaves moments on the contacts.
  static constexpr bool keepsMomentState = Moments::usesExtra;

  [[nodiscard]] std::string typeName() const override { return Names::law; }
  [[nodiscard]] std::string physicsName() const override { return Physics::ip2; }
  [[nodiscard]] int handles(const Material& m1, const Material& m2) const override
  {
    return physics_.handles(m1, m2);
  }
  [[nodiscard]] bool handlesGeometry(ContactGeometryKind kind) const override
  {
    if constexpr (requires { physics_.handlesGeometry(kind); })
      return physics_.handlesGeometry(kind);
    else
      return ContactLaw::handlesGeometry(kind);
  }
  void initialize(Contact& c, ContactExtra* x, const Scene& scene) const override
  {
    physics_.initialize(c, x, scene);
    forEachPart(*this, [&](const auto& part) {
      if constexpr (requires { part.initialize(c, x, scene); })
        part.initialize(c, x, scene);
    });
  }

  /// One contact's forces, part by part (ContactLawKernel's per-contact call; inline, no
  /// virtual call).
  /// @param c the contact, its geometry of this step
  /// @param k its index in the contact list (its ContactExtra's)
  /// @param step what the parts read besides the contact
  /// @param energy with Track, what the parts dissipate is added to it
  template <bool Track>
  void force(Contact& c, std::size_t k, const StepContext& step, ContactEnergy& energy) const
  {
    ContactExtra* x = nullptr;
    if constexpr (usesExtra)
      x = step.extra + k;
    if constexpr (requires { physics_.beforeForce(c, *x, step); })
      physics_.beforeForce(c, *x, step);
    const Motion motion(c, step);
    const double elastic = normal_.template force<Track>(c, x, energy);
    if constexpr (Normal::mayEnd)
      if (!c.real)
        return;
    const double fn = damping_.template normal<Track>(c, x, step, motion, elastic, energy);
    tangential_.template force<Track>(c, x, fn, step, motion, energy);
    moments_.template force<Track>(c, x, fn, step, motion, energy);
  }
  /// @return whether the contacts' moments carry over from step to step, so that the geometry
  /// turns them with the contact frame (the moments part's say)
  [[nodiscard]] bool carriesMoments() const { return moments_.carriesMoments(); }
  /// Four sphere contacts' geometry and forces at once, where Names gives them (its
  /// `sphereLanes`, AVX2 lanes that do force()'s operations in the same order, without energy)
  /// and the law keeps no moments (ContactLawKernel's batches).
  /// @param c the four contacts, real at the last step, between spheres, not across a periodic
  ///        boundary
  /// @param k their indices in the contact list (their states')
  /// @return the lanes whose geometry, and whose forces, were made
  template <class N = Names>
    requires requires(Contact* const* c, const std::int64_t* k, const StepContext& s) { N::sphereLanes(c, k, s); }
             && std::is_same_v<Moments, parts::NoMoments>
  SphereLanes sphereLanes(Contact* const* c, const std::int64_t* k, const StepContext& step) const
  {
    return N::sphereLanes(c, k, step);
  }
  /// @param x the contact's state (null when the law keeps none)
  /// @return the elastic energy (J) of the normal, tangential and moments parts
  double elastic(const Contact& c, const ContactExtra* x) const
  {
    return moments_.addElastic(normal_.elastic(c, x) + tangential_.elastic(c), x);
  }

  [[nodiscard]] std::vector<std::string> parameterNames() const override
  {
    std::vector<std::string> names;
    if constexpr (requires { physics_.parameterNames(); })
      names = physics_.parameterNames();
    forEachDeclared(*this, [&](const char* name, const auto& /*value*/) { names.emplace_back(name); });
    return names;
  }
  /// A declared yes/no is set by value != 0, a declared number checked.
  /// @throws std::invalid_argument naming the parameter if a declared number is not finite and
  ///         >= 0, or naming the law if it has no such parameter
  void setParameter(const std::string& name, double value) override
  {
    bool found = false;
    forEachDeclared(*this, [&](const char* declared, auto& slot) {
      if (found || name != declared)
        return;
      found = true;
      if constexpr (std::is_same_v<std::remove_cvref_t<decltype(slot)>, bool>)
        slot = value != 0;
      else if (!std::isfinite(value) || value < 0)
        throw std::invalid_argument(physicsName() + "." + name + " must be finite and >= 0, got "
                                    + std::to_string(value));
      else
        slot = value;
    });
    if (found)
      return;
    if constexpr (requires { physics_.setParameter(name, value, unknown()); })
      physics_.setParameter(name, value, unknown());
    else
      this->unknownParameter(name);
  }
  [[nodiscard]] double parameter(const std::string& name) const override
  {
    bool found = false;
    double value = 0;
    forEachDeclared(*this, [&](const char* declared, const auto& slot) {
      if (!found && name == declared)
      {
        found = true;
        value = static_cast<double>(slot);
      }
    });
    if (found)
      return value;
    if constexpr (requires { physics_.parameter(name, unknown()); })
      return physics_.parameter(name, unknown());
    else
      this->unknownParameter(name);
  }
  void setPairParameter(const std::string& name, const PairParameter& value) override
  {
    if constexpr (requires { physics_.setPairParameter(name, value, unknown()); })
      physics_.setPairParameter(name, value, unknown());
    else
      this->unknownParameter(name);
  }
  void stepDone() override
  {
    if constexpr (requires { physics_.stepDone(); })
      physics_.stepDone();
  }

private:
  /// Throws std::invalid_argument naming the law and the parameter (the parameter functions'
  /// `unknown`).
  struct Unknown
  {
    const PartsLaw* law;
    [[noreturn]] void operator()(const std::string& name) const { law->unknownParameter(name); }
  };
  [[nodiscard]] Unknown unknown() const { return {this}; }

  /// Call `f(part)` for each part after the physics, in the law's order.
  template <class Self, class F> // PartsLaw or const PartsLaw
  static void forEachPart(Self& self, F&& f)
  {
    f(self.normal_);
    f(self.damping_);
    f(self.tangential_);
    f(self.moments_);
  }
  /// Call `f(name, member)` for each parameter the physics and the parts declare.
  template <class Self, class F>
  static void forEachDeclared(Self& self, F&& f)
  {
    auto declaredBy = [&](auto& part) {
      parts::forEachParameter<std::remove_cvref_t<decltype(part)>>(
          [&](const auto& declared) { f(declared.name, part.*declared.member); });
    };
    declaredBy(self.physics_);
    forEachPart(self, declaredBy);
  }

  Physics physics_;
  Normal normal_;
  Damping damping_;
  Tangential tangential_;
  Moments moments_;
};
} // namespace talus::dem

/// Register the law composed of these parts under Yade's Law2 name and the given aliases.
#define TALUS_REGISTER_PARTS_LAW(TYPE, ...)                                                                      \
  TALUS_REGISTER_CONTACT_LAW(TYPE, TYPE##Names::law, __VA_ARGS__)
