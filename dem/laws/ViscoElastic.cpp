// Linear visco-elastic contact (spring-dashpot) with Coulomb friction and rolling resistance,
// as Yade's Ip2_ViscElMat_ViscElMat_ViscElPhys + Law2_ScGeom_ViscElPhys_Basic.
#include "dem/laws/ContactLawKernel.h"
#include "dem/laws/parts/Coulomb.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdio>
#include <mutex>
#include <stdexcept>

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

/// Velocity v of body 1 relative to body 2 (or its periodic image) at the contact point, and the
/// arms c1x, c2x from their centres to it (Yade's Law2 takes these, not ScGeom's incident
/// velocity with the radii as arms). The contact point is Yade's: against a wall, the sphere's
/// centre projected on the wall's plane (Yade's Ig2_Wall_Sphere_ScGeom), not mid-overlap.
struct RelativeMotion
{
  Vec3 point, c1x, c2x, v;
  RelativeMotion(const Contact& c, const Bodies& b, const Cell* cell)
  {
    const auto i1 = static_cast<std::size_t>(c.id1), i2 = static_cast<std::size_t>(c.id2);
    Vec3 shift2 = Vec3::Zero(), shiftVel = Vec3::Zero();
    if (cell && c.cellDist != Eigen::Vector3i::Zero())
    {
      shift2 = cell->shift(c.cellDist);
      shiftVel = cell->shiftVelocity(c.cellDist);
    }
    point = c.contactPoint;
    if (c.kind == ContactGeometryKind::WallSphere)
    {
      const int axis = b.walls[static_cast<std::size_t>(b.shapeIndex[i1])].axis;
      point = b.pos[i2] + shift2;
      point[axis] = b.pos[i1][axis];
    }
    c1x = point - b.pos[i1];
    c2x = point - b.pos[i2] - shift2;
    v = (b.vel[i1] + b.angVel[i1].cross(c1x)) - (b.vel[i2] + shiftVel + b.angVel[i2].cross(c2x));
  }
};

/// The functor's per-pair parameters (Yade's MatchMakers tc, en, et, frictAngle) and the first
/// error met while setting up a contact.
struct ViscElSettings : DeferredFailure
{
  PairParameter tc, en, et, frictAngle;
};

/// The law's loops, without (Rolling false) or with rolling resistance, whose moments live in
/// Contacts::extra: scenes without it keep the plain contact records of the fast path.
template <bool Rolling>
class ViscoElasticKernel : public ContactLawKernel<ViscoElasticKernel<Rolling>>
{
public:
  static constexpr bool usesExtra = Rolling;
  explicit ViscoElasticKernel(ViscElSettings& settings) : settings_(settings) {}

