// Hertz-Mindlin contact with Coulomb friction and Thornton's viscous damping, as Yade's
// Ip2_FrictMat_FrictMat_MindlinPhys + Law2_ScGeom_MindlinPhys_Mindlin (without adhesion and
// rolling moments): Hertz's spring, Thornton's damping and the incremental shear spring capped
// by Coulomb friction, with the shear dashpot while it sticks.
#include "dem/laws/PartsLaw.h"
#include "dem/contact/SphereLanesStore.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <stdexcept>

namespace talus::dem
{
namespace
{
constexpr double notGiven = std::numeric_limits<double>::quiet_NaN();

/// Damping ratio beta (fraction of the critical 2 sqrt(m kn)) that gives the restitution e with
/// Hertz springs, from the fit of Thornton et al. (2013), eqs. B6-B7 (as Yade does).
double thorntonDampingRatio(double e)
{
  if (e == 1.0)
    return 0.0;
  static constexpr double h[] = {-6.918798, -16.41105, 146.8049, -796.4559, 2928.711,
                                 -7206.864, 11494.29,  -11342.18, 6276.757, -1489.915};
  double poly = h[9];
  for (int i = 8; i >= 0; --i)
    poly = h[i] + e * poly;
  const double alpha = e * poly;
  return std::sqrt(1.0 / (1.0 - (1.0 + e) * (1.0 + e) * std::exp(alpha)) - 1.0);
}

/// Ip2_FrictMat_FrictMat_MindlinPhys: any pair of elastic materials (FrictMat and its kin), as
/// the linear law; its constants and damping ratios in HertzState.
struct MindlinPhys
{
  static constexpr const char* ip2 = "Ip2_FrictMat_FrictMat_MindlinPhys";
  static constexpr bool usesExtra = true;
  static constexpr bool stateForForcesOnly = true; ///< sets only what the parts' forces read
  [[nodiscard]] int handles(const Material& /*m1*/, const Material& /*m2*/) const { return 1; }

  // Restitution coefficients (normal, shear) or damping ratios, one value for all pairs of
  // materials or per pair (Yade's MatchMaker); not given: `given` false.
  PairParameter en, es, betan, betas;
  mutable DeferredFailure setupFailure; ///< a pair without a value, reported after the step
  void stepDone() { setupFailure.throwIfFailed(); }

  /// The parameter of that name (MindlinPhys or const MindlinPhys).
  template <class Self, class Unknown>
  static auto& named(Self& self, const std::string& name, const Unknown& unknown)
  {
    if (name == "en")
      return self.en;
    if (name == "es")
      return self.es;
    if (name == "betan")
      return self.betan;
    if (name == "betas")
      return self.betas;
    unknown(name);
  }

  [[nodiscard]] std::vector<std::string> parameterNames() const { return {"en", "es", "betan", "betas"}; }
  /// One value for every pair; NaN: not given.
  template <class Unknown>
  void setParameter(const std::string& name, double value, const Unknown& unknown)
  {
    if (std::isnan(value))
      named(*this, name, unknown) = PairParameter{};
    else
    {
      PairParameter p;
      p.fallback = value;
      setPairParameter(name, p, unknown);
    }
  }
  template <class Unknown>
  void setPairParameter(const std::string& name, const PairParameter& value, const Unknown& unknown)
  {
    PairParameter& slot = named(*this, name, unknown);
    const bool restitution = name[0] == 'e';
    auto check = [&](double v) {
      if (!(restitution ? (v > 0 && v <= 1) : (v >= 0 && std::isfinite(v))))
        throw std::invalid_argument(std::string(MindlinPhys::ip2) + "." + name + " must be "
                                    + (restitution ? "in (0, 1]" : "finite and >= 0") + ", got " + std::to_string(v));
    };
    for (const auto& match : value.matches)
      check(match.second);
    if (value.fallback)
      check(*value.fallback);
    const PairParameter& other
        = named(*this, name == "en" ? "betan" : name == "betan" ? "en" : name == "es" ? "betas" : "es", unknown);
    if (other.given)
      throw std::invalid_argument(std::string(MindlinPhys::ip2) + ": only one of "
                                  + (name.back() == 'n' ? "en, betan" : "es, betas") + " can be specified");
    slot = value;
    slot.given = true;
  }
  /// The value for all pairs (NaN: not given, or given per pair).
  template <class Unknown>
  [[nodiscard]] double parameter(const std::string& name, const Unknown& unknown) const
  {
    const PairParameter& p = named(*this, name, unknown);
    return p.given && p.matches.empty() && p.fallback ? *p.fallback : notGiven;
  }

