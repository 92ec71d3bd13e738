#include "dem/GlobalStiffnessTimeStepper.h"

#include "dem/Scene.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

namespace talus::dem
{
double GlobalStiffnessTimeStepper::stiffnessTimeStep(const Scene& scene) const
{
  const Bodies& b = scene.bodies;
  std::vector<Vec3> translational(b.size(), Vec3::Zero()), rotational(b.size(), Vec3::Zero());
  for (const Contact& c : scene.contacts.list)
  {
    if (!c.real || c.normalForce.squaredNorm() == 0)
      continue;
    const Vec3 nn = c.normal.cwiseProduct(c.normal);
    const Vec3 k = nn * (c.kn - c.ks) + Vec3::Constant(c.ks);
    const Vec3 kr = Vec3(nn[1] + nn[2], nn[0] + nn[2], nn[0] + nn[1]) * c.ks;
    translational[static_cast<std::size_t>(c.id1)] += k;
    translational[static_cast<std::size_t>(c.id2)] += k;
    rotational[static_cast<std::size_t>(c.id1)] += kr * (c.refR1 * c.refR1);
    rotational[static_cast<std::size_t>(c.id2)] += kr * (c.refR2 * c.refR2);
  }
  const double huge = std::numeric_limits<double>::max();
  double best = huge;
  for (std::size_t i = 0; i < b.size(); ++i)
  {
    if (!b.alive[i] || !b.dynamic[i] || translational[i].isZero(0))
      continue;
    const double kmax = translational[i].maxCoeff();
    double period2 = kmax != 0 ? b.mass[i] / kmax : huge; // squared eigen-period, translation
    for (int d = 0; d < 3; ++d)
      if (rotational[i][d] != 0)
        period2 = std::min(period2, b.inertia[i][d] / rotational[i][d]);
    best = std::min(best, 1.41044 * timestepSafetyCoefficient * std::sqrt(period2));
  }
  return best == huge ? std::numeric_limits<double>::infinity() : best;
}

void GlobalStiffnessTimeStepper::run(Scene& scene)
{
  if (!active || !(!computedOnce || scene.iter % std::max<std::int64_t>(timeStepUpdateInterval, 1) == 0 || scene.iter < 2))
    return;
  if (defaultDt < 0)
    defaultDt = timestepSafetyCoefficient * scene.pWaveTimeStep();
  const double dt = stiffnessTimeStep(scene);
  if (std::isfinite(dt))
  {
    // At most 5 % growth per update: no jump from a loose to a much stiffer state.
    previousDt = std::min({dt, maxDt, 1.05 * previousDt});
    scene.dt = previousDt;
    computedOnce = true;
  }
  else if (!computedOnce && std::isfinite(defaultDt) && defaultDt > 0)
    scene.dt = defaultDt;
}

double rayleighWaveTimeStep(const Scene& scene)
{
  const Bodies& b = scene.bodies;
  double best = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < b.size(); ++i)
  {
    if (!b.alive[i] || b.shape[i] != ShapeKind::Sphere)
      continue;
    const Material& m = scene.materials[static_cast<std::size_t>(b.material[i])];
    const double r = b.radius[i];
    const double density = b.mass[i] / ((4. / 3.) * M_PI * r * r * r);
    const double shear = m.young / (2. * (1 + m.poisson));
    const double lambda = 0.1631 * m.poisson + 0.876605;
    best = std::min(best, M_PI * r / lambda * std::sqrt(density / shear));
  }
  return best;
}
} // namespace talus::dem
