// Clumps: rigid aggregates of bodies (Yade's Clump), created by Scene::addClump and changed by
// addToClump, releaseFromClump and erase.
#include "dem/core/Clump.h"

#include "dem/core/Scene.h"

#include <Eigen/Eigenvalues>

#include <algorithm>
#include <cmath>
#include <numbers>
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

bool isSphere(const Bodies& b, BodyId id)
{
  return b.shape[static_cast<std::size_t>(id)] == ShapeKind::Sphere;
}

/// Members taken whole, overlaps counted twice (Yade without discretization): a sphere weighs
/// its material's density times its volume (not its state.mass, as in Yade), any other member
/// its own mass and principal inertia, turned to world axes.
MassMoments sumOfMembers(const Bodies& b, const std::vector<BodyId>& members, const std::deque<Material>& materials)
{
  MassMoments s;
  for (BodyId id : members)
  {
    const auto i = static_cast<std::size_t>(id);
    double m = b.mass[i];
    Mat3 I;
    if (isSphere(b, id))
    {
      // Yade's order of operations, for its bits.
      const double r = b.radius[i];
      m = materials[static_cast<std::size_t>(b.material[i])].density * ((4.0 / 3.0) * std::numbers::pi * std::pow(r, 3));
      I = Mat3(Vec3::Constant((2 / 5.0) * m * std::pow(r, 2)).asDiagonal());
    }
    else
    {
      const Mat3 R = b.ori[i].toRotationMatrix();
      I = R * b.inertia[i].asDiagonal() * R.transpose();
    }
    s.mass += m;
    s.first += m * b.pos[i];
    s.inertia += translated(I, m, -b.pos[i]);
  }
  return s;
}

