// Python bindings of flow/: no logic here, only the mapping of C++ names to Python. Defaults,
// docstrings, Yade's option numbers and attribute names live in the talus.flow Python layer.
#include "flow/VansFluid.h"
#include "flow/VansParameters.h"
#include "flow/WallFriction.h"

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <span>

namespace py = pybind11;
using namespace talus::flow;

namespace
{
using Array = py::array_t<double, py::array::c_style | py::array::forcecast>;

std::span<const double> span(const Array& a)
{
  if (a.ndim() != 1)
    throw py::value_error("expected a one-dimensional array of floats");
  return {a.data(), static_cast<std::size_t>(a.size())};
}

Array array(std::span<const double> v)
{
  return Array(static_cast<py::ssize_t>(v.size()), v.data());  // a copy: the owner may resize
}

template <void (VansFluid::*set)(std::span<const double>)>
void setProfile(VansFluid& fluid, const Array& values)
{
  (fluid.*set)(span(values));
}
} // namespace

PYBIND11_MODULE(_flow, m)
{
  void registerPoreFlow(py::module_&); registerPoreFlow(m); // pore flow: pore_wrappers.cpp
  m.doc() = "Compiled core of talus.flow (use the talus package, not this module)";

  py::enum_<MixingLengthModel>(m, "MixingLengthModel")
      .value("Prandtl", MixingLengthModel::Prandtl)
      .value("FreeSurface", MixingLengthModel::FreeSurface)
      .value("LiSawamoto", MixingLengthModel::LiSawamoto);
  py::enum_<EffectiveViscosityModel>(m, "EffectiveViscosityModel")
      .value("Fluid", EffectiveViscosityModel::Fluid)
      .value("Einstein", EffectiveViscosityModel::Einstein)
      .value("PowerLaw", EffectiveViscosityModel::PowerLaw);
  py::enum_<TopBoundary>(m, "TopBoundary")
      .value("ImposedVelocity", TopBoundary::ImposedVelocity)
      .value("FreeSurface", TopBoundary::FreeSurface);

  py::class_<VansParameters>(m, "VansParameters")
      .def(py::init<>())
      .def_readwrite("nCell", &VansParameters::nCell)
      .def_readwrite("deltaZ", &VansParameters::deltaZ)
      .def_readwrite("densFluid", &VansParameters::densFluid)
      .def_readwrite("viscoDyn", &VansParameters::viscoDyn)
      .def_readwrite("gravityX", &VansParameters::gravityX)
      .def_readwrite("dpdx", &VansParameters::dpdx)
      .def_readwrite("turbulence", &VansParameters::turbulence)
      .def_readwrite("mixingLength", &VansParameters::mixingLength)
      .def_readwrite("kappa", &VansParameters::kappa)
      .def_readwrite("phiMax", &VansParameters::phiMax)
      .def_readwrite("viscousSubLayer", &VansParameters::viscousSubLayer)
      .def_readwrite("effectiveViscosity", &VansParameters::effectiveViscosity)
      .def_readwrite("topBoundary", &VansParameters::topBoundary)
      .def_readwrite("uTop", &VansParameters::uTop)
      .def_readwrite("fluidWallFriction", &VansParameters::fluidWallFriction)
      .def_readwrite("channelWidth", &VansParameters::channelWidth)
      .def_readwrite("fluidFrictionCoef", &VansParameters::fluidFrictionCoef)
      .def_readwrite("radiusPart", &VansParameters::radiusPart)
      .def("validate", &VansParameters::validate)
      .def("fluidHeight", &VansParameters::fluidHeight);

  py::class_<VansFluid>(m, "VansFluid")
      .def(py::init<const VansParameters&>())
      .def("parameters", &VansFluid::parameters)
      .def("setParameters", &VansFluid::setParameters)
      .def("initialization", &VansFluid::initialization)
      .def("setPhiPart", &setProfile<&VansFluid::setPhiPart>)
      .def("setVxPart", &setProfile<&VansFluid::setVxPart>)
      .def("setAverageDrag", &setProfile<&VansFluid::setAverageDrag>)
      .def("setVxFluid", &setProfile<&VansFluid::setVxFluid>)
      .def("phiPart", [](const VansFluid& f) { return array(f.phiPart()); })
      .def("vxPart", [](const VansFluid& f) { return array(f.vxPart()); })
      .def("averageDrag", [](const VansFluid& f) { return array(f.averageDrag()); })
      .def("vxFluid", [](const VansFluid& f) { return array(f.vxFluid()); })
      .def("reynoldStresses", [](const VansFluid& f) { return array(f.reynoldStresses()); })
      .def("turbulentViscosity", [](const VansFluid& f) { return array(f.turbulentViscosity()); })
      .def("taufsi", [](const VansFluid& f) { return array(f.taufsi()); })
      .def("mixingLength", [](const VansFluid& f) { return array(f.mixingLength()); })
      .def("clippedDragCells", &VansFluid::clippedDragCells)
      .def("lastStepCount", &VansFluid::lastStepCount)
      .def("lastStepChange", &VansFluid::lastStepChange)
      .def("oscillating", &VansFluid::oscillating)
      .def("velocityNodeElevations", &VansFluid::velocityNodeElevations)
      .def("meshNodeElevations", &VansFluid::meshNodeElevations)
      // The resolution releases the GIL: it touches no Python object and can take seconds.
      .def("fluidResolution", &VansFluid::fluidResolution, py::call_guard<py::gil_scoped_release>());

  m.attr("oscillationThreshold") = VansFluid::oscillationThreshold;
  m.def("wallFrictionFactor", &wallFrictionFactor);
}
