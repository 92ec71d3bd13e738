#include "dem/measure/Measurements.h"

#include "dem/core/Clump.h"
#include "dem/engines/NewtonIntegrator.h"
#include "dem/core/Scene.h"

#include <array>
#include <cmath>
#include <limits>
#include <span>
#include <stdexcept>
#include <string>

namespace talus::dem
{
bool countsInSums(const Scene& scene, const Contact& c)
{
  return c.real && countsContact(scene.domain.get(), static_cast<std::size_t>(c.id1), static_cast<std::size_t>(c.id2));
}

double unbalancedForce(const Scene& scene, const Vec3& gravity, bool useMaxForce)
{
  const Bodies& b = scene.bodies;
  const Domain* domain = scene.domain.get();
  // The bodies' force magnitudes and count, the contacts' force magnitudes and count, each body
  // and contact counted by one process and summed exactly: split over processes, the same bits
  // as in one (the periodic cell's controllers compare it with their threshold on every process).
  std::array<ExactSum, 4> sums;
  double maxBody = 0;
  for (std::size_t i = 0; i < b.size(); ++i)
  {
    // A clump counts once, with its members' forces; its members do not count alone.
    if (!b.alive[i] || !b.dynamic[i] || b.clumpId[i] >= 0 || !countsBody(domain, i))
      continue;
    Vec3 force = b.force[i], torque = Vec3::Zero();
    if (b.shape[i] == ShapeKind::Clump)
      addClumpMemberForces(b, i, force, torque);
    const double f = (force + b.mass[i] * gravity).norm();
    sums[0] += f;
    maxBody = std::max(maxBody, f);
    sums[1] += 1;
  }
  for (const Contact& c : scene.contacts.list)
    if (countsInSums(scene, c))
    {
      sums[2] += c.force.norm();
      sums[3] += 1;
    }
  sumExactly(domain, sums);
  if (domain)
    maxBody = -domain->min(-maxBody);
  const double sumBodies = sums[0].value(), bodies = sums[1].value(), sumContacts = sums[2].value(),
               contacts = sums[3].value();
  if (contacts == 0 || sumContacts == 0 || bodies == 0)
    return std::numeric_limits<double>::quiet_NaN();
  const double meanContact = sumContacts / contacts;
  return (useMaxForce ? maxBody : sumBodies / bodies) / meanContact;
}

namespace
{
/// Split over processes, `values` summed over them in place (each process's share of a sum over
/// bodies or contacts, Domain::countsBody, countsContact); nothing when the scene is whole.
void sumOverProcesses(const Scene& scene, std::span<double> values)
{
  if (scene.domain)
    scene.domain->sum(values);
}

double sampleVolume(const Scene& scene, double volume, const char* caller)
{
  if (volume > 0)
    return volume;
  if (!scene.periodic)
    throw std::invalid_argument(std::string(caller) + ": give the volume of the sample (the scene is not periodic)");
  return scene.cell.volume();
}

/// From body 1's centre to body 2's image, with the cell as it is now (not as the geometry saw
/// it at the step's start, before the integrator moved the bodies and the cell). A wall or
/// facet has no centre: its branch vector is the sphere's distance to it along the normal, so
/// that in equilibrium the stress of a walled sample equals wall force over area.
Vec3 branchVector(const Scene& scene, const Contact& c)
{
  const Bodies& b = scene.bodies;
  const auto i2 = static_cast<std::size_t>(c.id2);
  if (c.kind != ContactGeometryKind::SphereSphere)
    return c.normal * (b.radius[i2] - c.penetration);
  const Vec3 shift = scene.periodic ? scene.cell.shift(c.cellDist) : Vec3::Zero();
  return b.pos[i2] + shift - b.pos[static_cast<std::size_t>(c.id1)];
}
} // namespace

void addContactForce(const Scene& scene, std::size_t row, std::span<ExactSum, 3> force, ExactSum* stiffness)
{
  const Contacts& contacts = scene.contacts;
  if (row >= static_cast<std::size_t>(contacts.indexedBodies())) // no contact index yet (before the first detection)
    return;
  for (std::int64_t e = contacts.start[row]; e < contacts.start[row + 1]; ++e)
  {
    const std::int64_t entry = contacts.entries[static_cast<std::size_t>(e)];
    const Contact& c = contacts.list[static_cast<std::size_t>(entry >> 1)];
    if (!c.real)
      continue;
    const double sense = (entry & 1) ? 1.0 : -1.0; // the contact's force acts on its second body
    for (std::size_t d = 0; d < 3; ++d)
      force[d] += sense * c.force[static_cast<Eigen::Index>(d)];
    if (stiffness && c.normalForce.norm() != 0)
      *stiffness += c.kn;
  }
}

std::pair<Vec3, double> totalForceInVolume(const Scene& scene)
{
  // the force's absolute components, the stiffness, the contacts: this process's shares, summed
  // exactly (PeriIsoCompressor moves the cell by them: the same bits at any process count)
  std::array<ExactSum, 5> sums;
  for (const Contact& c : scene.contacts.list)
  {
    if (!countsInSums(scene, c))
      continue;
    const Vec3 f = c.normalForce + c.shearForce;
    for (std::size_t d = 0; d < 3; ++d)
      sums[d] += std::abs(f[static_cast<Eigen::Index>(d)]);
    sums[3] += c.kn / 3 + 2 * c.ks / 3;
    sums[4] += 1;
  }
  sumExactly(scene.domain.get(), sums);
  const double contacts = sums[4].value();
  return {Vec3(sums[0].value(), sums[1].value(), sums[2].value()), contacts > 0 ? sums[3].value() / contacts : -1.0};
}

Vec3 sceneGravity(const Scene& scene)
{
  for (const auto& e : scene.engines)
    if (const auto* newton = dynamic_cast<const NewtonIntegrator*>(e.get()))
      return newton->gravity;
  return Vec3::Zero();
}

Mat3 loveWeberStress(const Scene& scene, double volume)
{
  volume = sampleVolume(scene, volume, "getStress");
  // The contacts of one sphere as their first body (a run of the list, which is sorted by bodies)
  // are summed in order, and the runs exactly (ExactSum): split over processes, each such run lies
  // whole, in the same order, on the process owning its first sphere, so the stress is the same
  // bits at any process count (the periodic cell's controllers read it). A wall's or facet's
  // contacts, spread over the processes of their spheres, are added exactly one by one.
  std::array<ExactSum, 9> total;
  Mat3 run = Mat3::Zero();
  BodyId first = -1;
  auto flush = [&] {
    for (std::size_t k = 0; k < 9; ++k)
      total[k] += run.data()[k];
    run.setZero();
  };
  for (const Contact& c : scene.contacts.list)
  {
    if (!countsInSums(scene, c))
      continue;
    if (c.id1 != first || c.kind != ContactGeometryKind::SphereSphere)
    {
      flush();
      first = c.id1;
    }
    run += c.force * branchVector(scene, c).transpose();
  }
  flush();
  sumExactly(scene.domain.get(), total);
  Mat3 sum;
  for (std::size_t k = 0; k < 9; ++k)
    sum.data()[k] = total[k].value();
  return -sum / volume;
}

namespace
{
/// sym(u (x) l) in Voigt form (xx, yy, zz, yz, xz, xy).
Eigen::Matrix<double, 6, 1> symmetricVoigt(const Vec3& u, const Vec3& l)
{
  Eigen::Matrix<double, 6, 1> a;
  a << u[0] * l[0], u[1] * l[1], u[2] * l[2], 0.5 * (u[1] * l[2] + u[2] * l[1]), 0.5 * (u[0] * l[2] + u[2] * l[0]),
      0.5 * (u[0] * l[1] + u[1] * l[0]);
  return a;
}

Eigen::Matrix<double, 6, 6> yadeTangent(const Scene& scene)
{
  Eigen::Matrix<double, 6, 6> tangent = Eigen::Matrix<double, 6, 6>::Zero();
  for (const Contact& c : scene.contacts.list)
  {
    if (!countsInSums(scene, c))
      continue;
    const Vec3 l = branchVector(scene, c);
    const Eigen::Matrix<double, 6, 1> a = symmetricVoigt(c.normal, l);
    tangent += c.kn * a * a.transpose();
    const double shear = c.shearForce.norm();
    if (shear > 0)
    {
      const Eigen::Matrix<double, 6, 1> b = symmetricVoigt(c.shearForce / shear, l);
      tangent += c.ks * b * b.transpose();
    }
  }
  sumOverProcesses(scene, std::span<double>(tangent.data(), 36));
  return tangent;
}
} // namespace

Eigen::Matrix<double, 6, 6> contactStiffnessTangent(const Scene& scene, double volume, TangentForm form)
{
  volume = sampleVolume(scene, volume, "getStressAndTangent");
  if (form == TangentForm::Yade)
    return yadeTangent(scene) / volume;
  // D as a 9x9 matrix on (ij),(kl) pairs: D(3i+j, 3k+l) = sum K_ik l_j l_l, i.e. a sum of
  // Kronecker products K (x) (l l^T) in a row-major pair numbering.
  Eigen::Matrix<double, 9, 9> d = Eigen::Matrix<double, 9, 9>::Zero();
  for (const Contact& c : scene.contacts.list)
  {
    if (!countsInSums(scene, c))
      continue;
    const Vec3 l = branchVector(scene, c);
    const Mat3 nn = c.normal * c.normal.transpose();
    // Between spheres the shear increment scales the relative translation by
    // alpha = (r1 + r2) / |l| (Yade's avoidGranularRatcheting, ContactGeometry.h): so does the
    // shear stiffness seen by an affine strain.
    const double alpha = c.kind == ContactGeometryKind::SphereSphere ? (c.refR1 + c.refR2) / l.norm() : 1.0;
    const Mat3 k = c.kn * nn + alpha * c.ks * (Mat3::Identity() - nn);
    const Mat3 ll = l * l.transpose();
    for (int i = 0; i < 3; ++i)
      for (int kk = 0; kk < 3; ++kk)
        d.block<3, 3>(3 * i, 3 * kk) += k(i, kk) * ll;
  }
  sumOverProcesses(scene, std::span<double>(d.data(), 81));
  static constexpr int voigtI[6] = {0, 1, 2, 1, 0, 0};
  static constexpr int voigtJ[6] = {0, 1, 2, 2, 2, 1};
  Eigen::Matrix<double, 6, 6> tangent;
  for (int a = 0; a < 6; ++a)
    for (int bb = 0; bb < 6; ++bb)
    {
      const int i = voigtI[a], j = voigtJ[a], k = voigtI[bb], l = voigtJ[bb];
      tangent(a, bb) = 0.25 * (d(3 * i + j, 3 * k + l) + d(3 * j + i, 3 * k + l) + d(3 * i + j, 3 * l + k) +
                               d(3 * j + i, 3 * l + k));
    }
  return tangent / volume;
}

double coordinationNumber(const Scene& scene, bool skipFree)
{
  const Bodies& b = scene.bodies;
  std::vector<int> count(b.size(), 0);
  for (const Contact& c : scene.contacts.list)
    if (c.real)
    {
      ++count[static_cast<std::size_t>(c.id1)];
      ++count[static_cast<std::size_t>(c.id2)];
    }
  // Split over processes, a process holds every contact of the bodies it owns.
  std::array<double, 2> sums{}; // contacts, spheres
  for (std::size_t i = 0; i < b.size(); ++i)
    if (b.alive[i] && b.shape[i] == ShapeKind::Sphere && (!skipFree || count[i] > 0) && countsBody(scene.domain.get(), i))
    {
      sums[0] += count[i];
      sums[1] += 1;
    }
  sumOverProcesses(scene, sums);
  return sums[1] > 0 ? sums[0] / sums[1] : 0.0;
}

Mat3 fabricTensor(const Scene& scene)
{
  std::array<double, 10> sums{}; // n (x) n, then the contacts
  Eigen::Map<Mat3> sum(sums.data());
  for (const Contact& c : scene.contacts.list)
    if (countsInSums(scene, c) && c.kind == ContactGeometryKind::SphereSphere)
    {
      sum += c.normal * c.normal.transpose();
      sums[9] += 1;
    }
  sumOverProcesses(scene, sums);
  return sums[9] > 0 ? Mat3(sum / sums[9]) : Mat3::Zero();
}

std::vector<Mat3> bodyStressTensors(const Scene& scene)
{
  const Bodies& b = scene.bodies;
  std::vector<Mat3> stress(b.size(), Mat3::Zero());
  auto add = [&](BodyId id, const Vec3& centre, const Contact& c, const Vec3& force) {
    const auto i = static_cast<std::size_t>(id);
    if (b.shape[i] == ShapeKind::Sphere)
      stress[i] += force * (c.contactPoint - centre).transpose() / (4.0 / 3.0 * M_PI * std::pow(b.radius[i], 3));
  };
  for (const Contact& c : scene.contacts.list)
  {
    if (!c.real)
      continue;
    const auto i1 = static_cast<std::size_t>(c.id1), i2 = static_cast<std::size_t>(c.id2);
    add(c.id1, b.pos[i1], c, -c.force);
    // body 2 meets body 1 through its image shifted by the contact's period
    add(c.id2, b.pos[i2] + (scene.periodic ? scene.cell.shift(c.cellDist) : Vec3::Zero()), c, c.force);
  }
  return stress;
}

double sphereVolume(const Scene& scene)
{
  const Bodies& b = scene.bodies;
  double v = 0;
  for (std::size_t i = 0; i < b.size(); ++i)
    if (b.alive[i] && b.shape[i] == ShapeKind::Sphere && countsBody(scene.domain.get(), i))
      v += 4.0 / 3.0 * M_PI * b.radius[i] * b.radius[i] * b.radius[i];
  sumOverProcesses(scene, std::span<double>(&v, 1));
  return v;
}
} // namespace talus::dem
