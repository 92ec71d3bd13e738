#include "flow/WallFriction.h"

#include <algorithm>
#include <cmath>

namespace talus::flow
{
double wallFrictionFactor(double reynolds)
{
  constexpr int maxIterations = 100;
  constexpr double tolerance = 1e-2;
  const double re = std::max(1e-10, reynolds);
  double previous = std::pow(0.32, -2);  // Yade's initial guess
  double f = previous;
  for (int iteration = 1; iteration <= maxIterations; ++iteration)
  {
    f = std::pow(2.0 * std::log(re * std::sqrt(previous)) + 0.32, -2);
    const double change = std::fabs(f - previous) / previous;
    previous = f;
    if (change < tolerance)
      // Yade flags non-convergence by the iteration count only; converging on the very last
      // allowed iteration therefore also counts as a failure there.
      return iteration == maxIterations ? 0.0 : f;
  }
  return 0.0;  // no fixed point within the budget: no wall friction, as in Yade
}
} // namespace talus::flow
