// Contact laws of Potential Blocks (Boon et al. 2012) and Potential Particles (Boon et al.
// 2013), as Yade's Ip2_FrictMat_FrictMat_KnKsPBPhys + Law2_SCG_KnKsPBPhys_KnKsPBLaw and
// Ip2_FrictMat_FrictMat_KnKsPhys + Law2_SCG_KnKsPhys_KnKsLaw: stiffnesses per unit contact
// area, times the area of the overlap region's section computed by the geometry. The two
// differ only where Yade's do: the particles' law has no separate boundary stiffness (its
// kn_i, ks_i are accepted and unused) and caps the shear force with the damped normal force.
#include "dem/ContactLawKernel.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace talus::dem
{
template <bool Particles>
class KnKs : public ContactLawKernel<KnKs<Particles>>
{
public:
  static constexpr bool usesExtra = true; // the contact area (ContactExtra::contactArea)

  // Ip2_FrictMat_FrictMat_KnKsPBPhys: stiffnesses per unit area (N/m^3) between non-boundary
  // blocks (Knormal, Kshear) and between a boundary block and a non-boundary one (kn_i, ks_i);
  // viscousDamping: fraction of the critical damping 2 sqrt(m kn) of the normal spring.
  double Knormal = 1e8, Kshear = 1e7, kn_i = 1e8, ks_i = 1e7, viscousDamping = 0;
  // Ig2_PB_PB_ScGeom.calContactArea: false takes an area of 1 (constant stiffnesses);
  // Law2's allowViscousAttraction: the damped normal force may pull.
  bool calContactArea = true, allowViscousAttraction = false;

  [[nodiscard]] std::string typeName() const override
  {
    return Particles ? "Law2_SCG_KnKsPhys_KnKsLaw" : "Law2_SCG_KnKsPBPhys_KnKsPBLaw";
  }
  [[nodiscard]] std::string physicsName() const override
  {
    return Particles ? "Ip2_FrictMat_FrictMat_KnKsPhys" : "Ip2_FrictMat_FrictMat_KnKsPBPhys";
  }
  [[nodiscard]] int handles(const Material&, const Material&) const override { return 1; }
  [[nodiscard]] bool handlesGeometry(ContactGeometryKind kind) const override
  {
    return Particles ? kind == ContactGeometryKind::ParticleParticle || kind == ContactGeometryKind::WallParticle
                     : kind == ContactGeometryKind::BlockBlock || kind == ContactGeometryKind::WallBlock;
  }

  [[nodiscard]] std::vector<std::string> parameterNames() const override
  {
    return {"Knormal", "Kshear", "kn_i", "ks_i", "viscousDamping", "calContactArea", "allowViscousAttraction"};
  }
  void setParameter(const std::string& name, double value) override
  {
    if (name == "calContactArea" || name == "allowViscousAttraction")
    {
      (name[0] == 'c' ? calContactArea : allowViscousAttraction) = value != 0;
      return;
    }
    double* slot = stiffness(name);
    if (!std::isfinite(value) || value < 0)
      throw std::invalid_argument(physicsName() + "." + name + " must be finite and >= 0, got " + std::to_string(value));
    *slot = value;
  }
  [[nodiscard]] double parameter(const std::string& name) const override
  {
    if (name == "calContactArea")
      return calContactArea ? 1 : 0;
    if (name == "allowViscousAttraction")
      return allowViscousAttraction ? 1 : 0;
    return *const_cast<KnKs*>(this)->stiffness(name);
  }

  /// Friction from the smaller FrictMat angle; stiffnesses follow the area at every step.
  void initialize(Contact& c, ContactExtra* /*x*/, const Scene& scene) const override
  {
    const auto& b = scene.bodies;
    const Material& m1 = scene.materials[static_cast<std::size_t>(b.material[static_cast<std::size_t>(c.id1)])];
    const Material& m2 = scene.materials[static_cast<std::size_t>(b.material[static_cast<std::size_t>(c.id2)])];
    c.tanPhi = std::tan(std::min(m1.frictionAngle, m2.frictionAngle));
  }

  /// F_n = Knormal A u_n n (+ viscous part), F_s -= Kshear A du_s capped at tan(phi) |F_n
  /// elastic| (particles: |F_n| with its viscous part); with a boundary block kn_i, ks_i
  /// instead. A has a floor of (1e-3 R)^2 so a vertex touching a face still has some stiffness.
  template <bool Track>
  void force(Contact& c, std::size_t k, const StepContext& step, ContactEnergy& e) const
  {
    const Bodies& b = step.bodies;
    const auto i1 = static_cast<std::size_t>(c.id1), i2 = static_cast<std::size_t>(c.id2);
    const bool boundary = !Particles && (isBoundary(b, i1) || isBoundary(b, i2));
    const double floor = 1e-6 * std::min(c.refR1, c.refR2) * std::min(c.refR1, c.refR2);
    const double area = calContactArea ? std::max(step.extra[k].contactArea, floor) : 1.0;
    c.kn = (boundary ? kn_i : Knormal) * area;
    c.ks = (boundary ? ks_i : Kshear) * area;
    const Vec3 elastic = c.kn * c.penetration * c.normal;
    c.normalForce = elastic;
    if (viscousDamping > 0)
    {
      const double m = reducedMass(b, i1, i2);
      c.cn = viscousDamping * 2 * std::sqrt(m * c.kn);
      const double vn = incidentVelocity(c, b, Vec3::Zero()).dot(c.normal);
      c.normalForce -= c.cn * vn * c.normal;
      if constexpr (Track)
        e.viscDamp += c.cn * vn * vn * step.dt;
      if (!allowViscousAttraction && c.normalForce.dot(c.normal) < 0)
        c.normalForce.setZero();
    }
    c.shearForce -= c.ks * c.shearIncrement;
    const double maxFs2 = (Particles ? c.normalForce : elastic).squaredNorm() * c.tanPhi * c.tanPhi;
    const double fs2 = c.shearForce.squaredNorm();
    if (fs2 > maxFs2)
    {
      const Vec3 trial = c.shearForce;
      c.shearForce *= std::sqrt(maxFs2 / fs2);
      if constexpr (Track)
        e.plastDissip += (trial - c.shearForce).dot(c.shearForce) / c.ks;
    }
    c.force = c.normalForce + c.shearForce;
  }

  /// 1/2 kn u_n^2 + 1/2 Fs^2 / ks (the dashpot's part of the normal force stores nothing).
  double elastic(const Contact& c, const ContactExtra* /*x*/) const { return springEnergy(c, c.penetration); }

private:
  double* stiffness(const std::string& name)
  {
    double* slot = name == "Knormal"          ? &Knormal
                   : name == "Kshear"         ? &Kshear
                   : name == "kn_i"           ? &kn_i
                   : name == "ks_i"           ? &ks_i
                   : name == "viscousDamping" ? &viscousDamping
                                              : nullptr;
    if (!slot)
      this->unknownParameter(name);
    return slot;
  }
  static bool isBoundary(const Bodies& b, std::size_t i)
  {
    return b.shape[i] == ShapeKind::PotentialBlock && b.blocks[static_cast<std::size_t>(b.shapeIndex[i])].isBoundary;
  }
  /// Reduced mass of the pair; a body that is not moved by forces counts as infinitely heavy.
  static double reducedMass(const Bodies& b, std::size_t i1, std::size_t i2)
  {
    const bool d1 = b.dynamic[i1] && b.mass[i1] > 0, d2 = b.dynamic[i2] && b.mass[i2] > 0;
    if (d1 && d2)
      return b.mass[i1] * b.mass[i2] / (b.mass[i1] + b.mass[i2]);
    return d1 ? b.mass[i1] : d2 ? b.mass[i2] : 0.0;
  }
};

using KnKsPB = KnKs<false>;
using KnKsPP = KnKs<true>;
TALUS_REGISTER_CONTACT_LAW(KnKsPB, "Law2_SCG_KnKsPBPhys_KnKsPBLaw")
TALUS_REGISTER_CONTACT_LAW(KnKsPP, "Law2_SCG_KnKsPhys_KnKsLaw")
} // namespace talus::dem
