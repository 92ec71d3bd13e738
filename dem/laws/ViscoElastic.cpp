// Linear visco-elastic contact (spring-dashpot) with Coulomb friction, as Yade's
// Ip2_ViscElMat_ViscElMat_ViscElPhys + Law2_ScGeom_ViscElPhys_Basic.
#include "dem/Clump.h"
#include "dem/ContactLawKernel.h"

#include <algorithm>
#include <cmath>

namespace talus::dem
{
class ViscoElastic : public ContactLawKernel<ViscoElastic>
{
public:
  [[nodiscard]] std::string typeName() const override { return "Law2_ScGeom_ViscElPhys_Basic"; }
  [[nodiscard]] std::string physicsName() const override { return "Ip2_ViscElMat_ViscElMat_ViscElPhys"; }
  [[nodiscard]] int handles(const Material& m1, const Material& m2) const override
  {
    return m1.kind == MaterialKind::ViscEl && m2.kind == MaterialKind::ViscEl ? 2 : 0;
  }

  /// From (tc, en, et): the spring-dashpot of reduced mass m that lasts tc and restitutes en:
  /// kn = m (pi^2 + ln^2 en) / tc^2, cn = -2 m ln(en) / tc; shear the same with et and 2/7 m.
  /// The reduced mass m1 m2 / (m1 + m2) is the mass of the dynamic body against a fixed one
  /// (Yade instead gives the fixed body the other's mass, halving m: contacts with walls then
  /// last sqrt(2) tc). Parameters of the two materials are averaged. From (kn, cn, ks, cs):
  /// the two materials' springs and dashpots in series.
  void initialize(Contact& c, ContactExtra* /*x*/, const Scene& scene) const override
  {
    const Bodies& b = scene.bodies;
    const auto i1 = static_cast<std::size_t>(c.id1), i2 = static_cast<std::size_t>(c.id2);
    const Material& m1 = scene.materials[static_cast<std::size_t>(b.material[i1])];
    const Material& m2 = scene.materials[static_cast<std::size_t>(b.material[i2])];
    c.tanPhi = std::tan(std::min(m1.frictionAngle, m2.frictionAngle));
    if (std::isfinite(m1.tc) && std::isfinite(m2.tc))
    {
      // A clump member vibrates with its whole clump (as in Yade).
      const double mass1 = rigidDynamic(b, i1) ? rigidMass(b, i1) : 0, mass2 = rigidDynamic(b, i2) ? rigidMass(b, i2) : 0;
      const double m = mass1 > 0 && mass2 > 0 ? mass1 * mass2 / (mass1 + mass2) : std::max(mass1, mass2);
      const double tc = 0.5 * (m1.tc + m2.tc), en = 0.5 * (m1.en + m2.en), et = 0.5 * (m1.et + m2.et);
      const double ln = std::log(en), lt = std::log(et);
      c.kn = m * (M_PI * M_PI + ln * ln) / (tc * tc);
      c.cn = -2.0 * m * ln / tc;
      c.ks = 2.0 / 7.0 * m * (M_PI * M_PI + lt * lt) / (tc * tc);
      c.cs = -2.0 * 2.0 / 7.0 * m * lt / tc;
      return;
    }
    auto inSeries = [](double a, double b2) { return a > 0 && b2 > 0 ? a * b2 / (a + b2) : 0.0; };
    const double kn1 = std::isfinite(m1.kn) ? m1.kn : m2.kn, kn2 = std::isfinite(m2.kn) ? m2.kn : m1.kn;
    const double ks1 = std::isfinite(m1.ks) ? m1.ks : m2.ks, ks2 = std::isfinite(m2.ks) ? m2.ks : m1.ks;
    const double cn1 = std::isfinite(m1.cn) ? m1.cn : m2.cn, cn2 = std::isfinite(m2.cn) ? m2.cn : m1.cn;
    const double cs1 = std::isfinite(m1.cs) ? m1.cs : m2.cs, cs2 = std::isfinite(m2.cs) ? m2.cs : m1.cs;
    c.kn = inSeries(kn1, kn2);
    c.ks = inSeries(ks1, ks2);
    c.cn = inSeries(cn1, cn2);
    c.cs = inSeries(cs1, cs2);
  }

  /// F_n = kn u_n - cn v_n (may be attractive while the dashpot pulls, which is what makes the
  /// restitution exactly en); F_s = elastic history - ks du_s plus viscous -cs v_s, capped at
  /// tan(phi) |F_n| (the viscous part is dropped while sliding).
  /// Energy: the dashpots dissipate cn vn^2 dt + cs |vs|^2 dt (with the half-step velocity the
  /// force used: first order in dt / tc); while sliding, friction dissipates its work less the
  /// change of the spring's energy (the shear dashpot is then inactive).
  template <bool Track>
  void force(Contact& c, std::size_t /*k*/, const StepContext& step, ContactEnergy& e) const
  {
    const double dt = step.dt;
    const Vec3 v = incidentVelocity(c, step.bodies, step.cell ? step.cell->shiftVelocity(c.cellDist) : Vec3::Zero());
    const double vn = c.normal.dot(v);
    c.normalForce = (c.kn * c.penetration - c.cn * vn) * c.normal;
    const Vec3 before = c.shearForce;
    c.shearForce -= c.ks * c.shearIncrement;
    Vec3 viscous = -c.cs * (c.shearIncrement / dt);
    const Vec3 total = c.shearForce + viscous;
    const double maxFs2 = c.normalForce.squaredNorm() * c.tanPhi * c.tanPhi;
    if (total.squaredNorm() > maxFs2)
    {
      const Vec3 trial = c.shearForce;
      c.shearForce = total * std::sqrt(maxFs2 / total.squaredNorm());
      viscous.setZero();
      // Friction's work over the step's shear displacement, less what the spring now holds
      // more (the capped force need not be parallel to the elastic trial force here).
      if constexpr (Track)
        if (c.ks > 0)
          e.plastDissip += (c.shearForce.dot(trial - before) - 0.5 * (c.shearForce.squaredNorm() - before.squaredNorm())) / c.ks;
    }
    if constexpr (Track)
      e.viscDamp += (c.cn * vn * vn - viscous.dot(c.shearIncrement / dt)) * dt;
    c.force = c.normalForce + c.shearForce + viscous;
  }

  /// 1/2 kn u^2 + 1/2 Fs^2 / ks (the dashpots store nothing).
  double elastic(const Contact& c, const ContactExtra* /*x*/) const
  {
    return 0.5 * c.kn * c.penetration * c.penetration + (c.ks > 0 ? 0.5 * c.shearForce.squaredNorm() / c.ks : 0.0);
  }
};

TALUS_REGISTER_CONTACT_LAW(ViscoElastic, "Law2_ScGeom_ViscElPhys_Basic", "viscoelastic")
} // namespace talus::dem
