// Python bindings of Potential Blocks (shape, contact geometry probe). Compiled into
// talus._dem; `talus_wrap_blocks(m)` is called from dem_wrappers.cpp. The Python API (Yade's
// names) is talus.dem.geometry.blocks.
#include "dem/contact/PotentialBlockContact.h"
#include "dem/core/Scene.h"
#include "dem/python/convex_contact_probe.h"

#include <pybind11/eigen.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <cmath>
#include <optional>
#include <stdexcept>
#include <string>

namespace py = pybind11;
using namespace talus::dem;

void talus_wrap_blocks(py::module_& m);

namespace
{
const PotentialBlockShape& blockOf(const Scene& s, BodyId id)
{
  return convexShapeOf(s, id, ShapeKind::PotentialBlock, &Bodies::blocks, "PotentialBlock");
}
} // namespace

void talus_wrap_blocks(py::module_& m)
{
#ifdef TALUS_HAVE_CLP
  m.attr("have_potential_blocks") = true;
#else
  m.attr("have_potential_blocks") = false;
#endif
  m.def(
      "add_potential_block",
      [](Scene& s, const std::vector<double>& a, const std::vector<double>& b, const std::vector<double>& c,
         const std::vector<double>& d, double r, double R, bool isBoundary, std::optional<Vec3> center,
         const Eigen::Vector4d& wxyz, int material, bool fixed, const std::vector<double>& cohesion,
         const std::vector<double>& tension, const std::vector<bool>& intactRock, const std::vector<int>& jointType) {
        // Checked before the body is added, so a bad list leaves the scene as it was.
        PotentialBlockShape probe;
        probe.normals.resize(a.size());
        const std::string which = "PotentialBlock #" + std::to_string(s.bodies.size());
        setBlockFaceProperties(probe, cohesion, tension, intactRock, jointType, which);
        const BodyId id = s.addPotentialBlock(a, b, c, d, r, R, isBoundary, center ? &*center : nullptr,
                                              Quat(wxyz[0], wxyz[1], wxyz[2], wxyz[3]), material, fixed);
        setBlockFaceProperties(s.bodies.blocks.back(), cohesion, tension, intactRock, jointType, which);
        return id;
      },
      py::arg("scene"), py::arg("a"), py::arg("b"), py::arg("c"), py::arg("d"), py::arg("r"), py::arg("R"),
      py::arg("isBoundary"), py::arg("center"), py::arg("orientation"), py::arg("material"), py::arg("fixed"),
      py::arg("cohesion") = std::vector<double>{}, py::arg("tension") = std::vector<double>{},
      py::arg("intactRock") = std::vector<bool>{}, py::arg("jointType") = std::vector<int>{});
  // Volume, centroid and corners (in the planes' frame) of the block the planes bound, without
  // adding a body (block generation); raises as addPotentialBlock does on bad planes.
  m.def("potential_block_geometry", [](const std::vector<double>& a, const std::vector<double>& b,
                                       const std::vector<double>& c, const std::vector<double>& d, double r,
                                       const std::string& which) {
    PotentialBlockPlacement p;
    const PotentialBlockShape s = makePotentialBlock(a, b, c, d, r, 0.0, false, which, &p);
    std::vector<Vec3> corners;
    for (const Vec3& v : s.vertices)
      corners.push_back(p.principalAxes * v + p.centroid);
    py::dict out;
    out["volume"] = s.volume;
    out["centroid"] = p.centroid;
    out["vertices"] = corners;
    return out;
  });
  // Centre and radius of the largest ball inside normals . x <= h (BlockGen's minSize pruning).
  m.def("deepest_point", [](const std::vector<Vec3>& normals, const std::vector<double>& h, double bound) {
    if (normals.size() != h.size())
      throw std::invalid_argument("deepest_point: " + std::to_string(normals.size()) + " normals but " +
                                  std::to_string(h.size()) + " offsets");
    Vec3 x = Vec3::Zero();
    const double depth = deepestPoint(normals, h, bound, x);
    return std::make_pair(depth, x);
  });
  // The shape in the body's (principal) frame.
  m.def("block_shape", [](const Scene& s, BodyId id) {
    const PotentialBlockShape& b = blockOf(s, id);
    py::dict out;
    out["normals"] = b.normals;
    out["d"] = b.d;
    out["r"] = b.r;
    out["R"] = b.R;
    out["isBoundary"] = b.isBoundary;
    out["vertices"] = b.vertices;
    out["faces"] = b.faces;
    out["volume"] = b.volume;
    out["cohesion"] = b.cohesion;
    out["tension"] = b.tension;
    out["intactRock"] = std::vector<bool>(b.intactRock.begin(), b.intactRock.end());
    out["jointType"] = b.jointType;
    return out;
  });
  m.def("block_aabb", [](const Scene& s, BodyId id) {
    blockOf(s, id);
    Vec3 lo, hi;
    potentialBlockAabb(s.bodies, static_cast<std::size_t>(id), lo, hi);
    return std::make_pair(lo, hi);
  });
  // The contact geometry of a pair as it stands, timed (convex_contact_probe.h).
  m.def(
      "block_contact",
      [](const Scene& s, BodyId id1, BodyId id2, int repeats, std::optional<double> accuracyTol) {
        return probeConvexContact(s, id1, id2, repeats, accuracyTol.value_or(s.bodies.blockContact.accuracyTol),
                                  [](const Scene& sc, BodyId id) { blockOf(sc, id); }, potentialBlockContact);
      },
      py::arg("scene"), py::arg("id1"), py::arg("id2"), py::arg("repeats") = 1,
      py::arg("accuracyTol") = std::nullopt);
  m.attr("default_block_accuracy_tol") = defaultBlockAccuracyTol;
  // Ig2_PB_PB_ScGeom's settings for every block contact of the scene (set from O.engines).
  m.def(
      "set_block_contact_settings",
      [](Scene& s, bool twoDimension, const Vec3& twoDdir, double unitWidth2D, bool exactDepth, double accuracyTol) {
        checkTwoDimension("Ig2_PB_PB_ScGeom", twoDdir, unitWidth2D);
        if (!std::isfinite(accuracyTol) || !(accuracyTol > 0))
          throw std::invalid_argument("Ig2_PB_PB_ScGeom.accuracyTol must be finite and > 0, got "
                                      + std::to_string(accuracyTol));
        s.bodies.blockContact =
            BlockContactSettings{twoDimension, twoDdir.normalized(), unitWidth2D, exactDepth, accuracyTol};
      },
      py::arg("scene"), py::arg("twoDimension"), py::arg("twoDdir"), py::arg("unitWidth2D"), py::arg("exactDepth"),
      py::arg("accuracyTol"));
  // Contact areas of the real contacts (same order as Scene.contacts()); 0 without extra state.
  m.def("contact_areas", [](const Scene& s) {
    std::vector<double> out;
    const auto& list = s.contacts.list;
    const ContactExtra* extra = s.contacts.extraState();
    for (std::size_t k = 0; k < list.size(); ++k)
      if (list[k].real)
        out.push_back(extra ? extra[k].contactArea : 0.0);
    return out;
  });
}
