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
  const double re2 = re * re;
  double previous = 1.0 / (0.32 * 0.32);  // Yade's initial guess, 0.32^-2
  double f = previous;
  for (int iteration = 1; iteration <= maxIterations; ++iteration)
  {
    // 2 ln(Re sqrt(f)) = ln(Re^2 f), and y^-2 = 1/(y y): one logarithm per iteration instead of
    // a logarithm, a square root and two powers. This runs for every cell at every fluid step
    // (a few iterations each), where it was most of a wall-friction run's fluid resolution;
    // the values differ from Yade's form by rounding only (parity case vans_vs_yade).
    const double y = std::log(re2 * previous) + 0.32;
    f = 1.0 / (y * y);
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
