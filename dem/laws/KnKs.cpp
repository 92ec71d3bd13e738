// Contact laws of Potential Blocks (Boon et al. 2012) and Potential Particles (Boon et al.
// 2013), as Yade's Ip2_FrictMat_FrictMat_KnKsPBPhys + Law2_SCG_KnKsPBPhys_KnKsPBLaw and
// Ip2_FrictMat_FrictMat_KnKsPhys + Law2_SCG_KnKsPhys_KnKsLaw: stiffnesses per unit contact
// area, times the area of the overlap region's section computed by the geometry. The two
// differ only where Yade's do: the particles' law has no separate boundary stiffness (its
// kn_i, ks_i are accepted and unused) and caps the shear force with the damped normal force.
// The blocks' law also has Yade's rock-joint bonds (useFaceProperties): a contact between two
// intact-rock faces (BlockGen's rock bridges and cemented joints) carries a cohesion and a
// tensile strength until it breaks, then it is frictional.
#include "dem/laws/ContactLawKernel.h"
#include "dem/laws/parts/Bond.h"
#include "dem/laws/parts/Coulomb.h"

#include <algorithm>
#include <cmath>
#include <numbers>
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
  // Blocks only. Ip2's useFaceProperties: new contacts read the faces' rock-joint properties;
  // cohesionBroken, tensionBroken: the state given to the bond of a new contact between two
  // intact-rock faces (Yade's defaults, true: none; a scene of generated blocks sets them false
  // for its first step, so that only the faces that were cut are bonded). Law2's
  // allowBreakage: a bond whose shear strength is exceeded breaks (else it yields at its
  // strength, as Yade's); initialOverlapDistance: the overlap at zero normal force (blocks
  // generated overlapping by it can carry tension across a bond until they separate).
  bool useFaceProperties = false, cohesionBroken = true, tensionBroken = true, allowBreakage = false;
  double initialOverlapDistance = 0;

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
    std::vector<std::string> names{"Knormal", "Kshear", "kn_i", "ks_i", "viscousDamping", "calContactArea",
                                   "allowViscousAttraction"};
    if constexpr (!Particles)
      names.insert(names.end(), {"useFaceProperties", "cohesionBroken", "tensionBroken", "allowBreakage",
                                 "initialOverlapDistance"});
    return names;
  }
  void setParameter(const std::string& name, double value) override
  {
    if (bool* f = flag(name))
    {
      *f = value != 0;
      return;
    }
    double* slot = number(name);
    if (!std::isfinite(value) || value < 0)
      throw std::invalid_argument(physicsName() + "." + name + " must be finite and >= 0, got " + std::to_string(value));
    *slot = value;
  }
  [[nodiscard]] double parameter(const std::string& name) const override
  {
    auto* self = const_cast<KnKs*>(this);
    if (const bool* f = self->flag(name))
      return *f ? 1 : 0;
    return *self->number(name);
  }

  /// Friction from the smaller FrictMat angle; stiffnesses follow the area at every step;
  /// blocks: the bond of intact-rock faces (bondFaces).
  void initialize(Contact& c, ContactExtra* x, const Scene& scene) const override
  {
    const auto& b = scene.bodies;
    const Material& m1 = scene.materials[static_cast<std::size_t>(b.material[static_cast<std::size_t>(c.id1)])];
    const Material& m2 = scene.materials[static_cast<std::size_t>(b.material[static_cast<std::size_t>(c.id2)])];
    c.tanPhi = std::tan(std::min(m1.frictionAngle, m2.frictionAngle));
    if constexpr (!Particles)
    {
      if (x)
        bondFaces(c, *x, b);
    }
    else
      (void)x;
  }

  /// F_n = Knormal A u_n n (+ viscous part), F_s -= Kshear A du_s capped at tan(phi) |F_n
  /// elastic| (particles: |F_n| with its viscous part); with a boundary block kn_i, ks_i
  /// instead. A has a floor of (1e-3 R)^2 so a vertex touching a face still has some stiffness.
  /// Blocks: u_n less initialOverlapDistance; a bond pulls down to -tension A0 (then it breaks
  /// altogether, as Yade erases the contact) and adds cohesion A0 to the shear strength, which
  /// then takes the signed normal force (Mohr-Coulomb with a tension cut-off). A0 is the area
  /// when the bond formed (the cut face): the section through the contact point shrinks as the
  /// overlap, microns deep, turns into a wedge when the block tilts under the shear, and a
  /// bridge's strength must not follow it (it halved the strength of the test's bridge).
  template <bool Track>
  void force(Contact& c, std::size_t k, const StepContext& step, ContactEnergy& e) const
  {
    const Bodies& b = step.bodies;
    const auto i1 = static_cast<std::size_t>(c.id1), i2 = static_cast<std::size_t>(c.id2);
    const bool boundary = !Particles && (isBoundary(b, i1) || isBoundary(b, i2));
    const double area = calContactArea ? std::max(step.extra[k].contactArea, areaFloor(c)) : 1.0;
    c.kn = (boundary ? kn_i : Knormal) * area;
    c.ks = (boundary ? ks_i : Kshear) * area;
    ContactExtra* bond = nullptr;
    double un = c.penetration;
    if constexpr (!Particles)
    {
      un -= initialOverlapDistance;
      if (step.extra[k].intactRock)
        bond = &step.extra[k];
    }
    double fn = c.kn * ((bond && !bond->tensionBroken) ? un : std::max(un, 0.0));
    if (bond && !bond->tensionBroken && fn < -bond->normalAdhesion)
    {
      bond->tensionBroken = bond->cohesionBroken = 1;
      fn = 0;
    }
    const Vec3 elastic = fn * c.normal;
    c.normalForce = elastic;
    if (viscousDamping > 0)
    {
      const double m = reducedMass(b, i1, i2);
      c.cn = viscousDamping * 2 * std::sqrt(m * c.kn);
      const double vn = incidentVelocity(c, b, nullptr).dot(c.normal);
      c.normalForce -= c.cn * vn * c.normal;
      if constexpr (Track)
        e.viscDamp += c.cn * vn * vn * step.dt;
      // The dashpot never turns the spring's force around: no pull from a pressed contact (unless
      // allowViscousAttraction), no push from a bond that pulls.
      const double total = c.normalForce.dot(c.normal);
      if (!allowViscousAttraction && (fn >= 0 ? total < 0 : total > 0))
        c.normalForce.setZero();
    }
    c.shearForce -= c.ks * c.shearIncrement;
    const double friction = (Particles ? c.normalForce : elastic).norm() * c.tanPhi;
    const bool cohesive = bond && !bond->cohesionBroken;
    double maxFs = cohesive ? parts::bondedShearStrength(bond->shearAdhesion, fn, c.tanPhi) : friction;
    const double fs = c.shearForce.norm();
    if (fs > maxFs)
    {
      if (cohesive && allowBreakage)
      {
        bond->cohesionBroken = bond->tensionBroken = 1;
        maxFs = parts::frictionStrength(fn, c.tanPhi);
      }
      parts::slide<Track>(c, maxFs / fs, e);
    }
    c.force = c.normalForce + c.shearForce;
  }

  /// 1/2 kn u_n^2 + 1/2 Fs^2 / ks (the dashpot's part of the normal force stores nothing).
  double elastic(const Contact& c, const ContactExtra* /*x*/) const { return springEnergy(c, c.penetration); }

