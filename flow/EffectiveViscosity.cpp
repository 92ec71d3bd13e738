#include "flow/EffectiveViscosity.h"

#include <cassert>
#include <cmath>
#include <cstddef>

namespace talus::flow
{
void effectiveViscosity(EffectiveViscosityModel model, double nu, std::span<const double> phiPart,
                        std::span<double> nuEff)
{
  const std::size_t n = nuEff.size();
  assert(n >= 2 && phiPart.size() == n);
  if (model == EffectiveViscosityModel::Fluid)
  {
    for (std::size_t j = 0; j < n; ++j)
      nuEff[j] = nu;
    return;
  }
  nuEff[0] = nu * (1.0 + 2.5 * phiPart[0]);
  for (std::size_t j = 1; j < n; ++j)
  {
    const double phiNode = 0.5 * (phiPart[j - 1] + phiPart[j]);  // the node lies between two cells
    nuEff[j] = model == EffectiveViscosityModel::Einstein ? nu * (1.0 + 2.5 * phiNode)
                                                          : nu * std::pow(1.0 - phiNode, -2.8);
  }
}
} // namespace talus::flow
