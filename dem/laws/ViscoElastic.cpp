// Linear visco-elastic contact (spring-dashpot) with Coulomb friction and rolling resistance,
// as Yade's Ip2_ViscElMat_ViscElMat_ViscElPhys + Law2_ScGeom_ViscElPhys_Basic: the motion at
// Yade's contact point, a linear spring, a normal dashpot that cannot pull, the shear spring
// driven by the contact point's velocity with its dashpot while it sticks, and rolling
// resistance once a material asks for it.
#include "dem/laws/PartsLaw.h"
#include "dem/contact/SphereLanesStore.h"
#include "dem/laws/StateOnDemand.h"
#include "dem/laws/parts/ContactPointMotion.h"
#include "dem/laws/parts/NormalDashpot.h"
#include "dem/laws/parts/RollingResistance.h"
#include "dem/laws/parts/VelocityShear.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace talus::dem
{
namespace
{
/// Restitution of a linear spring-dashpot collision of mass m whose force is never attractive
/// (Schwager and Poeschel 2007, the form Yade's get_en_from_cn evaluates): beta = cn / 2m,
/// omega0 = sqrt(kn / m); under-, over- and critically damped cases.
double restitutionOf(double cn, double m, double kn)
{
  const double beta = 0.5 * cn / m, omega0 = std::sqrt(kn / m);
  if (beta == omega0 / std::sqrt(2.0) || beta == omega0) // the formulas' singular points: just beside them
    return restitutionOf(cn + 1e-8, m, kn);
  if (beta < omega0 / std::sqrt(2.0))
  {
    const double omega = std::sqrt(omega0 * omega0 - beta * beta);
    return std::exp(-beta / omega * (M_PI - std::atan(2.0 * beta * omega / (omega * omega - beta * beta))));
  }
  if (beta < omega0)
  {
    const double omega = std::sqrt(omega0 * omega0 - beta * beta);
    return std::exp(-beta / omega * std::atan(-2.0 * beta * omega / (omega * omega - beta * beta)));
  }
  if (beta > omega0)
  {
    const double big = std::sqrt(beta * beta - omega0 * omega0);
    return std::exp(-beta / big * std::log((beta + big) / (beta - big)));
  }
  return 0; // NaN input
}

/// The dashpot cn that gives restitution en to a collision of mass m on spring kn: Newton's
/// method from cn = 1e-8 with a central-difference slope, stopped at 1% relative error in en,
/// as Yade's find_cn_from_en (so the dashpot is Yade's to round-off, error included). Not
/// converged in 15 iterations: 0 (no damping), with Yade's warning.
double dashpotFor(double en, double m, double kn, BodyId id1, BodyId id2)
{
  const double eps = 1e-8;
  double cn = eps, got = restitutionOf(cn, m, kn), error = 1.0 / eps;
  for (int i = 0; error > 1e-2 || std::isnan(error); ++i)
  {
    if (i == 15)
    {
      std::fprintf(stderr,
                   "Warning: Ip2_ViscElMat_ViscElMat_ViscElPhys: the dashpot for en=%g between bodies %d and %d was not "
                   "found in 15 Newton iterations; the contact is left undamped (cn=0), as Yade does\n",
                   en, id1, id2);
      return 0;
    }
    double slope = (restitutionOf(cn - eps, m, kn) - restitutionOf(cn + eps, m, kn)) / (-2.0 * eps);
    slope = std::abs(slope) > 1e-15 ? slope : 1e-15;
    cn -= (got - en) / slope;
    got = restitutionOf(cn, m, kn);
    error = std::abs(got - en) / en;
  }
  return cn;
}

/// Two springs (or dashpots) in series, a zero one left out (Yade's contactParameterCalculation).
double inSeries(double a, double b)
{
  const double compliance = (a != 0 ? 1 / a : 0) + (b != 0 ? 1 / b : 0);
  return compliance != 0 ? 1 / compliance : 0;
}

/// Ip2_ViscElMat_ViscElMat_ViscElPhys: pairs of ViscElMat; its per-pair parameters (Yade's
/// MatchMakers tc, en, et, frictAngle).
struct ViscElPhys
{
  static constexpr const char* ip2 = "Ip2_ViscElMat_ViscElMat_ViscElPhys";
  static constexpr bool usesExtra = false;
  [[nodiscard]] int handles(const Material& m1, const Material& m2) const
  {
    return m1.kind == MaterialKind::ViscEl && m2.kind == MaterialKind::ViscEl ? 2 : 0;
  }

  PairParameter tc, en, et, frictAngle;
  mutable DeferredFailure setupFailure; ///< the first error met while making contacts, reported after the step
  void stepDone() { setupFailure.throwIfFailed(); }

  [[nodiscard]] std::vector<std::string> parameterNames() const { return {"tc", "en", "et", "frictAngle"}; }
  template <class Unknown>
  void setPairParameter(const std::string& name, const PairParameter& value, const Unknown& unknown)
  {
    PairParameter* p = name == "tc"           ? &tc
                       : name == "en"         ? &en
                       : name == "et"         ? &et
                       : name == "frictAngle" ? &frictAngle
                                              : nullptr;
    if (!p)
      unknown(name);
    *p = value;
    p->given = true;
  }

  /// Yade's Ip2: kn, cn, ks, cs of each side from the first form both materials (or the
  /// functor) give, then in series. The mass m of the collision is the reduced mass of the two
  /// bodies' own masses (a clump member's own, a fixed sphere's or a box's too), a massless
  /// body (wall, facet) taking the other's.
  ///  - tc, en, et: per side 2 m (pi^2 + ln^2 en) / tc^2, -4 m ln(en) / tc; shear the same with
  ///    et and 2/7 (the pair lasts tc and restitutes en if its force may pull);
  ///  - kn, cn, ks, cs as given;
  ///  - young, poisson: per side 2 E R and 2 E R poisson (R the sphere's reference radius, a
  ///    wall's the sphere's), with cn, cs as given or cn from en (the restitution of the
  ///    never-pulling spring-dashpot, lowered by lubrication) and no shear dashpot.
  void initialize(Contact& c, ContactExtra* /*x*/, const Scene& scene) const
  {
    const Bodies& b = scene.bodies;
    const auto i1 = static_cast<std::size_t>(c.id1), i2 = static_cast<std::size_t>(c.id2);
    const int id1 = b.material[i1], id2 = b.material[i2];
    const Material& m1 = scene.materials[static_cast<std::size_t>(id1)];
    const Material& m2 = scene.materials[static_cast<std::size_t>(id2)];
    auto where = [&] {
      return " (bodies " + std::to_string(c.id1) + " and " + std::to_string(c.id2) + ", materials '" + m1.label
             + "' and '" + m2.label + "')";
    };
    auto same = [](double a, double b2) { return std::isfinite(a) == std::isfinite(b2); };
    if (!(same(m1.tc, m2.tc) && same(m1.en, m2.en) && same(m1.et, m2.et) && same(m1.kn, m2.kn)
          && same(m1.cn, m2.cn) && same(m1.ks, m2.ks) && same(m1.cs, m2.cs)))
      return setupFailure.fail("Ip2_ViscElMat_ViscElMat_ViscElPhys: both ViscElMat must give the same set of tc, "
                               "en, et, kn, cn, ks, cs" + where());
    if (m1.mRtype != m2.mRtype)
      return setupFailure.fail("Ip2_ViscElMat_ViscElMat_ViscElPhys: mRtype differs between the materials" + where());
    // The functor's value for the pair if it was given one, else the materials' mean.
    bool missing = false;
    auto pick = [&](const PairParameter& p, double v1, double v2) {
      if (!p.given)
        return (v1 + v2) / 2.0;
      const std::optional<double> v = p.at(id1, id2);
      missing = missing || !v;
      return v.value_or(0.0);
    };

    double mass1 = b.mass[i1], mass2 = b.mass[i2];
    if (mass1 == 0 && mass2 > 0)
      mass1 = mass2;
    else if (mass2 == 0 && mass1 > 0)
      mass2 = mass1;
    const double massR = mass1 * mass2 / (mass1 + mass2);
    const double r1 = c.refR1 > 0 ? c.refR1 : c.refR2, r2 = c.refR2 > 0 ? c.refR2 : c.refR1;

    double kn1 = 0, kn2 = 0, cn1 = 0, cn2 = 0, ks1 = 0, ks2 = 0, cs1 = 0, cs2 = 0;
    if ((std::isfinite(m1.tc) && std::isfinite(m1.en) && std::isfinite(m1.et)) || (tc.given && en.given && et.given))
    {
      const double time = pick(tc, m1.tc, m2.tc), normal = pick(en, m1.en, m2.en), shear = pick(et, m1.et, m2.et);
      kn1 = kn2 = 1 / time / time * (M_PI * M_PI + std::pow(std::log(normal), 2)) * massR * 2;
      cn1 = cn2 = -2.0 / time * std::log(normal) * massR * 2;
      ks1 = ks2 = 2.0 / 7.0 / time / time * (M_PI * M_PI + std::pow(std::log(shear), 2)) * massR * 2;
      cs1 = cs2 = -4.0 / 7.0 / time * std::log(shear) * massR * 2;
    }
    else if (std::isfinite(m1.kn) && std::isfinite(m1.ks) && std::isfinite(m1.cn) && std::isfinite(m1.cs))
    {
      kn1 = m1.kn, kn2 = m2.kn, ks1 = m1.ks, ks2 = m2.ks, cn1 = m1.cn, cn2 = m2.cn, cs1 = m1.cs, cs2 = m2.cs;
    }
    else
    {
      kn1 = 2 * m1.young * r1;
      kn2 = 2 * m2.young * r2;
      ks1 = kn1 * m1.poisson;
      ks2 = kn2 * m2.poisson;
      if (std::isfinite(m1.cn) && std::isfinite(m1.cs))
        cn1 = m1.cn, cn2 = m2.cn, cs1 = m1.cs, cs2 = m2.cs;
      else if (std::isfinite(m1.en))
      {
        double restitution = pick(en, m1.en, m2.en);
        if (m1.lubrication && m2.lubrication)
          restitution = lubricated(restitution, c, b, scene.periodic ? &scene.cell : nullptr, m1, m2, r1, r2);
        cn1 = cn2 = 2.0 * dashpotFor(restitution, massR, inSeries(kn1, kn2), c.id1, c.id2);
      }
      else
        return setupFailure.fail("Ip2_ViscElMat_ViscElMat_ViscElPhys: a ViscElMat without tc or kn needs en (or "
                                 "cn and cs) besides young and poisson" + where());
    }
    c.kn = inSeries(kn1, kn2);
    c.ks = inSeries(ks1, ks2);
    c.cn = inSeries(cn1, cn2);
    c.cs = inSeries(cs1, cs2);
    c.tanPhi = std::tan(frictAngle.given ? pick(frictAngle, 0, 0) : std::min(m1.frictionAngle, m2.frictionAngle));
    if (missing)
      return setupFailure.fail("Ip2_ViscElMat_ViscElMat_ViscElPhys: a MatchMaker (tc, en, et or frictAngle) has no "
                               "value for this pair of materials: list the pair in its matches, or give algo='val' "
                               "with val" + where());
  }

  /// Yade's lubricated restitution: en (1 + ln(roughness / mean radius) / St), at least 1e-3,
  /// with St = rho |v_n| (r1 + r2) / eta the Stokes number of the approach (means of the two
  /// materials' density, viscoDyn and roughnessScale).
  static double lubricated(double en, const Contact& c, const Bodies& b, const Cell* cell, const Material& m1,
                           const Material& m2, double r1, double r2)
  {
    const double vn = parts::ContactPointMotion(c, b, cell).vn;
    const double density = (m1.density + m2.density) / 2., viscosity = (m1.viscoDyn + m2.viscoDyn) / 2.;
    const double roughness = (m1.roughnessScale + m2.roughnessScale) / 2.;
    const double stokes = density * std::abs(vn) * (r1 + r2) / viscosity;
    return std::max(1e-3, en * (1 + 1 / stokes * std::log(roughness / ((r1 + r2) * 0.5))));
  }
};

struct ViscoElasticNames
{
  static constexpr const char* law = "Law2_ScGeom_ViscElPhys_Basic";
  static SphereLanes sphereLanes(Contact* const* c, const std::int64_t* k, const StepContext& step);
};

/// The law's force() of four sphere contacts in AVX2 lanes, the operations in force()'s order:
/// the motion at the contact point, the linear spring with its dashpot that cannot pull, the
/// velocity-driven shear spring capped by the normal force, its dashpot while it sticks.
[[gnu::target("avx2")]] SphereLanes ViscoElasticNames::sphereLanes(Contact* const* c, const std::int64_t* /*k*/,
                                                                     const StepContext& step)
{
  using namespace avx2;
  const SphereGeometry g = sphereGeometry(c, step.bodies, step.dt, step.cell, &step.images);
  if (g.touching == 0)
    return {};
  const Bodies& b = step.bodies;
  std::size_t i1[4], i2[4];
  for (int i = 0; i < 4; ++i)
  {
    i1[i] = static_cast<std::size_t>(c[i]->id1);
    i2[i] = static_cast<std::size_t>(c[i]->id2);
  }
  // ContactPointMotion between spheres: body 2's arm and velocity are its periodic image's for a
  // pair across the cell's boundary (zero shifts inside it).
  const __m256d zero = _mm256_setzero_pd();
  const Lanes3 none{zero, zero, zero};
  const ImageShift& shift = g.image;
  const Lanes3 c1x = sub(g.contactPoint, load(b.pos, i1));
  const Lanes3 c2x = sub(sub(g.contactPoint, load(b.pos, i2)), shift.offset);
  const Lanes3 v = sub(add(load(b.vel, i1), cross(load(b.angVel, i1), c1x)),
                       add(add(load(b.vel, i2), shift.velocity), cross(load(b.angVel, i2), c2x)));
  const __m256d vn = dot(g.normal, v);
  const Lanes3 vs = sub(v, scale(vn, g.normal));
  // LinearSpring and NormalDashpot.
  const __m256d fn = add(mul(load(c, &Contact::kn), g.penetration), mul(load(c, &Contact::cn), vn));
  const Lanes3 normalForce = select(_mm256_cmp_pd(fn, zero, _CMP_LT_OQ), none, scale(fn, g.normal));
  const __m256d pressing = _mm256_max_pd(zero, fn);
  // VelocityShear.
  Lanes3 shear = add(g.shearForce, scale(mul(load(c, &Contact::ks), broadcast(step.dt)), vs));
  const __m256d tanPhi = load(c, &Contact::tanPhi);
  const __m256d maxFs2 = mul(mul(mul(pressing, pressing), tanPhi), tanPhi);
  const __m256d fs2 = dot(shear, shear);
  const __m256d sliding = _mm256_cmp_pd(fs2, maxFs2, _CMP_GT_OQ);
  if (_mm256_movemask_pd(sliding) != 0)
    shear = select(sliding, scale(div(_mm256_sqrt_pd(maxFs2), _mm256_sqrt_pd(fs2)), shear), shear);
  const Lanes3 viscous = select(sliding, none, scale(load(c, &Contact::cs), vs));
  SphereGeometry out = g;
  out.shearForce = shear;
  storeForces(out, normalForce, add(add(normalForce, shear), viscous), c, g.touching);
  return {g.touching, g.touching, deepLanes(g, step.maxOverlapRatio, g.touching)};
}

/// F_n = kn u_n + cn v_n along the normal, never attractive; elastic shear incremental,
/// F_s += ks v_s dt, capped at |F_n| tan(phi), plus the shear dashpot cs v_s only while not
/// sliding; v the velocity of body 1 relative to body 2 at Yade's contact point; rolling
/// resistance (mR > 0) with the Moments part. Elastic energy 1/2 kn u^2 + 1/2 Fs^2 / ks.
template <class Moments>
using ViscoElasticWith = PartsLaw<ViscoElasticNames, ViscElPhys, parts::LinearSpring, parts::NormalDashpot,
                                  parts::VelocityShear, Moments, parts::ContactPointMotion>;

/// Some visco-elastic material has rolling resistance.
bool rollingResistance(const Scene& scene)
{
  return std::any_of(scene.materials.begin(), scene.materials.end(),
                     [](const Material& m) { return m.kind == MaterialKind::ViscEl && m.mR > 0; });
}
} // namespace

/// The law Yade scripts name: without rolling resistance, or with it from the first step any
/// visco-elastic material has mR > 0 (and from then on: contacts made before keep their mR).
using ViscoElastic = StateOnDemand<ViscoElasticWith<parts::NoMoments>, ViscoElasticWith<parts::RollingResistance>,
                                   rollingResistance>;

TALUS_REGISTER_PARTS_LAW(ViscoElastic, "viscoelastic")
} // namespace talus::dem
