#include "flow/MixingLength.h"

#include <cassert>
#include <cmath>
#include <cstddef>

namespace talus::flow
{
void mixingLength(MixingLengthModel model, double kappa, double phiMax, std::span<const double> z,
                  double deltaZ, std::span<const double> phiPart, std::span<double> lm)
{
  const std::size_t n = lm.size();
  assert(n >= 2 && z.size() == n && phiPart.size() == n);
  lm[0] = 0.0;  // no turbulence at the no-slip bottom wall
  switch (model)
  {
  case MixingLengthModel::Prandtl:
    for (std::size_t j = 1; j < n; ++j)
      lm[j] = kappa * z[j];
    break;
  case MixingLengthModel::FreeSurface:
  {
    const double h = z[n - 1];
    for (std::size_t j = 1; j < n - 1; ++j)
      lm[j] = kappa * z[j] * std::sqrt(1.0 - z[j] / h);
    lm[n - 1] = 0.0;  // set exactly: sqrt of a rounded 1 - h/h could be a tiny non-zero
    break;
  }
  case MixingLengthModel::LiSawamoto:
  {
    // Highest cell that reaches phiMax: below it the bed is taken as fully packed, so that a
    // pocket of loose packing inside the bed does not switch turbulence back on.
    std::ptrdiff_t top = static_cast<std::ptrdiff_t>(n) - 1;
    while (top >= 0 && phiPart[static_cast<std::size_t>(top)] < phiMax)
      --top;
    // The mixing length integrates the "fluid-likeness" of the mixture from the bottom, in the
    // same order of summation as Yade, so both give bit-for-bit the same lengths. As in Yade,
    // the cell `top` itself enters with its own phi (>= phiMax, so it adds nothing or shortens
    // l_m slightly if phi > phiMax).
    double sum = 0.0;
    for (std::size_t j = 1; j < n; ++j)
    {
      const bool packed = static_cast<std::ptrdiff_t>(j) - 1 < top;
      const double phi = packed ? phiMax : phiPart[j - 1];
      sum += kappa * (phiMax - phi) / phiMax * deltaZ;
      lm[j] = sum;
    }
    break;
  }
  }
}
} // namespace talus::flow
