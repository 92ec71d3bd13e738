#pragma once

// A law whose richer form keeps per-contact state that most scenes never need: it runs the plain
// form, whose contacts keep the plain records of the spheres' fast path (no Contacts::extra),
// until the scene first asks for the part with state.
#include "dem/laws/ContactLaw.h"

#include <string>
#include <vector>

namespace talus::dem
{
/// One law in two forms composed of the same physics (same names and parameters; a parameter is
/// set on both): Plain until the first step `needed(scene)` is true, then Stateful for good
/// (contacts made before keep what Plain gave them).
template <class Plain, class Stateful, bool (*needed)(const Scene&)>
class StateOnDemand final : public ContactLaw
{
public:
  [[nodiscard]] std::string typeName() const override { return plain_.typeName(); }
  [[nodiscard]] std::string physicsName() const override { return plain_.physicsName(); }
  [[nodiscard]] int handles(const Material& m1, const Material& m2) const override { return plain_.handles(m1, m2); }
  [[nodiscard]] bool handlesGeometry(ContactGeometryKind kind) const override { return plain_.handlesGeometry(kind); }
  [[nodiscard]] bool needsExtra() const override { return withState_; }
  [[nodiscard]] bool keepsMoments() const override { return active().keepsMoments(); }
  void prepare(Scene& scene) override
  {
    withState_ = withState_ || needed(scene);
    if (withState_)
      alignContactExtra(scene.contacts);
    active().prepare(scene);
  }
  void initialize(Contact& c, ContactExtra* x, const Scene& scene) const override { active().initialize(c, x, scene); }
  void computeForces(Scene& scene, std::uint8_t lawIndex) override { active().computeForces(scene, lawIndex); }
  std::int64_t computeAll(Scene& scene) override { return active().computeAll(scene); }
  std::int64_t computeAllIn(Scene& scene, std::int64_t first, std::int64_t last, ContactEnergy* energyBlocks) override
  {
    return active().computeAllIn(scene, first, last, energyBlocks);
  }
  void stepDone() override { active().stepDone(); }
  [[nodiscard]] double elasticEnergy(const Scene& scene, std::uint8_t lawIndex) const override
  {
    return active().elasticEnergy(scene, lawIndex);
  }
  [[nodiscard]] double grownElasticEnergy(const Scene& scene, std::uint8_t lawIndex,
                                          const std::vector<double>& grownBy) const override
  {
    return active().grownElasticEnergy(scene, lawIndex, grownBy);
  }
  [[nodiscard]] std::vector<std::string> parameterNames() const override { return plain_.parameterNames(); }
  void setParameter(const std::string& name, double value) override
  {
    plain_.setParameter(name, value);
    stateful_.setParameter(name, value);
  }
  [[nodiscard]] double parameter(const std::string& name) const override { return active().parameter(name); }
  void setPairParameter(const std::string& name, const PairParameter& value) override
  {
    plain_.setPairParameter(name, value);
    stateful_.setPairParameter(name, value);
  }

private:
  [[nodiscard]] ContactLaw& active() { return withState_ ? static_cast<ContactLaw&>(stateful_) : plain_; }
  [[nodiscard]] const ContactLaw& active() const
  {
    return withState_ ? static_cast<const ContactLaw&>(stateful_) : plain_;
  }
  Plain plain_;
  Stateful stateful_;
  bool withState_ = false;
};
} // namespace talus::dem