/// The union of the sphere members integrated on a regular grid of cubes whose edge is the
/// shortest side of their bounding box divided by `discretization`, each cube counted once with
/// the density of the first member containing its centre (Yade's discretization > 0; members
/// that are not spheres are left out, as in Yade).
MassMoments gridIntegral(const Bodies& b, const std::vector<BodyId>& members, const std::deque<Material>& materials,
                         int discretization)
{
  Vec3 lo = Vec3::Constant(INFINITY), hi = -lo;
  for (BodyId id : members)
    if (isSphere(b, id))
    {
      const auto i = static_cast<std::size_t>(id);
      lo = lo.cwiseMin(b.pos[i] - Vec3::Constant(b.radius[i]));
      hi = hi.cwiseMax(b.pos[i] + Vec3::Constant(b.radius[i]));
    }
  const double dx = (hi - lo).minCoeff() / discretization;
  const double dv = dx * dx * dx;
  MassMoments s;
  Vec3 x;
  for (x[0] = lo[0] + dx / 2; x[0] < hi[0]; x[0] += dx)
    for (x[1] = lo[1] + dx / 2; x[1] < hi[1]; x[1] += dx)
      for (x[2] = lo[2] + dx / 2; x[2] < hi[2]; x[2] += dx)
        for (BodyId id : members)
        {
          const auto i = static_cast<std::size_t>(id);
          if (isSphere(b, id) && (x - b.pos[i]).squaredNorm() < b.radius[i] * b.radius[i])
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

/// Whether two sphere members overlap by more than a thousandth of the smaller radius (Yade's
/// test for integrating on a grid).
bool membersOverlap(const Bodies& b, const std::vector<BodyId>& members)
{
  for (std::size_t p = 0; p < members.size(); ++p)
    for (std::size_t q = p + 1; q < members.size(); ++q)
    {
      if (!isSphere(b, members[p]) || !isSphere(b, members[q]))
        continue;
      const auto i = static_cast<std::size_t>(members[p]), j = static_cast<std::size_t>(members[q]);
      if (b.radius[i] + b.radius[j] - (b.pos[i] - b.pos[j]).norm() > 0.001 * std::min(b.radius[i], b.radius[j]))
        return true;
    }
  return false;
}

/// Take member `id` out of `clump`'s lists (its placement goes with it); the clump's mass
/// properties are left as they are (Yade's Clump::del).
void removeMember(Bodies& b, ClumpShape& clump, BodyId id)
{
  const auto k = static_cast<std::size_t>(std::find(clump.members.begin(), clump.members.end(), id) - clump.members.begin());
  clump.members.erase(clump.members.begin() + static_cast<std::ptrdiff_t>(k));
  if (k < clump.relPos.size())
  {
    clump.relPos.erase(clump.relPos.begin() + static_cast<std::ptrdiff_t>(k));
    clump.relOri.erase(clump.relOri.begin() + static_cast<std::ptrdiff_t>(k));
  }
  b.clumpId[static_cast<std::size_t>(id)] = -1;
}
} // namespace

ClumpShape& Scene::clumpShape(BodyId clump)
{
  checkBody(clump);
  const auto c = static_cast<std::size_t>(clump);
  if (bodies.shape[c] != ShapeKind::Clump)
    throw std::invalid_argument("body " + std::to_string(clump) + " is not a clump");
  return bodies.clumps[static_cast<std::size_t>(bodies.shapeIndex[c])];
}

void Scene::checkClumpable(const std::string& which, BodyId id) const
{
  checkBody(id);
  const ShapeKind kind = bodies.shape[static_cast<std::size_t>(id)];
  // The shapes whose contacts follow the body's position and orientation.
  if (kind != ShapeKind::Sphere && kind != ShapeKind::Facet && kind != ShapeKind::Box)
    throw std::invalid_argument(which + ": body " + std::to_string(id) + " is a " + shapeName(kind)
                                + "; clump members must be spheres, facets or boxes");
}

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
    checkClumpable(which, id);
  // A member of another clump leaves it (Yade's clump()), which keeps its mass properties;
  // a clump left without members goes.
  for (BodyId id : members)
  {
    const BodyId old = bodies.clumpId[static_cast<std::size_t>(id)];
    if (old < 0)
      continue;
    ClumpShape& oldShape = clumpShape(old);
    removeMember(bodies, oldShape, id);
    if (oldShape.members.empty())
      erase(old);
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

void Scene::addToClump(BodyId clump, const std::vector<BodyId>& ids, int discretization)
{
  const std::string which = "addToClump: clump " + std::to_string(clump);
  if (discretization < 0)
    throw std::invalid_argument(which + ": discretization must be >= 0, got " + std::to_string(discretization));
  ClumpShape& shape = clumpShape(clump);
  std::vector<BodyId> absorbed; // the clumps whose members join
  std::vector<BodyId> joining;
  for (BodyId id : ids)
  {
    checkBody(id);
    const auto i = static_cast<std::size_t>(id);
    if (id == clump || bodies.clumpId[i] == clump)
      throw std::invalid_argument(which + ": body " + std::to_string(id) + " is already part of it");
    // A clump joins with all its members, and so does the clump of a member (Yade's addToClump).
    const BodyId other = bodies.shape[i] == ShapeKind::Clump ? id : bodies.clumpId[i];
    if (other >= 0)
    {
      if (std::find(absorbed.begin(), absorbed.end(), other) == absorbed.end())
        absorbed.push_back(other);
    }
    else
    {
      checkClumpable(which, id);
      if (std::find(joining.begin(), joining.end(), id) == joining.end())
        joining.push_back(id);
    }
  }
  for (BodyId other : absorbed)
  {
    ClumpShape& otherShape = clumpShape(other);
    joining.insert(joining.end(), otherShape.members.begin(), otherShape.members.end());
    otherShape.members.clear();
    otherShape.relPos.clear();
    otherShape.relOri.clear();
  }
  for (BodyId id : joining)
  {
    bodies.clumpId[static_cast<std::size_t>(id)] = clump;
    shape.members.push_back(id);
  }
  std::sort(shape.members.begin(), shape.members.end());
  updateClump(clump, discretization);
  for (BodyId other : absorbed)
    erase(other);
  ++bodiesVersion;
}

void Scene::releaseFromClump(BodyId member, BodyId clump, int discretization)
{
  const std::string which = "releaseFromClump: body " + std::to_string(member);
  if (discretization < 0)
    throw std::invalid_argument(which + ": discretization must be >= 0, got " + std::to_string(discretization));
  ClumpShape& shape = clumpShape(clump);
  checkBody(member);
  if (bodies.clumpId[static_cast<std::size_t>(member)] != clump)
    throw std::invalid_argument(which + " is not a member of clump " + std::to_string(clump));
  if (shape.members.size() <= 2)
    throw std::invalid_argument(which + ": clump " + std::to_string(clump)
                                + " would be left with fewer than 2 members (erase the clump instead)");
  removeMember(bodies, shape, member);
  updateClump(clump, discretization);
  ++bodiesVersion;
}

void Scene::eraseClumpMember(BodyId member)
{
  const BodyId clump = bodies.clumpId[static_cast<std::size_t>(member)];
  ClumpShape& shape = clumpShape(clump);
  removeMember(bodies, shape, member);
  if (shape.members.empty())
    erase(clump);
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
                                                                           : sumOfMembers(b, members, materials);
    if (!(s.mass > 0))
      throw std::invalid_argument("clump " + std::to_string(id) + ": its members have no mass (mass "
                                  + std::to_string(s.mass) + "); give them a density or a mass");
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
  // The clump at rest, as Yade's Clump::updateProperties; the members stay where they are (the
  // first step places them from relPos, to the same point up to rounding).
  b.vel[c].setZero();
  b.angVel[c].setZero();
  b.angMom[c].setZero();
  ++bodyPropertiesVersion;
}
} // namespace talus::dem
