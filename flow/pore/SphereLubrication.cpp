#include "flow/pore/SphereLubrication.h"

#include <Eigen/Geometry> // cross products

#include <algorithm>
#include <cmath>
#include <map>
#include <numbers>
#include <stdexcept>
#include <string>

namespace talus::flow::pore
{
namespace
{
/// Area of the power-diagram face dual to edge (a, b): the polygon of the centres of the pores
/// around the edge, visited by crossing from pore to pore through the facets that contain the
/// edge, summed as a fan of triangles from the first centre (Yade's computeVFacetArea). 0 if the
/// ring meets the outside of the triangulation (not for two real spheres: the boundary spheres
/// enclose them).
double dualFaceArea(const PoreNetwork& net, int start, int a, int b)
{
  std::vector<Vec3> ring;
  int previous = -1;
  int current = start;
  do
  {
    const Pore& p = net.pores[static_cast<std::size_t>(current)];
    ring.push_back(p.centre);
    // the two facets of this pore that contain the edge are those opposite its other two
    // vertices; leave through the one that does not lead back
    int next = -1;
    for (int k = 0; k < 4; ++k)
    {
      const int v = p.vertices[static_cast<std::size_t>(k)];
      const int across = p.neighbours[static_cast<std::size_t>(k)];
      if (v != a && v != b && across != previous)
        next = across;
    }
    if (next < 0 || ring.size() > net.pores.size())
      return 0.0;
    previous = current;
    current = next;
  } while (current != start);
  double area = 0;
  for (std::size_t k = 1; k + 1 < ring.size(); ++k)
    area += 0.5 * (ring[k] - ring[0]).cross(ring[k + 1] - ring[0]).norm();
  return area;
}
} // namespace

void SphereLubrication::setNetwork(const PoreNetwork& net)
{
  if (net.periodic)
    throw std::invalid_argument("FlowEngine: viscousShear, shearLubrication and normalLubrication are not "
                                "supported by PeriodicFlowEngine");
  // the springs' loads of the previous network, by the pair's body ids
  std::map<std::array<std::int64_t, 2>, double> load;
  for (std::size_t k = 0; k < pairs_.size(); ++k)
    if (pairs_[k].normalForce != 0)
      load[pairIds_[k]] = pairs_[k].normalForce;
  // every edge between two spheres (vertex a < b) with a pore containing it, each edge once
  std::vector<std::array<int, 3>> edges;
  edges.reserve(6 * net.pores.size());
  for (std::size_t i = 0; i < net.pores.size(); ++i)
  {
    const Pore& p = net.pores[i];
    for (int j = 0; j < 4; ++j)
      for (int k = j + 1; k < 4; ++k)
      {
        const auto [u, v] = std::minmax(p.vertices[static_cast<std::size_t>(j)], p.vertices[static_cast<std::size_t>(k)]);
        if (!net.vertices[static_cast<std::size_t>(u)].fictitious && !net.vertices[static_cast<std::size_t>(v)].fictitious)
          edges.push_back({u, v, static_cast<int>(i)});
      }
  }
  std::sort(edges.begin(), edges.end());
  edges.erase(std::unique(edges.begin(), edges.end(), [](const auto& x, const auto& y) { return x[0] == y[0] && x[1] == y[1]; }),
              edges.end());
  pairs_.clear();
  pairIds_.clear();
  pairs_.reserve(edges.size());
  pairIds_.reserve(edges.size());
  for (const auto& [a, b, pore] : edges)
  {
    const auto [low, high] = std::minmax(net.vertices[static_cast<std::size_t>(a)].id, net.vertices[static_cast<std::size_t>(b)].id);
    const std::array<std::int64_t, 2> ids{low, high};
    const auto carried = load.find(ids);
    pairs_.push_back(SpherePair{a, b, dualFaceArea(net, pore, a, b), carried == load.end() ? 0.0 : carried->second});
    pairIds_.push_back(ids);
  }
}

void SphereLubrication::compute(const PoreNetwork& net, const ViscousParameters& params, double viscosity,
                                const std::vector<Vec3>& velocities, const std::vector<Vec3>& angularVelocities,
                                double dt)
{
  const std::size_t n = net.sphereCount();
  if (velocities.size() != n || angularVelocities.size() != n)
    throw std::invalid_argument("FlowEngine: " + std::to_string(velocities.size()) + " velocities and " +
                                std::to_string(angularVelocities.size()) + " angular velocities for " +
                                std::to_string(n) + " spheres of the pore network");
  for (std::size_t i = 0; i < n; ++i)
    if (!velocities[i].allFinite() || !angularVelocities[i].allFinite())
      throw std::invalid_argument("FlowEngine: non-finite velocity of body " + std::to_string(net.vertices[kBoundaries + i].id));
  const bool spring = params.normalLubrication && params.stiffness > 0;
  if (spring && !(dt > 0))
    throw std::invalid_argument("FlowEngine.normalLubrication with stiffness > 0 needs a time step > 0, got " +
                                std::to_string(dt));
  shearForce_.assign(n, Vec3::Zero());
  shearTorque_.assign(n, Vec3::Zero());
  normalForce_.assign(n, Vec3::Zero());
  constexpr double pi = std::numbers::pi;
  for (SpherePair& pair : pairs_)
  {
    const Vertex& s1 = net.vertices[static_cast<std::size_t>(pair.a)];
    const Vertex& s2 = net.vertices[static_cast<std::size_t>(pair.b)];
    const auto i1 = static_cast<std::size_t>(pair.a - kBoundaries);
    const auto i2 = static_cast<std::size_t>(pair.b - kBoundaries);
    const double r1 = s1.radius;
    const double r2 = s2.radius;
    const Vec3 branch = s2.pos - s1.pos;
    const double distance = branch.norm();
    const Vec3 normal = branch / distance;
    const double gap = distance - r1 - r2;
    const double meanRadius = (r1 + r2) / 2;
    // the torques act at the radical plane of the two spheres, as Yade's
    const Vec3 toPlane1 = (distance / 2 + (r1 * r1 - r2 * r2) / (2 * distance)) * normal;
    const Vec3 toPlane2 = toPlane1 - branch;
    // relative velocity of the two surfaces facing each other
    const Vec3 dv = (velocities[i2] + angularVelocities[i2].cross(-r2 * normal)) -
                    (velocities[i1] + angularVelocities[i1].cross(r1 * normal));
    const Vec3 dvShear = dv - normal.dot(dv) * normal;
    // the lubrication gap never closes below the roughness
    const double film = std::max(gap, 0.0) + 2 * params.eps * meanRadius;
    Vec3 shear = Vec3::Zero();
    if (params.shearLubrication)
      shear = 0.5 * pi * viscosity * (-2 * meanRadius + distance * std::log(distance / film)) * dvShear;
    else if (params.viscousShear)
      shear = viscosity * dvShear / (gap + 0.45 * std::min(r1, r2)) * pair.faceArea;
    shearForce_[i1] += shear;
    shearForce_[i2] -= shear;
    shearTorque_[i1] += toPlane1.cross(shear);
    shearTorque_[i2] += toPlane2.cross(-shear);
    if (!params.normalLubrication)
      continue;
    const double dvNormal = normal.dot(dv);
    const double damping = 1.5 * pi * meanRadius * meanRadius * viscosity;
    double force = damping * dvNormal / film;
    if (spring)
    {
      // the dashpot of the film in series with the spring of the asperities (implicit over dt):
      // the film is thinner by the spring's compression under the last force
      const double k = params.stiffness * meanRadius;
      const double dashpot = damping / (film - pair.normalForce / k);
      force = dashpot * (dvNormal + pair.normalForce / (k * dt)) / (1 + dashpot / (k * dt));
      pair.normalForce = force;
    }
    normalForce_[i1] += force * normal;
    normalForce_[i2] -= force * normal;
  }
}
} // namespace talus::flow::pore
