// Clumps: rigid aggregates of spheres (Yade's Clump), created by Scene::addClump.
#include "dem/Clump.h"

#include "dem/Scene.h"

#include <Eigen/Eigenvalues>

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace talus::dem
{
namespace
{
/// Inertia tensor I (about some point) moved by `offset` for a body of mass m: parallel axes
/// (m < 0 moves towards the centroid), as Yade's Clump::inertiaTensorTranslate.
Mat3 translated(const Mat3& I, double m, const Vec3& offset)
{
  return I + m * (offset.dot(offset) * Mat3::Identity() - offset * offset.transpose());
}

/// Mass, first moment and inertia tensor about the origin (world axes) of the members.
struct MassMoments
{
  double mass = 0;
  Vec3 first = Vec3::Zero();
  Mat3 inertia = Mat3::Zero();
};

/// Members taken as whole spheres (overlaps counted twice), as Yade without discretization.
MassMoments sumOfSpheres(const Bodies& b, const std::vector<BodyId>& members)
{
  MassMoments s;
  for (BodyId id : members)
  {
    const auto i = static_cast<std::size_t>(id);
    s.mass += b.mass[i];
    s.first += b.mass[i] * b.pos[i];
    s.inertia += translated(Mat3(b.inertia[i].asDiagonal()), b.mass[i], -b.pos[i]);
  }
  return s;
}

/// The union of the member spheres integrated on a regular grid of cubes of edge
/// rmin / discretization (at most 150 along the longest side), each cube counted once with
/// the density of the first member containing its centre (Yade's discretization > 0).
MassMoments gridIntegral(const Bodies& b, const std::vector<BodyId>& members, const std::deque<Material>& materials,
                         int discretization)
{
  Vec3 lo = Vec3::Constant(INFINITY), hi = -lo;
  double rmin = INFINITY;
  for (BodyId id : members)
  {
    const auto i = static_cast<std::size_t>(id);
    lo = lo.cwiseMin(b.pos[i] - Vec3::Constant(b.radius[i]));
    hi = hi.cwiseMax(b.pos[i] + Vec3::Constant(b.radius[i]));
    rmin = std::min(rmin, b.radius[i]);
  }
  double dx = rmin / discretization;
  dx = std::max(dx, (hi - lo).maxCoeff() / 150);
  const double dv = dx * dx * dx;
  MassMoments s;
  Vec3 x;
  for (x[0] = lo[0] + dx / 2; x[0] < hi[0]; x[0] += dx)
    for (x[1] = lo[1] + dx / 2; x[1] < hi[1]; x[1] += dx)
      for (x[2] = lo[2] + dx / 2; x[2] < hi[2]; x[2] += dx)
        for (BodyId id : members)
        {
          const auto i = static_cast<std::size_t>(id);
          if ((x - b.pos[i]).squaredNorm() < b.radius[i] * b.radius[i])
          {
            const double dm = materials[static_cast<std::size_t>(b.material[i])].density * dv;
            s.mass += dm;
            s.first += dm * x;
            s.inertia += dm * (x.dot(x) * Mat3::Identity() - x * x.transpose()) + Mat3::Identity() * (dm * dx * dx / 6);
            break;
          }
        }
  return s;
}

bool membersOverlap(const Bodies& b, const std::vector<BodyId>& members)
{
  for (std::size_t p = 0; p < members.size(); ++p)
    for (std::size_t q = p + 1; q < members.size(); ++q)
    {
      const auto i = static_cast<std::size_t>(members[p]), j = static_cast<std::size_t>(members[q]);
      if (b.radius[i] + b.radius[j] - (b.pos[i] - b.pos[j]).norm() > -0.001 * std::min(b.radius[i], b.radius[j]))
        return true;
    }
  return false;
}
} // namespace

BodyId Scene::addClump(std::vector<BodyId> members, int discretization)
{
  const std::string which = "clump #" + std::to_string(bodies.size());
  if (members.empty())
    throw std::invalid_argument(which + ": needs at least one member");
  if (discretization < 0)
    throw std::invalid_argument(which + ": discretization must be >= 0, got " + std::to_string(discretization));
  std::sort(members.begin(), members.end());
  if (std::adjacent_find(members.begin(), members.end()) != members.end())
    throw std::invalid_argument(which + ": a body is listed twice");
  for (BodyId id : members)
  {
    checkBody(id);
    const auto i = static_cast<std::size_t>(id);
    if (bodies.shape[i] != ShapeKind::Sphere)
      throw std::invalid_argument(which + ": body " + std::to_string(id) + " is not a sphere (clumps are made of spheres)");
    if (bodies.clumpId[i] >= 0)
      throw std::invalid_argument(which + ": body " + std::to_string(id) + " is already a member of clump "
                                  + std::to_string(bodies.clumpId[i]));
  }

  ClumpShape shape;
  shape.members = std::move(members);
  bodies.clumps.push_back(std::move(shape));
  const BodyId id = bodies.append(ShapeKind::Clump, static_cast<int>(bodies.clumps.size()) - 1,
                                  bodies.material[static_cast<std::size_t>(bodies.clumps.back().members[0])]);
  for (BodyId m : bodies.clumps.back().members)
    bodies.clumpId[static_cast<std::size_t>(m)] = id;
  updateClump(id, discretization);
  ++bodiesVersion;
  return id;
}

void Scene::updateClump(BodyId id, int discretization)
{
  Bodies& b = bodies;
  const auto c = static_cast<std::size_t>(id);
  ClumpShape& shape = b.clumps[static_cast<std::size_t>(b.shapeIndex[c])];
  const std::vector<BodyId>& members = shape.members;
  if (members.size() == 1)
  {
    // The clump is its member (Yade's special case).
    const auto m = static_cast<std::size_t>(members[0]);
    b.pos[c] = b.pos[m];
    b.ori[c] = b.ori[m];
    b.mass[c] = b.mass[m];
    b.inertia[c] = b.inertia[m];
  }
  else
  {
    const MassMoments s = discretization > 0 && membersOverlap(b, members) ? gridIntegral(b, members, materials, discretization)
                                                                           : sumOfSpheres(b, members);
    b.pos[c] = s.first / s.mass;
    Mat3 I = translated(s.inertia, -s.mass, b.pos[c]); // about the centroid, world axes
    I = 0.5 * (I + I.transpose());
    const Eigen::SelfAdjointEigenSolver<Mat3> principal(I);
    // Principal axes as a proper rotation (eigenvectors may come as a reflection).
    Mat3 axes = principal.eigenvectors();
    if (axes.determinant() < 0)
      axes.col(2) *= -1;
    b.ori[c] = Quat(axes).normalized();
    b.mass[c] = s.mass;
    b.inertia[c] = principal.eigenvalues();
  }
  shape.relPos.clear();
  shape.relOri.clear();
  for (BodyId mid : members)
  {
    const auto m = static_cast<std::size_t>(mid);
    shape.relPos.push_back(b.ori[c].conjugate() * (b.pos[m] - b.pos[c]));
    shape.relOri.push_back(b.ori[c].conjugate() * b.ori[m]);
  }
  // Members at rest with the clump, as Yade's Clump::updateProperties.
  b.vel[c].setZero();
  b.angVel[c].setZero();
  b.angMom[c].setZero();
  moveClumpMembers(b, c);
  ++bodyPropertiesVersion;
}
} // namespace talus::dem
