#include "dem/engines/GlobalStiffnessTimeStepper.h"

#include "dem/core/Scene.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

namespace talus::dem
{
namespace
{
/// Diagonal of a contact's translational and rotational (per unit lever arm squared) matrices
/// for a normal coefficient `normal` and a shear one `shear` (springs kn, ks or dashpots cn, cs).
struct ContactDiagonal
{
  Vec3 translational, rotational;
  ContactDiagonal(const Vec3& n, double normal, double shear)
  {
    const Vec3 nn = n.cwiseProduct(n);
    translational = nn * (normal - shear) + Vec3::Constant(shear);
    rotational = Vec3(nn[1] + nn[2], nn[0] + nn[2], nn[0] + nn[1]) * shear;
  }
};

/// Per body, the sums of its contacts' diagonals.
struct BodyDiagonals
{
  std::vector<Vec3> translational, rotational;
  explicit BodyDiagonals(std::size_t n) : translational(n, Vec3::Zero()), rotational(n, Vec3::Zero()) {}
  void add(const Contact& c, const ContactDiagonal& d)
  {
    const auto i1 = static_cast<std::size_t>(c.id1), i2 = static_cast<std::size_t>(c.id2);
    translational[i1] += d.translational;
    translational[i2] += d.translational;
    rotational[i1] += d.rotational * (c.refR1 * c.refR1);
    rotational[i2] += d.rotational * (c.refR2 * c.refR2);
  }
  /// min(m / max_i T_i, min_i I_i / R_i) over the non-zero sums; `huge` if all are zero.
  [[nodiscard]] double ratio(const Bodies& b, std::size_t i, double huge) const
  {
    const double tmax = translational[i].maxCoeff();
    double best = tmax != 0 ? b.mass[i] / tmax : huge;
    for (int d = 0; d < 3; ++d)
      if (rotational[i][d] != 0)
        best = std::min(best, b.inertia[i][d] / rotational[i][d]);
    return best;
  }
};
} // namespace

double GlobalStiffnessTimeStepper::stiffnessTimeStep(const Scene& scene) const
{
  const Bodies& b = scene.bodies;
  BodyDiagonals stiffness(b.size()), viscosity(viscEl ? b.size() : 0);
  for (const Contact& c : scene.contacts.list)
  {
    if (!c.real || c.normalForce.squaredNorm() == 0)
      continue;
    stiffness.add(c, ContactDiagonal(c.normal, c.kn, c.ks));
    if (viscEl)
      viscosity.add(c, ContactDiagonal(c.normal, c.cn, c.cs));
  }
  const double huge = std::numeric_limits<double>::max();
  double best = huge;
  for (std::size_t i = 0; i < b.size(); ++i)
  {
    // Split over processes, a ghost's sums lack the contacts its owner alone computes: the owner
    // counts it.
    if (!b.alive[i] || !b.dynamic[i] || stiffness.translational[i].isZero(0) || !countsBody(scene.domain.get(), i))
      continue;
    // The squared eigen-period of the springs; a dashpot's limit is linear in m / c.
    double dt = 1.41044 * timestepSafetyCoefficient * std::sqrt(stiffness.ratio(b, i, huge));
    if (viscEl)
      dt = std::min(dt, 2 * timestepSafetyCoefficient * viscosity.ratio(b, i, huge));
    best = std::min(best, dt);
  }
  if (scene.domain) // the smallest over processes: every process takes the same step
    best = scene.domain->min(best);
  return best == huge ? std::numeric_limits<double>::infinity() : best;
}

void GlobalStiffnessTimeStepper::run(Scene& scene)
{
  if (!active || !(!computedOnce || scene.iter % std::max<std::int64_t>(timeStepUpdateInterval, 1) == 0 || scene.iter < 2))
    return;
  if (defaultDt < 0)
    defaultDt = timestepSafetyCoefficient * (scene.domain ? scene.domain->min(scene.pWaveTimeStep()) : scene.pWaveTimeStep());
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