  [[nodiscard]] std::string typeName() const override { return "Law2_ScGeom_ViscElPhys_Basic"; }
  [[nodiscard]] std::string physicsName() const override { return "Ip2_ViscElMat_ViscElMat_ViscElPhys"; }
  [[nodiscard]] int handles(const Material& m1, const Material& m2) const override
  {
    return m1.kind == MaterialKind::ViscEl && m2.kind == MaterialKind::ViscEl ? 2 : 0;
  }
  void stepDone() override { settings_.throwIfFailed(); }

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
  void initialize(Contact& c, ContactExtra* x, const Scene& scene) const override
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
      return settings_.fail("Ip2_ViscElMat_ViscElMat_ViscElPhys: both ViscElMat must give the same set of tc, en, "
                            "et, kn, cn, ks, cs" + where());
    if (m1.mRtype != m2.mRtype)
      return settings_.fail("Ip2_ViscElMat_ViscElMat_ViscElPhys: mRtype differs between the materials" + where());
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
    const Settings& s = settings_;
    if ((std::isfinite(m1.tc) && std::isfinite(m1.en) && std::isfinite(m1.et)) || (s.tc.given && s.en.given && s.et.given))
    {
      const double tc = pick(s.tc, m1.tc, m2.tc), en = pick(s.en, m1.en, m2.en), et = pick(s.et, m1.et, m2.et);
      kn1 = kn2 = 1 / tc / tc * (M_PI * M_PI + std::pow(std::log(en), 2)) * massR * 2;
      cn1 = cn2 = -2.0 / tc * std::log(en) * massR * 2;
      ks1 = ks2 = 2.0 / 7.0 / tc / tc * (M_PI * M_PI + std::pow(std::log(et), 2)) * massR * 2;
      cs1 = cs2 = -4.0 / 7.0 / tc * std::log(et) * massR * 2;
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
        double en = pick(s.en, m1.en, m2.en);
        if (m1.lubrication && m2.lubrication)
          en = lubricated(en, c, b, scene.periodic ? &scene.cell : nullptr, m1, m2, r1, r2);
        cn1 = cn2 = 2.0 * dashpotFor(en, massR, inSeries(kn1, kn2), c.id1, c.id2);
      }
      else
        return settings_.fail("Ip2_ViscElMat_ViscElMat_ViscElPhys: a ViscElMat without tc or kn needs en (or cn "
                              "and cs) besides young and poisson" + where());
    }
    c.kn = inSeries(kn1, kn2);
    c.ks = inSeries(ks1, ks2);
    c.cn = inSeries(cn1, cn2);
    c.cs = inSeries(cs1, cs2);
    c.tanPhi = std::tan(s.frictAngle.given ? pick(s.frictAngle, 0, 0) : std::min(m1.frictionAngle, m2.frictionAngle));
    if (missing)
      return settings_.fail("Ip2_ViscElMat_ViscElMat_ViscElPhys: a MatchMaker (tc, en, et or frictAngle) has no value "
                            "for this pair of materials: list the pair in its matches, or give algo='val' with val"
                            + where());
    if constexpr (Rolling)
    {
      // Twice the harmonic mean of the materials' mR > 0 (one alone: twice it), as Yade.
      x->mR = m1.mR > 0 || m2.mR > 0 ? 2.0 / ((m1.mR > 0 ? 1 / m1.mR : 0) + (m2.mR > 0 ? 1 / m2.mR : 0)) : 0;
      x->mRtype = static_cast<std::uint8_t>(m1.mRtype);
    }
  }

  /// Yade's Law2: F_n = kn u_n + cn v_n along the normal, never attractive (the dashpot cannot
  /// pull); elastic shear incremental, F_s += ks v_s dt, capped at |F_n| tan(phi), plus the shear
  /// dashpot cs v_s only while not sliding; v the velocity of body 1 relative to body 2 at the
  /// contact point (v_n > 0 approaching). Rolling resistance (mR > 0): a moment on body 1 of
  /// -mR |F_n| (w1 - w2) (mRtype 1), times also |c1 x w1 - c2 x w2| (mRtype 2), the opposite on
  /// body 2.
  /// Energy: what the contact force does beyond its springs, (F_n - kn u_n) v_n dt (the normal
  /// dashpot, and while it would pull the spring's release) plus cs |v_s|^2 dt; while sliding,
  /// friction dissipates its work less the change of the spring's energy; the rolling moment
  /// dissipates its power.
  template <bool Track>
  void force(Contact& c, std::size_t k, const StepContext& step, ContactEnergy& e) const
  {
    const Bodies& b = step.bodies;
    const auto i1 = static_cast<std::size_t>(c.id1), i2 = static_cast<std::size_t>(c.id2);
    const double dt = step.dt;
    const RelativeMotion r(c, b, step.cell);
    c.contactPoint = r.point; // the point the forces act at, for the bodies' torques
    const Vec3 &c1x = r.c1x, &c2x = r.c2x;
    const double vn = c.normal.dot(r.v);
    const Vec3 vs = r.v - vn * c.normal;

    const Vec3 before = c.shearForce;
    c.shearForce += c.ks * dt * vs;
    const double fn = c.kn * c.penetration + c.cn * vn;
    c.normalForce = fn < 0 ? Vec3::Zero() : Vec3(fn * c.normal);
    const double normal = std::max(fn, 0.0);
    const double maxFs2 = normal * normal * c.tanPhi * c.tanPhi;
    Vec3 viscous = Vec3::Zero();
    if (c.shearForce.squaredNorm() > maxFs2)
    {
      const Vec3 trial = parts::cap(c.shearForce, std::sqrt(maxFs2) / c.shearForce.norm());
      if constexpr (Track)
        if (c.ks > 0)
          e.plastDissip += (c.shearForce.dot(trial - before) - 0.5 * (c.shearForce.squaredNorm() - before.squaredNorm())) / c.ks;
    }
    else
      viscous = c.cs * vs;
    c.force = c.normalForce + c.shearForce + viscous;
    if constexpr (Track)
      e.viscDamp += ((normal - c.kn * c.penetration) * vn + viscous.dot(vs)) * dt;
    if constexpr (Rolling)
    {
      ContactExtra& x = step.extra[k];
      x.momentBending.setZero();
      if (x.mR > 0)
      {
        const Vec3 relAngVel = b.angVel[i1] - b.angVel[i2];
        double scale = x.mR * normal;
        if (x.mRtype == 2)
          scale *= (c1x.cross(b.angVel[i1]) - c2x.cross(b.angVel[i2])).norm();
        x.momentBending = scale * relAngVel; // the moment on body 2 (body 1 gets the opposite)
        if constexpr (Track)
          e.viscDamp += x.momentBending.dot(relAngVel) * dt;
      }
    }
  }

  /// 1/2 kn u^2 + 1/2 Fs^2 / ks (the dashpots store nothing).
  double elastic(const Contact& c, const ContactExtra* /*x*/) const { return springEnergy(c, c.penetration); }

