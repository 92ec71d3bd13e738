#pragma once

// A contact law composed at compile time from parts (dem/laws/parts/): the physics set when a
// contact is made (Yade's Ip2), a normal spring, a damping, a tangential and a moments part,
// each a struct of inline functions, so that one law's loop over its contacts makes no virtual
// call. The parts that keep per-contact state declare it once in core/ContactExtra.h.
#include "dem/laws/ContactLawKernel.h"
#include "dem/laws/parts/Damping.h"
#include "dem/laws/parts/Moments.h"
#include "dem/laws/parts/Normal.h"
#include "dem/laws/parts/Tangential.h"

#include <string>
#include <vector>

namespace talus::dem
{
/// The law made of Physics, Normal, Damping, Tangential and Moments; Names gives Yade's Law2
/// name (`static constexpr const char* law`).
///
/// Physics (the Ip2 part) has `static constexpr const char* ip2` (its Yade name) and `usesExtra`,
/// `int handles(const Material&, const Material&) const` and
/// `void initialize(Contact&, ContactExtra*, const Scene&) const` (stiffnesses, friction and
/// its part state of a new contact); optionally parameters, by name (each taking `unknown`, a
/// function that throws naming the law and the parameter):
/// `std::vector<std::string> parameterNames() const`, `void setParameter(name, double, unknown)`,
/// `double parameter(name, unknown) const`, `void setPairParameter(name, const PairParameter&,
/// unknown)`, `void stepDone()` (one-shot settings, report what failed while contacts were
/// made) and `void beforeForce(Contact&, ContactExtra&, const StepContext&) const` (a bond set
/// on an existing contact). The Moments part's parameters (its `flag`s) are the law's too.
/// For a contact: F_n = Damping::normal(Normal::force) along the normal (unless the normal part
/// ended the contact), then the tangential part's shear force and the moments; the elastic
/// energy is the normal, tangential and moments parts'.
template <class Names, class Physics, class Normal, class Damping, class Tangential, class Moments = parts::NoMoments>
class PartsLaw final : public ContactLawKernel<PartsLaw<Names, Physics, Normal, Damping, Tangential, Moments>>
{
public:
  static constexpr bool usesExtra = Physics::usesExtra || Normal::usesExtra || Damping::usesExtra
                                    || Tangential::usesExtra || Moments::usesExtra;

  [[nodiscard]] std::string typeName() const override { return Names::law; }
  [[nodiscard]] std::string physicsName() const override { return Physics::ip2; }
  [[nodiscard]] int handles(const Material& m1, const Material& m2) const override
  {
    return physics_.handles(m1, m2);
  }
  void initialize(Contact& c, ContactExtra* x, const Scene& scene) const override { physics_.initialize(c, x, scene); }

  template <bool Track>
  void force(Contact& c, std::size_t k, const StepContext& step, ContactEnergy& energy) const
  {
    ContactExtra* x = nullptr;
    if constexpr (usesExtra)
      x = step.extra + k;
    if constexpr (requires { physics_.beforeForce(c, *x, step); })
      physics_.beforeForce(c, *x, step);
    const double elastic = Normal::template force<Track>(c, x, energy);
    if constexpr (Normal::mayEnd)
      if (!c.real)
        return;
    const double fn = Damping::template normal<Track>(c, x, step, elastic, energy);
    c.normalForce = fn * c.normal;
    Tangential::template force<Track>(c, x, fn, step, energy);
    moments_.template force<Track>(c, x, step, energy);
  }
  double elastic(const Contact& c, const ContactExtra* x) const
  {
    return moments_.addElastic(Normal::elastic(c, x) + Tangential::elastic(c), x);
  }

  [[nodiscard]] std::vector<std::string> parameterNames() const override
  {
    std::vector<std::string> names;
    if constexpr (requires { physics_.parameterNames(); })
      names = physics_.parameterNames();
    for (const std::string& name : moments_.parameterNames())
      names.push_back(name);
    return names;
  }
  void setParameter(const std::string& name, double value) override
  {
    if (bool* f = Moments::flag(moments_, name))
      *f = value != 0;
    else if constexpr (requires { physics_.setParameter(name, value, unknown()); })
      physics_.setParameter(name, value, unknown());
    else
      this->unknownParameter(name);
  }
  [[nodiscard]] double parameter(const std::string& name) const override
  {
    if (const bool* f = Moments::flag(moments_, name))
      return *f ? 1.0 : 0.0;
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
  Physics physics_;
  Moments moments_;
};
} // namespace talus::dem

/// Register the law composed of these parts under Yade's Law2 name and the given aliases.
#define TALUS_REGISTER_PARTS_LAW(TYPE, ...)                                                                      \
  TALUS_REGISTER_CONTACT_LAW(TYPE, TYPE##Names::law, __VA_ARGS__)
