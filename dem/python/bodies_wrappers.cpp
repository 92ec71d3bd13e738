// Python bindings of dem/'s body types and kinematics: kinematic engines, clumps, boxes.
// Compiled into talus._dem; `talus_wrap_bodies(m)` is called from dem_wrappers.cpp. The Python
// API (Yade's names, defaults, docstrings) is talus.dem.step.kinematic and talus.dem.core.bodies.
#include "dem/impose/KinematicEngines.h"
#include "dem/core/Scene.h"
#include "dem/control/ServoPIDController.h"

#include <pybind11/eigen.h>
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <cstring>
#include <stdexcept>
#include <string>

namespace py = pybind11;
using namespace talus::dem;

namespace
{
/// Row `row` of a per-body array, copied into a new 3-array of `type`, a subclass of numpy's
/// ndarray (Yade's Vector3 of talus.dem.base.linalg). Scripts read bodies one at a time in their
/// loops: made here in one call, the vector costs a fraction of a view of the whole array
/// indexed and copied in Python (docs/dem.md, "Measurements behind the code").
py::object rowVector(const std::vector<Vec3>& rows, BodyId row, const py::handle& type)
{
  if (row < 0 || static_cast<std::size_t>(row) >= rows.size())
    throw py::index_error("no body " + std::to_string(row) + " (the scene has " + std::to_string(rows.size()) + ")");
  auto& api = py::detail::npy_api::get();
  if (!PyType_Check(type.ptr()) || !PyType_IsSubtype(reinterpret_cast<PyTypeObject*>(type.ptr()), api.PyArray_Type_))
    throw py::type_error("rowVector: the type must be a subclass of numpy.ndarray");
  Py_intptr_t shape[1] = {3};
  PyObject* array = api.PyArray_NewFromDescr_(reinterpret_cast<PyTypeObject*>(type.ptr()),
                                              py::dtype::of<double>().release().ptr(), 1, shape, nullptr, nullptr, 0, nullptr);
  if (array == nullptr)
    throw py::error_already_set();
  std::memcpy(py::detail::array_proxy(array)->data, rows[static_cast<std::size_t>(row)].data(), 3 * sizeof(double));
  return py::reinterpret_steal<py::object>(array);
}
} // namespace

