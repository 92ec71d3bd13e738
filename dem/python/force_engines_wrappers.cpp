// Python bindings of the force engines and the InteractionLoop's callbacks. Compiled into
// talus._dem; `talus_wrap_force_engines(m)` is called from dem_wrappers.cpp. The Python API
// (Yade's names, defaults, docstrings) is talus.dem.step.force_engines.
#include "dem/impose/ForceEngines.h"
#include "dem/engines/InteractionLoop.h"
#include "dem/laws/IntrCallback.h"

#include <pybind11/eigen.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

namespace py = pybind11;
using namespace talus::dem;

void talus_wrap_force_engines(py::module_& m);

void talus_wrap_force_engines(py::module_& m)
{
  py::class_<ForceEngine, Engine, std::shared_ptr<ForceEngine>>(m, "ForceEngine")
      .def(py::init<>())
      .def_readwrite("ids", &ForceEngine::ids)
      .def_readwrite("force", &ForceEngine::force);
  py::class_<InterpolatingDirectedForceEngine, ForceEngine, std::shared_ptr<InterpolatingDirectedForceEngine>>(
      m, "InterpolatingDirectedForceEngine")
      .def(py::init<>())
      .def_readwrite("times", &InterpolatingDirectedForceEngine::times)
      .def_readwrite("magnitudes", &InterpolatingDirectedForceEngine::magnitudes)
      .def_readwrite("direction", &InterpolatingDirectedForceEngine::direction)
      .def_readwrite("wrap", &InterpolatingDirectedForceEngine::wrap);
  py::class_<HarmonicForceEngine, ForceEngine, std::shared_ptr<HarmonicForceEngine>>(m, "HarmonicForceEngine")
      .def(py::init<>())
      .def_readwrite("A", &HarmonicForceEngine::A)
      .def_readwrite("f", &HarmonicForceEngine::f)
      .def_readwrite("fi", &HarmonicForceEngine::fi);
  py::class_<GravityEngine, Engine, std::shared_ptr<GravityEngine>>(m, "GravityEngine")
      .def(py::init<>())
      .def_readwrite("gravity", &GravityEngine::gravity)
      .def_readwrite("warnOnce", &GravityEngine::warnOnce)
      .def_readwrite("mask", &GravityEngine::mask);
  py::class_<HdapsGravityEngine, GravityEngine, std::shared_ptr<HdapsGravityEngine>>(m, "HdapsGravityEngine")
      .def(py::init<>())
      .def_readwrite("hdapsDir", &HdapsGravityEngine::hdapsDir)
      .def_readwrite("msecUpdate", &HdapsGravityEngine::msecUpdate)
      .def_readwrite("updateThreshold", &HdapsGravityEngine::updateThreshold)
      .def_readwrite("calibrate", &HdapsGravityEngine::calibrate)
      .def_readwrite("calibrated", &HdapsGravityEngine::calibrated)
      .def_readwrite("zeroGravity", &HdapsGravityEngine::zeroGravity)
      .def_readwrite("accel", &HdapsGravityEngine::accel);

  py::class_<IntrCallback, std::shared_ptr<IntrCallback>>(m, "IntrCallback");
  py::class_<SumIntrForcesCb, IntrCallback, std::shared_ptr<SumIntrForcesCb>>(m, "SumIntrForcesCb")
      .def(py::init<>())
      .def_readwrite("force", &SumIntrForcesCb::force)
      .def_readwrite("numIntr", &SumIntrForcesCb::numIntr);
  m.def("set_loop_callbacks", [](InteractionLoop& loop, const std::vector<std::shared_ptr<IntrCallback>>& callbacks) {
    loop.callbacks = callbacks;
  });
}
