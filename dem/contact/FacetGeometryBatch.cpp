// Four facet-sphere contacts in the four lanes of AVX2 vectors (dem/base/Avx2Lanes.h): each
// lane does contactGeometry's facet path (nonSphereOverlap, closestPointOnTriangle, the frame's
// turn, the incident velocity at the contact point), Eigen's expressions term by term. The
// closest point's Voronoi regions, a branch each in the scalar path that the processor
// mispredicts, become selections between lanes.
#include "dem/contact/FacetGeometryBatch.h"
#include "dem/contact/SphereGeometryLanes.h"

namespace talus::dem
{
namespace
{
using namespace avx2;

/// The same mask of each of the four booleans (all bits of lane i for b[i]).
[[TALUS_AVX2]] inline __m256d maskOf(const bool* b)
{
  return _mm256_castsi256_pd(_mm256_set_epi64x(-static_cast<long long>(b[3]), -static_cast<long long>(b[2]),
                                               -static_cast<long long>(b[1]), -static_cast<long long>(b[0])));
}
[[TALUS_AVX2]] inline __m256d both(__m256d a, __m256d b) { return _mm256_and_pd(a, b); }
[[TALUS_AVX2]] inline __m256d either(__m256d a, __m256d b) { return _mm256_or_pd(a, b); }
[[TALUS_AVX2]] inline __m256d lessEqual(__m256d a, __m256d b) { return _mm256_cmp_pd(a, b, _CMP_LE_OQ); }
[[TALUS_AVX2]] inline __m256d greaterEqual(__m256d a, __m256d b) { return _mm256_cmp_pd(a, b, _CMP_GE_OQ); }
[[TALUS_AVX2]] inline __m256d greater(__m256d a, __m256d b) { return _mm256_cmp_pd(a, b, _CMP_GT_OQ); }
[[TALUS_AVX2]] inline Lanes3 negated(const Lanes3& v)
{
  const __m256d sign = broadcast(-0.0);
  return {_mm256_xor_pd(v.x, sign), _mm256_xor_pd(v.y, sign), _mm256_xor_pd(v.z, sign)};
}

/// Eigen's q * v (_transformVector): uv = q.vec() x v, uv += uv, v + q.w() uv + q.vec() x uv.
/// @param axis, w the quaternions' x, y, z and their w
[[TALUS_AVX2]] inline Lanes3 rotated(const Lanes3& axis, __m256d w, const Lanes3& v)
{
  Lanes3 uv = cross(axis, v);
  uv = add(uv, uv);
  return add(add(v, scale(w, uv)), cross(axis, uv));
}

/// closestPointOnTriangle of four points, each lane's Voronoi region chosen in the scalar
/// path's order (a vertex, an edge, the face) by selections instead of branches.
/// @param inFace set to the lanes whose closest point lies inside the face
[[TALUS_AVX2]] inline Lanes3 closestPoint(const Lanes3& p, const Lanes3& a, const Lanes3& b, const Lanes3& c, __m256d& inFace)
{
  const __m256d zero = _mm256_setzero_pd();
  const Lanes3 ab = sub(b, a), ac = sub(c, a), ap = sub(p, a);
  const __m256d d1 = dot(ab, ap), d2 = dot(ac, ap);
  const Lanes3 bp = sub(p, b);
  const __m256d d3 = dot(ab, bp), d4 = dot(ac, bp);
  const __m256d vc = sub(mul(d1, d4), mul(d3, d2));
  const Lanes3 cp = sub(p, c);
  const __m256d d5 = dot(ab, cp), d6 = dot(ac, cp);
  const __m256d vb = sub(mul(d5, d2), mul(d1, d6));
  const __m256d va = sub(mul(d3, d6), mul(d5, d4));
  const __m256d d43 = sub(d4, d3), d56 = sub(d5, d6);
  // The regions, earliest first as the scalar path tests them.
  const __m256d region[6] = {both(lessEqual(d1, zero), lessEqual(d2, zero)),
                             both(greaterEqual(d3, zero), lessEqual(d4, d3)),
                             both(both(lessEqual(vc, zero), greaterEqual(d1, zero)), lessEqual(d3, zero)),
                             both(greaterEqual(d6, zero), lessEqual(d5, d6)),
                             both(both(lessEqual(vb, zero), greaterEqual(d2, zero)), lessEqual(d6, zero)),
                             both(both(lessEqual(va, zero), greaterEqual(d43, zero)), greaterEqual(d56, zero))};
  const Lanes3 point[6] = {a,
                           b,
                           add(a, scale(div(d1, sub(d1, d3)), ab)),
                           c,
                           add(a, scale(div(d2, sub(d2, d6)), ac)),
                           add(b, scale(div(d43, add(d43, d56)), sub(c, b)))};
  const __m256d denom = div(broadcast(1.0), add(add(va, vb), vc));
  Lanes3 closest = add(add(a, scale(mul(vb, denom), ab)), scale(mul(vc, denom), ac));
  __m256d anyRegion = zero;
  for (int r = 5; r >= 0; --r)
  {
    closest = select(region[r], point[r], closest);
    anyRegion = either(anyRegion, region[r]);
  }
  inFace = _mm256_andnot_pd(anyRegion, _mm256_castsi256_pd(_mm256_set1_epi64x(-1)));
  return closest;
}

/// contactGeometry<false> without a bond (no contact state) of four facet-sphere contacts (body
/// 1 the facet) not across a periodic boundary (cellDist zero); nothing written.
/// @param dt the time step (s)
/// @param apart set to the lanes of contacts that were not real and do not touch (nothing to do)
/// @return the geometry; `touching`: the lanes of contacts that were real and still touch, the
///         others' values mean nothing (left to contactGeometry: contacts beginning or ending)
[[TALUS_AVX2]] inline SphereGeometry facetGeometry(Contact* const* contacts, const Bodies& b, double dt, unsigned& apart)
{
  std::size_t i1[4], i2[4];
  const double* vertex[3][4];
  const double* faceNormal[4];
  const double* q[4];
  bool wasReal[4];
  for (int i = 0; i < 4; ++i)
  {
    i1[i] = static_cast<std::size_t>(contacts[i]->id1);
    i2[i] = static_cast<std::size_t>(contacts[i]->id2);
    const FacetShape& f = b.facets[static_cast<std::size_t>(b.shapeIndex[i1[i]])];
    for (int v = 0; v < 3; ++v)
      vertex[v][i] = f.vertices[static_cast<std::size_t>(v)].data();
    faceNormal[i] = f.normal.data();
    q[i] = b.ori[i1[i]].coeffs().data(); // x, y, z, w
    wasReal[i] = contacts[i]->real;
  }
  const __m256d zero = _mm256_setzero_pd();
  const Lanes3 noShift{zero, zero, zero};
  const __m256d real = maskOf(wasReal);
  // The facet's vertices and normal in the world frame (facetVertices).
  const Lanes3 axis = load(q[0], q[1], q[2], q[3]);
  const __m256d w = _mm256_set_pd(q[3][3], q[2][3], q[1][3], q[0][3]);
  const Lanes3 p1 = load(b.pos, i1);
  Lanes3 v[3];
  for (int k = 0; k < 3; ++k)
    v[k] = add(p1, rotated(axis, w, load(vertex[k][0], vertex[k][1], vertex[k][2], vertex[k][3])));
  // The overlap (nonSphereOverlap's facet path, no bond to hold the contact).
  const __m256d r = load(b.radius, i2);
  const Lanes3 p2 = load(b.pos, i2);
  const Lanes3 centre = add(p2, noShift);
  __m256d inFace;
  const Lanes3 d = sub(centre, closestPoint(centre, v[0], v[1], v[2], inFace));
  const __m256d dist2 = dot(d, d);
  const __m256d far = greater(dist2, mul(r, r));
  const auto farLanes = static_cast<unsigned>(_mm256_movemask_pd(far));
  const auto realLanes = static_cast<unsigned>(_mm256_movemask_pd(real));
  SphereGeometry g;
  apart = farLanes & ~realLanes;
  g.touching = ~farLanes & realLanes & 15U;
  if (g.touching == 0)
    return g;
  const __m256d dist = _mm256_sqrt_pd(dist2);
  const Lanes3 n = rotated(axis, w, load(faceNormal[0], faceNormal[1], faceNormal[2], faceNormal[3]));
  // Inside the face: its normal on the sphere's side (the previous side if on the plane); else
  // from the closest point, or the face's normal with the centre on an edge or a vertex.
  const Lanes3 oldNormal = load(contacts, &Contact::normal);
  const __m256d side = dot(d, n);
  const __m256d facing
      = either(greater(side, zero), both(both(_mm256_cmp_pd(side, zero, _CMP_EQ_OQ), real), greater(dot(oldNormal, n), zero)));
  const Lanes3 fromPoint = select(greater(dist, zero), Lanes3{div(d.x, dist), div(d.y, dist), div(d.z, dist)}, n);
  g.normal = select(inFace, select(facing, n, negated(n)), fromPoint);
  g.penetration = sub(r, dist);
  g.contactPoint = sub(centre, scale(sub(r, mul(broadcast(0.5), g.penetration)), g.normal));
  g.r1 = mul(broadcast(2.0), r);
  g.r2 = r;

  // The shear force turned with the frame, as for two spheres.
  const Lanes3 w1 = load(b.angVel, i1), w2 = load(b.angVel, i2);
  g.shearForce = turnedShearForce(contacts, oldNormal, g.normal, w1, w2, dt);

  // The shear increment: the incident velocity with the true arms to the contact point
  // (incidentVelocity), its tangential part times dt.
  const Lanes3 incident = sub(add(add(load(b.vel, i2), noShift), cross(w2, sub(g.contactPoint, add(p2, noShift)))),
                              add(load(b.vel, i1), cross(w1, sub(g.contactPoint, p1))));
  g.shearIncrement = scale(broadcast(dt), sub(incident, scale(dot(g.normal, incident), g.normal)));
  return g;
}
} // namespace

[[gnu::target("avx2")]] FacetLanes facetGeometryBatch(Contact* const* contacts, const Bodies& b, double dt)
{
  FacetLanes done;
  const SphereGeometry g = facetGeometry(contacts, b, dt, done.apart);
  store(g, contacts, g.touching);
  done.geometry = g.touching;
  return done;
}
} // namespace talus::dem
