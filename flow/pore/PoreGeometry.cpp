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

/// Solid angles at apex s of the cones (s; x, b, c) for several x with b and c fixed: what
/// depends on s, b, c only is computed once. A throat asks for two or three cones at each of its
/// spheres, all towards the two pore centres (b, c); the solid angles, an arctangent each, are
/// most of the geometry's cost. The arithmetic is the formula of solidAngle, term for term.
class ConesAt
{
public:
  ConesAt(const Vec3& s, const Vec3& b, const Vec3& c)
      : apex_(s), v_(b - s), w_(c - s), vw_(v_.cross(w_)), nv_(v_.norm()), nw_(w_.norm()), dotVW_(v_.dot(w_))
  {
  }
  /// Solid angle of the triangle (x, b, c) seen from the apex (Van Oosterom & Strackee; as Yade,
  /// the absolute value of 2 atan(ratio)).
  [[nodiscard]] double towards(const Vec3& x) const
  {
    const Vec3 u = x - apex_;
    const double nu = u.norm();
    const double ratio = u.dot(vw_) / (nu * nv_ * nw_ + u.dot(v_) * nw_ + u.dot(w_) * nv_ + dotVW_ * nu);
    return std::abs(2 * std::atan(ratio));
  }

private:
  Vec3 apex_;
  Vec3 v_;
  Vec3 w_;
  Vec3 vw_;
  double nv_;
  double nw_;
  double dotVW_;
};

/// The spherical triangle cut on a sphere by a cone at its centre and the sphere sector inside
/// it (the throat formulas need both of the same cone).
struct Sector
{
  double area;
  double volume;
};

/// The sectors of sphere v in the cones (v; x, p1, p2) towards the two pore centres of a throat.
class SectorsTowards
{
public:
  SectorsTowards(const Vertex& v, const Vec3& p1, const Vec3& p2) : v_(v), cones_(v.pos, p1, p2) {}
  [[nodiscard]] Sector of(const Vec3& x) const
  {
    const double area = v_.radius == 0 ? 0.0 : v_.radius * v_.radius * cones_.towards(x);
    return {area, kThird * v_.radius * area};
  }

private:
  const Vertex& v_;
  ConesAt cones_;
};

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
    const Vec3& b = net.vertices[static_cast<std::size_t>(p.vertices[perm[2]])].pos;
    const Vec3& c = net.vertices[static_cast<std::size_t>(p.vertices[perm[3]])].pos;
    v += SectorsTowards(s, b, c).of(net.vertices[static_cast<std::size_t>(p.vertices[perm[1]])].pos).volume;
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
      const SectorsTowards at(*w[static_cast<std::size_t>(i)], p1, p2);
      const Sector toB = at.of(w[static_cast<std::size_t>((i + 1) % 3)]->pos);
      const Sector toC = at.of(w[static_cast<std::size_t>((i + 2) % 3)]->pos);
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
    const SectorsTowards at1(r1, p1, p2);
    const SectorsTowards at2(r2, p1, p2);
    const Sector r1r2 = at1.of(r2.pos);
    const Sector r2r1 = at2.of(r1.pos);
    const double vsolid = at1.of(a).volume + r1r2.volume + at2.of(bb).volume + r2r1.volume;
    vpore = vtot - vsolid;
    if (solidWall(b))
      t.solidSurfaces[slot(&f)] = std::abs(0.5 * (p1 - p2).cross(r1.pos - r2.pos)[c]);
    // As Yade: the sphere surfaces towards the wall use the fictitious sphere's centre.
    t.solidSurfaces[slot(&r1)] = at1.of(f.pos).area + r1r2.area;
    t.solidSurfaces[slot(&r2)] = r2r1.area + at2.of(f.pos).area;
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
    const SectorsTowards at(r, p1, p2);
    const Sector toA = at.of(a);
    const Sector toB = at.of(bb);
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

double solidAngle(const Vec3& s, const Vec3& a, const Vec3& b, const Vec3& c) { return ConesAt(s, b, c).towards(a); }

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
  constexpr std::ptrdiff_t kPrefetchAhead = 16;
  updatePoreVolumes(net, true);
  const auto n = static_cast<std::ptrdiff_t>(net.throats.size());
#pragma omp parallel for schedule(static)
  for (std::ptrdiff_t i = 0; i < n; ++i)
  {
    // the second pore is anywhere in the array (the first near the last throat's): its centre
    // is fetched a few throats ahead instead of waited for (unitForceVectors does the same)
    if (i + kPrefetchAhead < n)
    {
      const Throat& ahead = net.throats[static_cast<std::size_t>(i + kPrefetchAhead)];
      __builtin_prefetch(&net.pores[static_cast<std::size_t>(ahead.pores[1])].centre);
    }
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

double computeConductances(PoreNetwork& net, const ConductanceParameters& params, const std::vector<char>& outside)
{
  const auto between = [&outside](const Throat& t) {
    return !outside.empty() && outside[static_cast<std::size_t>(t.pores[0])] && outside[static_cast<std::size_t>(t.pores[1])];
  };
  if (!(params.viscosity > 0))
    throw std::invalid_argument("FlowEngine.viscosity must be positive");
  if (params.permeabilityFactor == 0)
    throw std::invalid_argument("FlowEngine.permeabilityFactor must be non-zero");
  double sumK = 0;
  double sumL = 0;
  double vPoral = 0;
  double sSolid = 0;
  std::size_t counted = 0;
  for (Throat& t : net.throats)
  {
    if (between(t))
      continue;
    ++counted;
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
  const double n = static_cast<double>(counted);
  const double globalK = params.permeabilityFactor > 0
                             ? params.permeabilityFactor * (sumL / n) * vPoral / (sSolid * 8 * params.viscosity)
                             : sumK / n;
  for (Throat& t : net.throats)
  {
    if (between(t))
      t.conductance = 0;
    else if (params.clampKValues)
      t.conductance = std::isnan(t.conductance)
                          ? params.minKdivKmean * globalK
                          : std::clamp(t.conductance, params.minKdivKmean * globalK, params.maxKdivKmean * globalK);
    else if (std::isnan(t.conductance))
      t.conductance = 0;
  }
  return globalK;
}
} // namespace talus::flow::pore