void talus_wrap_bodies(py::module_& m)
{
  py::class_<KinematicEngine, Engine, std::shared_ptr<KinematicEngine>>(m, "KinematicEngine")
      .def_readwrite("ids", &KinematicEngine::ids);
  py::class_<TranslationEngine, KinematicEngine, std::shared_ptr<TranslationEngine>>(m, "TranslationEngine")
      .def(py::init<>())
      .def_readwrite("translationAxis", &TranslationEngine::translationAxis)
      .def_readwrite("velocity", &TranslationEngine::velocity);
  py::class_<ServoPIDController, TranslationEngine, std::shared_ptr<ServoPIDController>>(m, "ServoPIDController")
      .def(py::init<>())
      .def_readwrite("axis", &ServoPIDController::axis)
      .def_readwrite("target", &ServoPIDController::target)
      .def_readwrite("maxVelocity", &ServoPIDController::maxVelocity)
      .def_readwrite("kP", &ServoPIDController::kP)
      .def_readwrite("kI", &ServoPIDController::kI)
      .def_readwrite("kD", &ServoPIDController::kD)
      .def_readwrite("iterPeriod", &ServoPIDController::iterPeriod)
      .def_readwrite("iterPrevStart", &ServoPIDController::iterPrevStart)
      .def_readwrite("errorCur", &ServoPIDController::errorCur)
      .def_readwrite("errorPrev", &ServoPIDController::errorPrev)
      .def_readwrite("iTerm", &ServoPIDController::iTerm)
      .def_readwrite("curVel", &ServoPIDController::curVel)
      .def_readwrite("current", &ServoPIDController::current);
  py::class_<RotationEngine, KinematicEngine, std::shared_ptr<RotationEngine>>(m, "RotationEngine")
      .def(py::init<>())
      .def_readwrite("rotationAxis", &RotationEngine::rotationAxis)
      .def_readwrite("angularVelocity", &RotationEngine::angularVelocity)
      .def_readwrite("rotateAroundZero", &RotationEngine::rotateAroundZero)
      .def_readwrite("zeroPoint", &RotationEngine::zeroPoint);
  py::class_<HarmonicMotionEngine, KinematicEngine, std::shared_ptr<HarmonicMotionEngine>>(m, "HarmonicMotionEngine")
      .def(py::init<>())
      .def_readwrite("A", &HarmonicMotionEngine::A)
      .def_readwrite("f", &HarmonicMotionEngine::f)
      .def_readwrite("fi", &HarmonicMotionEngine::fi);
  py::class_<CombinedKinematicEngine, KinematicEngine, std::shared_ptr<CombinedKinematicEngine>>(m, "CombinedKinematicEngine")
      .def(py::init<>())
      .def_readwrite("comb", &CombinedKinematicEngine::comb);
  py::class_<HelixEngine, RotationEngine, std::shared_ptr<HelixEngine>>(m, "HelixEngine")
      .def(py::init<>())
      .def_readwrite("linearVelocity", &HelixEngine::linearVelocity)
      .def_readwrite("angleTurned", &HelixEngine::angleTurned);
  py::class_<InterpolatingHelixEngine, HelixEngine, std::shared_ptr<InterpolatingHelixEngine>>(m, "InterpolatingHelixEngine")
      .def(py::init<>())
      .def_readwrite("times", &InterpolatingHelixEngine::times)
      .def_readwrite("angularVelocities", &InterpolatingHelixEngine::angularVelocities)
      .def_readwrite("wrap", &InterpolatingHelixEngine::wrap)
      .def_readwrite("slope", &InterpolatingHelixEngine::slope);

  m.def("add_box", [](Scene& s, const Vec3& center, const Vec3& extents, const Eigen::Vector4d& wxyz, int material, bool fixed) {
    return s.addBox(center, extents, Quat(wxyz[0], wxyz[1], wxyz[2], wxyz[3]), material, fixed);
  });
  m.def("add_clump", &Scene::addClump, py::arg("scene"), py::arg("members"), py::arg("discretization") = 0);
  m.def("clump_id", [](const Scene& s, BodyId id) {
    s.checkBody(id);
    return s.bodies.clumpId[static_cast<std::size_t>(id)];
  });
  // Yade's b.mask: a change re-detects the contacts (the pairs it allows or refuses now), and
  // engines with a mask see it.
  m.def("group_mask", [](const Scene& s, BodyId id) {
    s.checkBody(id);
    return s.bodies.groupMask[static_cast<std::size_t>(id)];
  });
  m.def("set_group_mask", [](Scene& s, BodyId id, int mask) {
    s.checkBody(id);
    s.bodies.groupMask[static_cast<std::size_t>(id)] = mask;
    ++s.bodiesVersion;
  });
  // Yade's State.isDamped: whether NewtonIntegrator's damping acts on the body.
  m.def("is_damped", [](const Scene& s, BodyId id) {
    s.checkBody(id);
    return s.bodies.damped[static_cast<std::size_t>(id)] != 0;
  });
  m.def("set_damped", [](Scene& s, BodyId id, bool damped) {
    s.checkBody(id);
    s.bodies.damped[static_cast<std::size_t>(id)] = damped ? 1 : 0;
  });
  m.def("add_to_clump", &Scene::addToClump, py::arg("scene"), py::arg("clump"), py::arg("ids"),
        py::arg("discretization") = 0);
  m.def("release_from_clump", &Scene::releaseFromClump, py::arg("scene"), py::arg("member"), py::arg("clump"),
        py::arg("discretization") = 0);
  // A clump's members with their placement in its frame: (ids, relPos, relOri as w, x, y, z).
  m.def("clump_members", [](Scene& s, BodyId id) {
    const ClumpShape& clump = s.clumpShape(id);
    std::vector<Eigen::Vector4d> ori;
    for (const Quat& q : clump.relOri)
      ori.emplace_back(q.w(), q.x(), q.y(), q.z());
    return py::make_tuple(clump.members, clump.relPos, ori);
  });
  // What a script reads as `b.shape.<attribute>` (talus.dem.geometry.shapes): the per-kind geometry.
  m.def("shape_data", [](const Scene& s, BodyId id) {
    s.checkBody(id);
    const auto i = static_cast<std::size_t>(id);
    const auto k = static_cast<std::size_t>(s.bodies.shapeIndex[i]);
    py::dict d;
    switch (s.bodies.shape[i])
    {
    case ShapeKind::Wall:
      d["axis"] = s.bodies.walls[k].axis;
      d["sense"] = s.bodies.walls[k].sense;
      break;
    case ShapeKind::Facet:
      d["vertices"] = std::vector<Vec3>(s.bodies.facets[k].vertices.begin(), s.bodies.facets[k].vertices.end());
      d["normal"] = s.bodies.facets[k].normal;
      d["bounded"] = s.bodies.facets[k].bounded;
      break;
    default: break;
    }
    return d;
  });
  m.def("box_extents", [](const Scene& s, BodyId id) {
    s.checkBody(id);
    const auto i = static_cast<std::size_t>(id);
    if (s.bodies.shape[i] != ShapeKind::Box)
      throw std::invalid_argument("body " + std::to_string(id) + " is not a box");
    return s.bodies.boxes[static_cast<std::size_t>(s.bodies.shapeIndex[i])].extents;
  });
  m.def("set_ang_vel", [](Scene& s, BodyId id, const Vec3& w) {
    s.checkBody(id);
    if (!w.allFinite())
      throw std::invalid_argument("body " + std::to_string(id) + ": angVel must be finite");
    s.bodies.setAngularVelocity(static_cast<std::size_t>(id), w);
  });
  m.def("ang_mom", [](Scene& s, BodyId id) {
    s.checkBody(id);
    return s.bodies.angMom[static_cast<std::size_t>(id)];
  });
  // O.bodies[id] of a scene in one process: its row (the id, counted from the end if negative),
  // -1 if the body was erased.
  m.def("body_row", [](const Scene& s, std::int64_t id) {
    const auto n = static_cast<std::int64_t>(s.bodies.size());
    const std::int64_t row = id < 0 ? id + n : id;
    if (row < 0 || row >= n)
      throw py::index_error("no body with id " + std::to_string(id) + " (ids run from 0 to " + std::to_string(n - 1) + ")");
    return s.bodies.alive[static_cast<std::size_t>(row)] ? row : std::int64_t{-1};
  });
  m.def("body_pos", [](const Scene& s, BodyId row, py::handle type) { return rowVector(s.bodies.pos, row, type); });
  m.def("body_vel", [](const Scene& s, BodyId row, py::handle type) { return rowVector(s.bodies.vel, row, type); });
  m.def("body_ang_vel", [](const Scene& s, BodyId row, py::handle type) { return rowVector(s.bodies.angVel, row, type); });
  m.def("erase", &Scene::erase, py::arg("scene"), py::arg("id"), py::arg("eraseClumpMembers") = false);
}
