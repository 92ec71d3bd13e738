// Python bindings of dem/SpherePack (Yade's SpherePack.makeCloud). Compiled into talus._dem;
// `talus_wrap_pack(m)` is called from dem_wrappers.cpp. The Python API is talus.dem.packing.pack.
#include "dem/shapes/SpherePack.h"

#include <pybind11/eigen.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

namespace py = pybind11;
using namespace talus::dem;

void talus_wrap_pack(py::module_& m)
{
  py::class_<SpherePack>(m, "SpherePack")
      .def(py::init<>())
      .def_readwrite("centers", &SpherePack::centers)
      .def_readwrite("radii", &SpherePack::radii)
      .def_readwrite("hSize", &SpherePack::hSize)
      .def_readwrite("appliedPsdScaling", &SpherePack::appliedPsdScaling)
      .def_readonly_static("maxSpheres", &SpherePack::maxSpheres)
      .def("makeCloud", &SpherePack::makeCloud, py::call_guard<py::gil_scoped_release>());
}
