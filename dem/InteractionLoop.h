#pragma once

#include "dem/ContactLaw.h"
#include "dem/Engine.h"

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

  std::vector<std::shared_ptr<ContactLaw>> laws;

private:
  void assignLaw(Contact& c, const Scene& scene) const;
};
} // namespace talus::dem
