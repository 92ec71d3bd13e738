// Python bindings of Potential Particles (shape, contact geometry probe, surface for output).
// Compiled into talus._dem; `talus_wrap_particles(m)` is called from dem_wrappers.cpp. The Python
// API (Yade's names) is talus.dem.geometry.particles.
#include "dem/contact/PotentialParticleContact.h"
#include "dem/core/Scene.h"
#include "dem/python/convex_contact_probe.h"

#include <pybind11/eigen.h>
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <cmath>
#include <stdexcept>
#include <string>

namespace py = pybind11;
using namespace talus::dem;

void talus_wrap_particles(py::module_& m);

namespace
{
const PotentialParticleShape& particleOf(const Scene& s, BodyId id)
{
  return convexShapeOf(s, id, ShapeKind::PotentialParticle, &Bodies::particles, "PotentialParticle");
}

py::dict describe(const PotentialParticleShape& p)
{
  py::dict out;
  out["normals"] = p.normals;
  out["d"] = p.d;
  out["r"] = p.r;
  out["k"] = p.k;
  out["R"] = p.R;
  out["isBoundary"] = p.isBoundary;
  out["volume"] = p.volume;
  out["inertiaPerDensity"] = p.inertiaPerDensity;
  out["axes"] = p.axes;
  out["centroid"] = p.centroid;
  out["boundingRadius"] = p.boundingRadius;
  return out;
}
} // namespace

void talus_wrap_particles(py::module_& m)
{
  m.def(
      "add_potential_particle",
      [](Scene& s, const std::vector<double>& a, const std::vector<double>& b, const std::vector<double>& c,
         const std::vector<double>& d, double r, double k, double R, bool isBoundary, const Vec3& position,
         const Eigen::Vector4d& wxyz, int material, bool fixed) {
        return s.addPotentialParticle(a, b, c, d, r, k, R, isBoundary, position,
                                      Quat(wxyz[0], wxyz[1], wxyz[2], wxyz[3]), material, fixed);
      },
      py::arg("scene"), py::arg("a"), py::arg("b"), py::arg("c"), py::arg("d"), py::arg("r"), py::arg("k"),
      py::arg("R"), py::arg("isBoundary"), py::arg("position"), py::arg("orientation"), py::arg("material"),
      py::arg("fixed"));
  // Volume, centroid, principal axes and inertia of the particle the arguments define, at a
  // given quadrature (rays: quadrature x 2 quadrature), without adding a body.
  m.def(
      "potential_particle_properties",
      [](const std::vector<double>& a, const std::vector<double>& b, const std::vector<double>& c,
         const std::vector<double>& d, double r, double k, double R, int quadrature) {
        if (quadrature < 4 || quadrature > 2000)
          throw std::invalid_argument("quadrature must be in 4..2000, got " + std::to_string(quadrature));
        return describe(makePotentialParticle(a, b, c, d, r, k, R, false, "PotentialParticle", quadrature));
      },
      py::arg("a"), py::arg("b"), py::arg("c"), py::arg("d"), py::arg("r"), py::arg("k"), py::arg("R"),
      py::arg("quadrature") = 96);
  m.def("particle_shape", [](const Scene& s, BodyId id) { return describe(particleOf(s, id)); });
  m.def("particle_aabb", [](const Scene& s, BodyId id) {
    particleOf(s, id);
    Vec3 lo, hi;
    potentialParticleAabb(s.bodies, static_cast<std::size_t>(id), lo, hi);
    return std::make_pair(lo, hi);
  });
  // The potential f of particle `id` at world points (n x 3).
  m.def("particle_potential", [](const Scene& s, BodyId id, const Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor>& x) {
    const PotentialParticleShape& p = particleOf(s, id);
    const auto i = static_cast<std::size_t>(id);
    const PlacedPotential f = placePotential(p, s.bodies.pos[i], s.bodies.ori[i], Vec3::Zero());
    Eigen::VectorXd out(x.rows());
    for (Eigen::Index k = 0; k < x.rows(); ++k)
      out[k] = f.eval(x.row(k).transpose());
    return out;
  });
  // World points of the surface on a latitude-longitude grid of rays from the centroid
  // (nTheta + 1 rings of nPhi points, poles repeated): a closed mesh of the true surface.
  m.def("particle_surface", [](const Scene& s, BodyId id, int nTheta, int nPhi) {
    const PotentialParticleShape& p = particleOf(s, id);
    if (nTheta < 2 || nPhi < 3)
      throw std::invalid_argument("particle_surface: nTheta >= 2 and nPhi >= 3 needed");
    const auto i = static_cast<std::size_t>(id);
    const PlacedPotential f = placePotential(p, s.bodies.pos[i], s.bodies.ori[i], s.bodies.pos[i]);
    Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor> out((nTheta + 1) * nPhi, 3);
    double rho = 0;
    for (int t = 0; t <= nTheta; ++t)
      for (int q = 0; q < nPhi; ++q)
      {
        const double th = M_PI * t / nTheta, ph = 2 * M_PI * q / nPhi;
        const Vec3 u(std::sin(th) * std::cos(ph), std::sin(th) * std::sin(ph), std::cos(th));
        rho = rayExit(f, nullptr, Vec3::Zero(), u, rho, p.R);
        out.row(t * nPhi + q) = (s.bodies.pos[i] + rho * u).transpose();
      }
    return out;
  });
  // Ig2_PP_PP_ScGeom's settings for every particle contact of the scene (set from O.engines).
  m.def(
      "set_particle_contact_settings",
      [](Scene& s, bool twoDimension, const Vec3& twoDdir, double unitWidth2D) {
        checkTwoDimension("Ig2_PP_PP_ScGeom", twoDdir, unitWidth2D);
        s.bodies.particleContact = ParticleContactSettings{twoDimension, twoDdir.normalized(), unitWidth2D};
      },
      py::arg("scene"), py::arg("twoDimension"), py::arg("twoDdir"), py::arg("unitWidth2D"));
  // The contact geometry of a pair as it stands, timed (convex_contact_probe.h).
  m.def(
      "particle_contact",
      [](const Scene& s, BodyId id1, BodyId id2, int repeats, double accuracyTol) {
        return probeConvexContact(s, id1, id2, repeats, accuracyTol,
                                  [](const Scene& sc, BodyId id) { particleOf(sc, id); }, potentialParticleContact);
      },
      py::arg("scene"), py::arg("id1"), py::arg("id2"), py::arg("repeats") = 1,
      py::arg("accuracyTol") = defaultParticleAccuracyTol);
}
