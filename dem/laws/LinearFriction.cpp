// Linear elastic contact with Coulomb friction (Cundall & Strack), as Yade's
// Ip2_FrictMat_FrictMat_FrictPhys + Law2_ScGeom_FrictPhys_CundallStrack: a linear spring, no
// damping and the incremental shear spring capped by Coulomb friction.
#include "dem/laws/PartsLaw.h"
#include "dem/contact/SphereLanesStore.h"

#include <algorithm>
#include <cmath>
#include <cstddef>

namespace talus::dem
{
namespace
{
/// Harmonic-type average 2ab/(a+b) of two springs in series, 0 if both are 0.
double series(double a, double b) { return a + b > 0 ? 2 * a * b / (a + b) : 0.0; }

/// Ip2_FrictMat_FrictMat_FrictPhys: any pair of elastic materials (FrictMat and its kin).
struct FrictPhys
{
  static constexpr const char* ip2 = "Ip2_FrictMat_FrictMat_FrictPhys";
  static constexpr bool usesExtra = false;
  [[nodiscard]] int handles(const Material& /*m1*/, const Material& /*m2*/) const { return 1; }

  /// Two springs in series, each of stiffness E_i * 2 r_i (normal) and E_i * 2 r_i * nu_i
  /// (shear); friction angle = the smaller of the two.
  void initialize(Contact& c, ContactExtra* /*x*/, const Scene& scene) const
  {
    const Material& m1 = scene.materials[static_cast<std::size_t>(scene.bodies.material[static_cast<std::size_t>(c.id1)])];
    const Material& m2 = scene.materials[static_cast<std::size_t>(scene.bodies.material[static_cast<std::size_t>(c.id2)])];
    const double a = m1.young * c.refR1, b = m2.young * c.refR2;
    c.kn = series(a, b);
    c.ks = series(a * m1.poisson, b * m2.poisson);
    c.cn = c.cs = 0;
    c.tanPhi = std::tan(std::min(m1.frictionAngle, m2.frictionAngle));
  }
};

struct LinearFrictionNames
{
  static constexpr const char* law = "Law2_ScGeom_FrictPhys_CundallStrack";
  static SphereLanes sphereLanes(Contact* const* c, const std::int64_t* k, const StepContext& step);
};

/// The law's force() of four sphere contacts in AVX2 lanes: the linear spring, no damping, the
/// shear spring capped from the normal force's squared length, the operations in force()'s order.
[[gnu::target("avx2")]] SphereLanes LinearFrictionNames::sphereLanes(Contact* const* c, const std::int64_t* /*k*/,
                                                                       const StepContext& step)
{
  using namespace avx2;
  SphereGeometry g = sphereGeometry(c, step.bodies, step.dt, step.cell, &step.images);
  if (g.touching == 0)
    return {};
  static_assert(offsetof(Contact, ks) == offsetof(Contact, kn) + sizeof(double), "kn and ks load as a pair");
  __m256d kn, ks;
  loadPairs(c, offsetof(Contact, kn), kn, ks);
  const Lanes3 normalForce = scale(mul(kn, g.penetration), g.normal);
  g.shearForce = sub(g.shearForce, scale(ks, g.shearIncrement));
  const __m256d tanPhi = load(c, &Contact::tanPhi);
  const __m256d maxFs2 = mul(mul(dot(normalForce, normalForce), tanPhi), tanPhi);
  const __m256d fs2 = dot(g.shearForce, g.shearForce);
  const __m256d sliding = _mm256_cmp_pd(fs2, maxFs2, _CMP_GT_OQ);
  if (_mm256_movemask_pd(sliding) != 0)
    g.shearForce = select(sliding, scale(_mm256_sqrt_pd(div(maxFs2, fs2)), g.shearForce), g.shearForce);
  storeForces(g, normalForce, add(normalForce, g.shearForce), c, g.touching);
  return {g.touching, g.touching, deepLanes(g, step.maxOverlapRatio, g.touching)};
}
} // namespace

/// F_n = kn u_n n; F_s -= ks du_s, capped at tan(phi) |F_n|; sliding dissipates the slip
/// (F_trial - F_s) / ks times F_s; elastic energy 1/2 kn u_n^2 + 1/2 Fs^2 / ks.
using LinearFriction
    = PartsLaw<LinearFrictionNames, FrictPhys, parts::LinearSpring, parts::NoDamping,
               parts::IncrementalCoulomb<parts::CoulombLimit::FromNormalForce, false>>;

TALUS_REGISTER_PARTS_LAW(LinearFriction, "linear")
} // namespace talus::dem
