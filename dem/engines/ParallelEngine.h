#pragma once

#include "dem/core/Engine.h"

#include <memory>
#include <vector>

namespace talus::dem
{
/// Groups of engines Yade runs side by side (Yade's ParallelEngine: `slaves`, each an engine or
/// a list of engines run in order). Talus runs the groups one after the other, in the order
/// given: Yade's groups must not touch the same data, so the order cannot change the result,
/// and the engines inside parallelise their own loops.
class ParallelEngine : public Engine
{
public:
  void run(Scene& scene) override;
  [[nodiscard]] std::string typeName() const override { return "ParallelEngine"; }

  std::vector<std::vector<std::shared_ptr<Engine>>> slaves;
};
} // namespace talus::dem