private:
  bool* flag(const std::string& name)
  {
    if (name == "calContactArea")
      return &calContactArea;
    if (name == "allowViscousAttraction")
      return &allowViscousAttraction;
    if constexpr (!Particles)
    {
      if (name == "useFaceProperties")
        return &useFaceProperties;
      if (name == "cohesionBroken")
        return &cohesionBroken;
      if (name == "tensionBroken")
        return &tensionBroken;
      if (name == "allowBreakage")
        return &allowBreakage;
    }
    return nullptr;
  }
  double* number(const std::string& name)
  {
    double* slot = name == "Knormal"          ? &Knormal
                   : name == "Kshear"         ? &Kshear
                   : name == "kn_i"           ? &kn_i
                   : name == "ks_i"           ? &ks_i
                   : name == "viscousDamping" ? &viscousDamping
                                              : nullptr;
    if (!Particles && name == "initialOverlapDistance")
      slot = &initialOverlapDistance;
    if (!slot)
      this->unknownParameter(name);
    return slot;
  }
  /// useFaceProperties: the contact's face on each block (the plane whose outward normal is
  /// within 1 degree of the contact normal, +n for body 1, -n for body 2). Both intact rock:
  /// a bond with the smaller cohesion and tension (Yade's rule) times the contact's area now;
  /// anything else (an edge or a corner, a wall, a boundary block) is frictional.
  void bondFaces(const Contact& c, ContactExtra& x, const Bodies& b) const
  {
    x.intactRock = 0;
    x.cohesionBroken = x.tensionBroken = 1;
    x.shearAdhesion = x.normalAdhesion = 0;
    if (!useFaceProperties || c.kind != ContactGeometryKind::BlockBlock)
      return;
    const auto i1 = static_cast<std::size_t>(c.id1), i2 = static_cast<std::size_t>(c.id2);
    if (isBoundary(b, i1) || isBoundary(b, i2))
      return;
    const PotentialBlockShape& s1 = block(b, i1);
    const PotentialBlockShape& s2 = block(b, i2);
    const int f1 = contactFace(s1, b.ori[i1], c.normal), f2 = contactFace(s2, b.ori[i2], -c.normal);
    if (f1 < 0 || f2 < 0)
      return;
    const auto p1 = static_cast<std::size_t>(f1), p2 = static_cast<std::size_t>(f2);
    if (!(s1.intactRock[p1] && s2.intactRock[p2]))
      return;
    x.intactRock = 1;
    const double area = calContactArea ? std::max(x.contactArea, areaFloor(c)) : 1.0;
    x.shearAdhesion = std::min(s1.cohesion[p1], s2.cohesion[p2]) * area;
    x.normalAdhesion = std::min(s1.tension[p1], s2.tension[p2]) * area;
    x.cohesionBroken = cohesionBroken ? 1 : 0;
    x.tensionBroken = tensionBroken ? 1 : 0;
  }
  static int contactFace(const PotentialBlockShape& s, const Quat& ori, const Vec3& outward)
  {
    const Vec3 local = ori.conjugate() * outward;
    const double cosLimit = std::cos(std::numbers::pi / 180);
    for (std::size_t k = 0; k < s.normals.size(); ++k)
      if (s.normals[k].dot(local) > cosLimit)
        return static_cast<int>(k);
    return -1;
  }
  static const PotentialBlockShape& block(const Bodies& b, std::size_t i)
  {
    return b.blocks[static_cast<std::size_t>(b.shapeIndex[i])];
  }
  /// (1e-3 R)^2: a vertex touching a face still has some stiffness.
  static double areaFloor(const Contact& c) { return 1e-6 * std::min(c.refR1, c.refR2) * std::min(c.refR1, c.refR2); }
  static bool isBoundary(const Bodies& b, std::size_t i)
  {
    return b.shape[i] == ShapeKind::PotentialBlock && block(b, i).isBoundary;
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