  /// Effective moduli of the two materials: E* = 1 / ((1 - nu1^2)/E1 + (1 - nu2^2)/E2),
  /// G* = 1 / ((2 - nu1)/G1 + (2 - nu2)/G2), R* = R1 R2 / (R1 + R2) from the contact's reference
  /// radii (for walls Yade's geometry gives both the sphere's radius, so R* = r/2; facets
  /// R* = 2r/3); kno = 4/3 E* sqrt(R*), kso = 8 G* sqrt(R*). Damping ratios from en, es when
  /// given (one alone stands for both), else betan, betas (betas defaults to betan), else none.
  void initialize(Contact& c, ContactExtra* x, const Scene& scene) const
  {
    const Material& m1 = scene.materials[static_cast<std::size_t>(scene.bodies.material[static_cast<std::size_t>(c.id1)])];
    const Material& m2 = scene.materials[static_cast<std::size_t>(scene.bodies.material[static_cast<std::size_t>(c.id2)])];
    const double da = c.refR1 > 0 ? c.refR1 : c.refR2, db = c.refR2 > 0 ? c.refR2 : c.refR1;
    const double ga = m1.young / (2 * (1 + m1.poisson)), gb = m2.young / (2 * (1 + m2.poisson));
    const double g = 1.0 / ((2 - m1.poisson) / ga + (2 - m2.poisson) / gb);
    const double e = m1.young * m2.young / ((1 - m1.poisson * m1.poisson) * m2.young + (1 - m2.poisson * m2.poisson) * m1.young);
    const double r = da * db / (da + db);
    x->kno = 4.0 / 3.0 * e * std::sqrt(r);
    x->kso = 8.0 * std::sqrt(r) * g;
    c.tanPhi = std::tan(std::min(m1.frictionAngle, m2.frictionAngle));
    // As Yade: en or es (one alone stands for both) gives both ratios by Thornton's fit; else
    // betan (default 0) and betas (default betan).
    const int id1 = scene.bodies.material[static_cast<std::size_t>(c.id1)];
    const int id2 = scene.bodies.material[static_cast<std::size_t>(c.id2)];
    bool missing = false;
    auto value = [&](const PairParameter& p) {
      const std::optional<double> v = p.at(id1, id2);
      missing = missing || !v;
      return v.value_or(0.0);
    };
    if (en.given || es.given)
    {
      x->betan = thorntonDampingRatio(value(en.given ? en : es));
      x->betas = thorntonDampingRatio(value(es.given ? es : en));
    }
    else
    {
      x->betan = betan.given ? value(betan) : 0.0;
      x->betas = betas.given ? value(betas) : x->betan;
    }
    if (missing)
      setupFailure.fail(std::string(ip2) + ": a MatchMaker (en, es, betan or betas) has no value for materials '" + m1.label
                        + "' and '" + m2.label + "' (bodies " + std::to_string(c.id1) + " and " + std::to_string(c.id2)
                        + "): list the pair in its matches, or give algo='val' with val");
    c.kn = c.ks = c.cn = c.cs = 0;
  }
};

struct HertzMindlinNames
{
  static constexpr const char* law = "Law2_ScGeom_MindlinPhys_Mindlin";
  static SphereLanes sphereLanes(Contact* const* c, const std::int64_t* k, const StepContext& step);
};

/// The law's force() of four sphere contacts in AVX2 lanes, the operations in force()'s order:
/// Hertz's spring and the shear spring capped by the normal force's magnitude, for contacts
/// without dashpots (no betan, betas: Yade's default); with one, the forces are left to force().
[[gnu::target("avx2")]] SphereLanes HertzMindlinNames::sphereLanes(Contact* const* c, const std::int64_t* k,
                                                                     const StepContext& step)
{
  using namespace avx2;
  const SphereGeometry g = sphereGeometry(c, step.bodies, step.dt, step.cell, &step.images);
  HertzState* const x[4] = {step.extra + k[0], step.extra + k[1], step.extra + k[2], step.extra + k[3]};
  const __m256d zero = _mm256_setzero_pd();
  const __m256d dashpots = _mm256_or_pd(
      _mm256_or_pd(_mm256_cmp_pd(load(x, &HertzState::betan), zero, _CMP_NEQ_UQ),
                   _mm256_cmp_pd(load(x, &HertzState::betas), zero, _CMP_NEQ_UQ)),
      _mm256_cmp_pd(load(c, &Contact::cs), zero, _CMP_NEQ_UQ));
  const unsigned forces = g.touching & ~static_cast<unsigned>(_mm256_movemask_pd(dashpots));
  if (forces != g.touching)
  {
    store(g, c, g.touching);
    return {g.touching, 0};
  }
  if (forces == 0)
    return {};
  // HertzSpring: u = max(overlap, 0) (MAXPD keeps its second operand unless the first is larger).
  const __m256d u = _mm256_max_pd(zero, g.penetration);
  const __m256d sqrtU = _mm256_sqrt_pd(u);
  const __m256d kno = load(x, &HertzState::kno);
  const __m256d ks = mul(load(x, &HertzState::kso), sqrtU);
  const __m256d fn = mul(mul(kno, u), sqrtU);
  const Lanes3 normalForce = scale(fn, g.normal);
  // IncrementalCoulomb from the magnitude; no shear dashpot (cs is 0).
  Lanes3 shear = sub(g.shearForce, scale(ks, g.shearIncrement));
  const __m256d maxFs = mul(fn, load(c, &Contact::tanPhi));
  const __m256d fs2 = dot(shear, shear);
  const __m256d sliding = _mm256_cmp_pd(fs2, mul(maxFs, maxFs), _CMP_GT_OQ);
  if (_mm256_movemask_pd(sliding) != 0)
    shear = select(sliding, scale(div(maxFs, _mm256_sqrt_pd(fs2)), shear), shear);
  SphereGeometry out = g;
  out.shearForce = shear;
  storeForces(out, normalForce, add(normalForce, shear), c, forces);
  store(mul(mul(broadcast(1.5), kno), sqrtU), at(c, &Contact::kn).data(), forces);
  store(ks, at(c, &Contact::ks).data(), forces);
  return {forces, forces, deepLanes(g, step.maxOverlapRatio, forces)};
}
} // namespace

/// F_n = kno u^1.5 - cn v_n (never attractive: the dashpot at most cancels the spring),
/// with tangent stiffnesses kn = 3/2 kno u^0.5, ks = kso u^0.5 and dashpots
/// cn = 2 betan sqrt(m kn), cs = 2 betas sqrt(m ks). Shear: elastic history -= ks du_s, capped at
/// tan(phi) |F_n|; the shear dashpot acts only while sticking. Elastic energy
/// 2/5 kno u^2.5 + 1/2 Fs^2 / ks.
using HertzMindlin = PartsLaw<HertzMindlinNames, MindlinPhys, parts::HertzSpring, parts::ThorntonDamping,
                              parts::IncrementalCoulomb<parts::CoulombLimit::FromMagnitude, true>>;

TALUS_REGISTER_PARTS_LAW(HertzMindlin, "hertz")
} // namespace talus::dem
