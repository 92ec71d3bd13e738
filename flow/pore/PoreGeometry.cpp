#include "flow/pore/PoreGeometry.h"

#include <Eigen/Geometry> // cross products

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace talus::flow::pore
{
namespace
{
constexpr double kThird = 1.0 / 3.0;
/// Yade's hydraulic-radius factors for throats touching one or two walls (symmetry images).
const double kMultSym1 = 1 / std::pow(2.0, 0.25);
const double kMultSym2 = 1 / std::pow(4.0, 0.25);
/// Yade's minimal throat length, relative to the throat diameter (coincident pore centres).
constexpr double kMinPermLength = 1e-6;

/// Area of the spherical triangle cut on sphere v by the cone (v; a, b, c).
double sphericalArea(const Vertex& v, const Vec3& a, const Vec3& b, const Vec3& c)
{
  return v.radius == 0 ? 0.0 : v.radius * v.radius * solidAngle(v.pos, a, b, c);
}

/// Volume of the sphere sector of v in the cone (v; a, b, c).
double sectorVolume(const Vertex& v, const Vec3& a, const Vec3& b, const Vec3& c)
{
  return kThird * v.radius * sphericalArea(v, a, b, c);
}

/// The spherical triangle of sphericalArea and the sector of sectorVolume together, from one
/// solid angle (the throat formulas need both of the same cone: the solid angles, an arctangent
/// each, are most of the geometry's cost).
struct Sector
{
  double area;
  double volume;
};
Sector sector(const Vertex& v, const Vec3& a, const Vec3& b, const Vec3& c)
{
  const double area = sphericalArea(v, a, b, c);
  return {area, kThird * v.radius * area};
}

/// The point p with its coordinate along boundary b moved onto the boundary plane.
Vec3 projected(const Vec3& p, const Boundary& b)
{
  Vec3 q = p;
  q[b.coordinate] = b.position;
  return q;
}

/// Area of the circular sector of a sphere in a facet (angle at the vertex times r^2 / 2).
double crossSection(const Vertex& v, const Vec3& a, const Vec3& b)
{
  if (v.fictitious)
    return 0;
  const Vec3 e1 = a - v.pos;
  const Vec3 e2 = b - v.pos;
  return 0.5 * v.radius * v.radius * std::acos(e1.dot(e2) / std::sqrt(e1.squaredNorm() * e2.squaredNorm()));
}

/// The part of sphere v0 beyond the edge (v1, v2) when the sphere crosses it (Yade's S0: added
/// back because the two sectors at v1 and v2 would count it twice... as Yade does).
double sphereEdgeOverlap(const Vertex& v0, const Vertex& v1, const Vertex& v2)
{
  const double dist = (v0.pos - v1.pos).dot(v2.pos - v1.pos);
  if (dist < 0)
    return 0;
  const double v1v2 = (v2.pos - v1.pos).squaredNorm();
  if (dist > v1v2)
    return 0;
  const double m = (v0.pos - v1.pos).cross(v2.pos - v1.pos).squaredNorm() / v1v2;
  const double w = v0.radius * v0.radius;
  if (m >= w)
    return 0;
  const double d = 2 * std::sqrt(w - m);
  const double theta = 2 * std::acos(std::sqrt(m / w));
  return 0.5 * (theta * w - d * std::sqrt(m));
}

/// Orient the facet vector s against p2 - p1 and return the double-pyramid volume |s.(p1-p2)|/3.
double bipyramidVolume(Vec3& s, const Vec3& p1, const Vec3& p2)
{
  if (s.dot(p2 - p1) > 0)
    s = -s;
  return kThird * std::abs(s.dot(p1 - p2));
}

/// Yade's cell volume: the tetrahedron, or for cells touching walls the part between the real
/// spheres and the wall planes (FlowEngine::volumeCell*Fictious).
double cellVolume(const PoreNetwork& net, const Pore& p)
{
  // fixed-size lists: this runs for every pore at every step (moveVertices)
  std::array<Vec3, 4> real;
  std::array<const Boundary*, 4> walls{};
  std::size_t nWalls = 0;
  std::size_t nReal = 0;
  for (int v : p.vertices)
  {
    const Vertex& vx = net.vertices[static_cast<std::size_t>(v)];
    if (vx.fictitious)
      walls[nWalls++] = &net.boundaries[static_cast<std::size_t>(vx.id)];
    else
      real[nReal++] = vx.pos;
  }
  switch (nWalls)
  {
  case 0:
  {
    const Vec3& p0 = real[0];
    return -(1.0 / 6.0) * (p0 - real[1]).cross(p0 - real[2]).dot(p0 - real[3]);
  }
  case 1:
  {
    const int c = walls[0]->coordinate;
    const double mean = kThird * (real[0][c] + real[1][c] + real[2][c]);
    return std::abs(0.5 * (real[0] - real[1]).cross(real[0] - real[2])[c] * (mean - walls[0]->position));
  }
  case 2:
  {
    const int c0 = walls[0]->coordinate;
    const int c1 = walls[1]->coordinate;
    const double w0 = walls[0]->position;
    const double w1 = walls[1]->position;
    const Vec3& a = real[0];
    const Vec3& b = real[1];
    Vec3 as = a;
    Vec3 bs = b;
    as[c0] = bs[c0] = w0;
    const double vol1 = 0.5 * (a - bs).cross(b - bs)[c1] * (kThird * (2 * b[c1] + a[c1]) - w1);
    const double vol2 = 0.5 * (as - bs).cross(a - bs)[c1] * (kThird * (b[c1] + 2 * a[c1]) - w1);
    return std::abs(vol1 + vol2);
  }
  case 3:
  {
    const Vec3& a = real[0];
    double v = 1;
    for (std::size_t k = 0; k < nWalls; ++k)
      v *= a[walls[k]->coordinate] - walls[k]->position;
    return std::abs(v);
  }
  default: return 0;
  }
}

/// Sphere sectors inside a pore (Yade's volumeSolidPore, fictitious vertices excluded).
double solidVolume(const PoreNetwork& net, const Pore& p)
{
  constexpr int kPermut4[4][4] = {{0, 1, 2, 3}, {1, 2, 3, 0}, {2, 3, 0, 1}, {3, 0, 1, 2}};
  double v = 0;
  for (const auto& perm : kPermut4)
  {
    const Vertex& s = net.vertices[static_cast<std::size_t>(p.vertices[perm[0]])];
    if (s.fictitious)
      continue;
    v += sectorVolume(s, net.vertices[static_cast<std::size_t>(p.vertices[perm[1]])].pos,
                      net.vertices[static_cast<std::size_t>(p.vertices[perm[2]])].pos,
                      net.vertices[static_cast<std::size_t>(p.vertices[perm[3]])].pos);
  }
  return v;
}

/// Pore volume, solid surface and facet vector of the region between the facet and the two pore
/// centres p1, p2 (Yade's volumePoreVoronoiFraction and surfaceSolidThroat).
void throatRegion(const PoreNetwork& net, Throat& t, const std::array<const Vertex*, 3>& w, const Vec3& p1,
                  const Vec3& p2, bool slipBoundary)
{
  std::array<const Vertex*, 3> fict{};
  std::array<const Vertex*, 3> real{};
  int nf = 0;
  int nr = 0;
  for (const Vertex* v : w)
  {
    if (v->fictitious)
      fict[static_cast<std::size_t>(nf++)] = v;
    else
      real[static_cast<std::size_t>(nr++)] = v;
  }
  t.nFictitious = nf;
  // index (0..2) in the facet of a vertex pointer, to file its solid surface share
  auto slot = [&](const Vertex* v) { return static_cast<std::size_t>(std::find(w.begin(), w.end(), v) - w.begin()); };
  t.solidSurfaces = {0, 0, 0};
  auto bnd = [&](const Vertex* v) -> const Boundary& { return net.boundaries[static_cast<std::size_t>(v->id)]; };
  auto solidWall = [&](const Boundary& b) { return !b.imposedPressure && !slipBoundary; };
  Vec3 s = Vec3::Zero();
  double vpore = 0;
  double ssolid = 0;
  switch (nf)
  {
  case 0:
  {
    s = 0.5 * (w[0]->pos - w[2]->pos).cross(w[1]->pos - w[2]->pos);
    const double vtot = bipyramidVolume(s, p1, p2);
    double vsolid = 0;
    for (int i = 0; i < 3; ++i)
    {
      const Vertex& a = *w[static_cast<std::size_t>(i)];
      const Sector toB = sector(a, w[static_cast<std::size_t>((i + 1) % 3)]->pos, p1, p2);
      const Sector toC = sector(a, w[static_cast<std::size_t>((i + 2) % 3)]->pos, p1, p2);
      vsolid += toB.volume + toC.volume;
      t.solidSurfaces[static_cast<std::size_t>(i)] = toB.area + toC.area;
    }
    vpore = vtot - vsolid;
    break;
  }
  case 1:
  {
    const Vertex& f = *fict[0];
    const Vertex& r1 = *real[0];
    const Vertex& r2 = *real[1];
    const Boundary& b = bnd(&f);
    const int c = b.coordinate;
    // The quadrilateral between the two spheres and their projections on the wall.
    const Vec3 meanHeight = (b.position - 0.5 * (r2.pos[c] + r1.pos[c])) * b.normal;
    s = meanHeight.cross(r2.pos - r1.pos);
    const double vtot = bipyramidVolume(s, p1, p2);
    const Vec3 a = projected(r1.pos, b);
    const Vec3 bb = projected(r2.pos, b);
    const Sector r1r2 = sector(r1, r2.pos, p1, p2);
    const Sector r2r1 = sector(r2, r1.pos, p1, p2);
    const double vsolid = sectorVolume(r1, a, p1, p2) + r1r2.volume + sectorVolume(r2, bb, p1, p2) + r2r1.volume;
    vpore = vtot - vsolid;
    if (solidWall(b))
      t.solidSurfaces[slot(&f)] = std::abs(0.5 * (p1 - p2).cross(r1.pos - r2.pos)[c]);
    // As Yade: the sphere surfaces towards the wall use the fictitious sphere's centre.
    t.solidSurfaces[slot(&r1)] = sphericalArea(r1, f.pos, p1, p2) + r1r2.area;
    t.solidSurfaces[slot(&r2)] = r2r1.area + sphericalArea(r2, f.pos, p1, p2);
    break;
  }
  case 2:
  {
    const Boundary& b1 = bnd(fict[0]);
    const Boundary& b2 = bnd(fict[1]);
    const Vertex& r = *real[0];
    const Vec3 a = projected(r.pos, b1);
    const Vec3 bb = projected(r.pos, b2);
    s = (r.pos - a).cross(r.pos - bb);
    const double vtot = bipyramidVolume(s, p1, p2);
    const Sector toA = sector(r, a, p1, p2);
    const Sector toB = sector(r, bb, p1, p2);
    vpore = vtot - toA.volume - toB.volume;
    t.solidSurfaces[slot(&r)] = toA.area + toB.area;
    const Vec3 side = 0.5 * (p1 - p2).cross(r.pos - p2);
    if (solidWall(b1))
      t.solidSurfaces[slot(fict[0])] = std::abs(side[b1.coordinate]);
    if (solidWall(b2))
      t.solidSurfaces[slot(fict[1])] = std::abs(side[b2.coordinate]);
    break;
  }
  default: break; // three walls: no fluid region (Yade returns 0 volume and 0 surface)
  }
  ssolid = t.solidSurfaces[0] + t.solidSurfaces[1] + t.solidSurfaces[2];
  t.area = s.norm();
  t.facetVector = s;
  t.poreVolume = vpore;
  t.solidSurface = ssolid;
  const double mult = nf == 0 ? 1.0 : nf == 1 ? kMultSym1 : kMultSym2;
  t.hydraulicRadius = ssolid > 0 ? vpore / ssolid * mult : 0.0;
  double cross = 0;
  for (std::size_t i = 0; i < 3; ++i)
  {
    t.crossSections[i] = crossSection(*w[i], w[(i + 1) % 3]->pos, w[(i + 2) % 3]->pos);
    cross += t.crossSections[i];
  }
  double s0 = sphereEdgeOverlap(*w[0], *w[1], *w[2]);
  if (s0 == 0)
    s0 = sphereEdgeOverlap(*w[1], *w[2], *w[0]);
  if (s0 == 0)
    s0 = sphereEdgeOverlap(*w[2], *w[0], *w[1]);
  // Absolute value as Yade: with overlapping spheres the sectors can exceed the facet.
  t.fluidArea = std::abs(t.area - cross + s0);
}
} // namespace

double solidAngle(const Vec3& s, const Vec3& a, const Vec3& b, const Vec3& c)
{
  const Vec3 u = a - s;
  const Vec3 v = b - s;
  const Vec3 w = c - s;
  const double det = u.dot(v.cross(w));
  const double nu = u.norm();
  const double nv = v.norm();
  const double nw = w.norm();
  const double ratio = det / (nu * nv * nw + u.dot(v) * nw + u.dot(w) * nv + v.dot(w) * nu);
  return std::abs(2 * std::atan(ratio));
}

void updatePoreVolumes(PoreNetwork& net, bool voids)
{
  // each pore and (below) each throat only writes its own entry: parallel with OpenMP
  const auto n = static_cast<std::ptrdiff_t>(net.pores.size());
#pragma omp parallel for schedule(static)
  for (std::ptrdiff_t i = 0; i < n; ++i)
  {
    Pore& p = net.pores[static_cast<std::size_t>(i)];
    p.volume = cellVolume(net, p);
    if (voids)
      p.voidVolume = std::abs(p.volume) - solidVolume(net, p);
  }
}

void computeGeometry(PoreNetwork& net, bool slipBoundary)
{
  updatePoreVolumes(net, true);
  const auto n = static_cast<std::ptrdiff_t>(net.throats.size());
#pragma omp parallel for schedule(static)
  for (std::ptrdiff_t i = 0; i < n; ++i)
  {
    Throat& t = net.throats[static_cast<std::size_t>(i)];
    const Pore& p = net.pores[static_cast<std::size_t>(t.pores[0])];
    const Pore& q = net.pores[static_cast<std::size_t>(t.pores[1])];
    // the facet's vertices in the network's canonical order (setFacetVertices)
    std::array<const Vertex*, 3> w{};
    for (std::size_t k = 0; k < 3; ++k)
      w[k] = &net.vertices[static_cast<std::size_t>(t.vertices[k])];
    // the other pore as this one sees it (its periodic image next to it)
    const Vec3 other = q.centre + net.shift(t.period);
    throatRegion(net, t, w, p.centre, other, slipBoundary);
    t.length = std::max(kMinPermLength * 2 * t.hydraulicRadius, (p.centre - other).norm());
  }
}

double computeConductances(PoreNetwork& net, const ConductanceParameters& params)
{
  if (!(params.viscosity > 0))
    throw std::invalid_argument("FlowEngine.viscosity must be positive");
  if (params.permeabilityFactor == 0)
    throw std::invalid_argument("FlowEngine.permeabilityFactor must be non-zero");
  double sumK = 0;
  double sumL = 0;
  double vPoral = 0;
  double sSolid = 0;
  for (Throat& t : net.throats)
  {
    const double diameter = 2 * t.hydraulicRadius;
    if (params.permeabilityFactor > 0)
      t.conductance = params.permeabilityFactor * t.fluidArea * diameter * diameter / (8 * params.viscosity * t.length);
    else
      t.conductance = -params.permeabilityFactor * t.area / t.length;
    // A facet of three walls has no fluid region: Yade's 0/0 there ends at the clamp floor.
    if (t.nFictitious == 3)
      t.conductance = std::numeric_limits<double>::quiet_NaN();
    else
      sumK += t.conductance;
    sumL += t.length;
    vPoral += t.poreVolume;
    sSolid += t.solidSurface;
  }
  const double n = static_cast<double>(net.throats.size());
  const double globalK = params.permeabilityFactor > 0
                             ? params.permeabilityFactor * (sumL / n) * vPoral / (sSolid * 8 * params.viscosity)
                             : sumK / n;
  for (Throat& t : net.throats)
  {
    if (params.clampKValues)
      t.conductance = std::isnan(t.conductance)
                          ? params.minKdivKmean * globalK
                          : std::clamp(t.conductance, params.minKdivKmean * globalK, params.maxKdivKmean * globalK);
    else if (std::isnan(t.conductance))
      t.conductance = 0;
  }
  return globalK;
}
} // namespace talus::flow::pore