private:
  using Settings = ViscElSettings;

  /// Yade's lubricated restitution: en (1 + ln(roughness / mean radius) / St), at least 1e-3,
  /// with St = rho |v_n| (r1 + r2) / eta the Stokes number of the approach (means of the two
  /// materials' density, viscoDyn and roughnessScale).
  static double lubricated(double en, const Contact& c, const Bodies& b, const Cell* cell, const Material& m1,
                           const Material& m2, double r1, double r2)
  {
    const double vn = c.normal.dot(RelativeMotion(c, b, cell).v);
    const double density = (m1.density + m2.density) / 2., viscosity = (m1.viscoDyn + m2.viscoDyn) / 2.;
    const double roughness = (m1.roughnessScale + m2.roughnessScale) / 2.;
    const double stokes = density * std::abs(vn) * (r1 + r2) / viscosity;
    return std::max(1e-3, en * (1 + 1 / stokes * std::log(roughness / ((r1 + r2) * 0.5))));
  }

  ViscElSettings& settings_;
};
} // namespace

/// The law Yade scripts name: the plain kernel, or the rolling one from the first step any
/// visco-elastic material has mR > 0 (and from then on: contacts made before keep their mR).
class ViscoElastic : public ContactLaw
{
public:
  [[nodiscard]] std::string typeName() const override { return plain_.typeName(); }
  [[nodiscard]] std::string physicsName() const override { return plain_.physicsName(); }
  [[nodiscard]] int handles(const Material& m1, const Material& m2) const override { return plain_.handles(m1, m2); }
  [[nodiscard]] bool needsExtra() const override { return rolling_; }
  void prepare(Scene& scene) override
  {
    if (!rolling_)
      rolling_ = std::any_of(scene.materials.begin(), scene.materials.end(),
                             [](const Material& m) { return m.kind == MaterialKind::ViscEl && m.mR > 0; });
    if (rolling_)
      alignContactExtra(scene.contacts);
  }
  void initialize(Contact& c, ContactExtra* x, const Scene& scene) const override { active().initialize(c, x, scene); }
  void computeForces(Scene& scene, std::uint8_t lawIndex) override { active().computeForces(scene, lawIndex); }
  std::int64_t computeAll(Scene& scene) override { return active().computeAll(scene); }
  std::int64_t computeAllIn(Scene& scene, std::int64_t first, std::int64_t last, ContactEnergy* energyBlocks) override
  {
    return active().computeAllIn(scene, first, last, energyBlocks);
  }
  void stepDone() override { active().stepDone(); }
  [[nodiscard]] double elasticEnergy(const Scene& scene, std::uint8_t lawIndex) const override
  {
    return active().elasticEnergy(scene, lawIndex);
  }
  [[nodiscard]] double grownElasticEnergy(const Scene& scene, std::uint8_t lawIndex,
                                          const std::vector<double>& grownBy) const override
  {
    return active().grownElasticEnergy(scene, lawIndex, grownBy);
  }
  [[nodiscard]] std::vector<std::string> parameterNames() const override { return {"tc", "en", "et", "frictAngle"}; }
  void setPairParameter(const std::string& name, const PairParameter& value) override
  {
    PairParameter* p = name == "tc"           ? &settings_.tc
                       : name == "en"         ? &settings_.en
                       : name == "et"         ? &settings_.et
                       : name == "frictAngle" ? &settings_.frictAngle
                                              : nullptr;
    if (!p)
      unknownParameter(name);
    *p = value;
    p->given = true;
  }

private:
  [[nodiscard]] ContactLaw& active() { return rolling_ ? static_cast<ContactLaw&>(withRolling_) : plain_; }
  [[nodiscard]] const ContactLaw& active() const
  {
    return rolling_ ? static_cast<const ContactLaw&>(withRolling_) : plain_;
  }
  ViscElSettings settings_;
  ViscoElasticKernel<false> plain_{settings_};
  ViscoElasticKernel<true> withRolling_{settings_};
  bool rolling_ = false;
};

TALUS_REGISTER_CONTACT_LAW(ViscoElastic, "Law2_ScGeom_ViscElPhys_Basic", "viscoelastic")
} // namespace talus::dem
