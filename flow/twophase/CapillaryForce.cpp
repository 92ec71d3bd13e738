#include "flow/twophase/CapillaryForce.h"

#include <cmath>
#include <numbers>

namespace talus::flow::twophase
{
using pore::Vec3;

namespace
{
/// The arc of sphere `s` between the directions of `a` and `b` from its centre.
double arc(const pore::Vertex& s, const Vec3& a, const Vec3& b)
{
  const Vec3 u = a - s.pos, v = b - s.pos;
  return std::acos(u.dot(v) / std::sqrt(u.squaredNorm() * v.squaredNorm())) * s.radius;
}
} // namespace

std::vector<std::array<double, 3>> solidLineShares(const pore::PoreNetwork& net)
{
  std::vector<std::array<double, 3>> shares(net.throats.size(), {0.0, 0.0, 0.0});
  for (std::size_t t = 0; t < net.throats.size(); ++t)
  {
    std::array<const pore::Vertex*, 3> v{};
    std::array<std::size_t, 3> real{}, walls{};
    std::size_t nReal = 0, nWalls = 0;
    for (std::size_t y = 0; y < 3; ++y)
    {
      v[y] = &net.vertices[static_cast<std::size_t>(net.throats[t].vertices[y])];
      (v[y]->fictitious ? walls[nWalls++] : real[nReal++]) = y;
    }
    std::array<double, 3>& line = shares[t];
    if (nWalls == 0)
      for (std::size_t y = 0; y < 3; ++y)
        line[y] = arc(*v[y], v[(y + 1) % 3]->pos, v[(y + 2) % 3]->pos);
    else if (nWalls == 1)
    {
      // the two spheres' arcs towards each other and the wall's (far) centre; the wall's line
      // is the trace of the facet on it: the distance between the spheres projected on the wall
      const std::size_t a = real[0], b = real[1], w = walls[0];
      line[a] = arc(*v[a], v[b]->pos, v[w]->pos);
      line[b] = arc(*v[b], v[a]->pos, v[w]->pos);
      Vec3 d = v[a]->pos - v[b]->pos;
      d[net.boundaries[static_cast<std::size_t>(v[w]->id)].coordinate] = 0;
      line[w] = d.norm();
    }
    else if (nWalls == 2)
    {
      // a sphere in the corner of two walls: a quarter circle, and on each wall the distance
      // from the sphere's centre to the other wall
      const pore::Vertex& s = *v[real[0]];
      line[real[0]] = 0.5 * std::numbers::pi * s.radius;
      for (std::size_t k = 0; k < 2; ++k)
      {
        const pore::Boundary& other = net.boundaries[static_cast<std::size_t>(v[walls[1 - k]]->id)];
        line[walls[k]] = std::abs(other.position - s.pos[other.coordinate]);
      }
    }
    const double total = line[0] + line[1] + line[2];
    for (double& l : line)
      l = total > 0 ? l / total : 0.0;
  }
  return shares;
}

} // namespace talus::flow::twophase
