// Python bindings of flow/: no logic here, only the mapping of C++ names to Python. Defaults,
// docstrings, Yade's option numbers and attribute names live in the talus.flow Python layer.
#include "flow/HydroForce.h"
#include "flow/VansFluid.h"
#include "flow/VansParameters.h"
#include "flow/WallFriction.h"

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <cstdint>
#include <span>
#include <string>

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

using IdArray = py::array_t<std::int64_t, py::array::c_style | py::array::forcecast>;

std::span<const std::int64_t> idSpan(const IdArray& a)
{
  if (a.ndim() != 1)
    throw py::value_error("ids must be a one-dimensional array of body ids");
  return {a.data(), static_cast<std::size_t>(a.size())};
}

/// A (bodies, 3) array of the particle exchange interface, read without copying.
std::span<const double> rows3(const Array& a, const char* name)
{
  if (a.ndim() != 2 || a.shape(1) != 3)
    throw py::value_error(std::string(name) + " must be an array of shape (bodies, 3)");
  return {a.data(), static_cast<std::size_t>(a.size())};
}

ParticleArrays particles(const Array& pos, const Array& vel, const Array& radius)
{
  ParticleArrays p{rows3(pos, "positions"), rows3(vel, "velocities"), span(radius)};
  if (p.positions.size() != 3 * p.radii.size() || p.velocities.size() != 3 * p.radii.size())
    throw py::value_error("positions, velocities and radii must describe the same bodies");
  return p;
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
  void registerThermal(py::module_&); registerThermal(m); // heat conduction: thermal_wrappers.cpp
  void registerTwoPhase(py::module_&); registerTwoPhase(m); // two-phase flow: twophase_wrappers.cpp
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

  py::class_<HydroForceParameters>(m, "HydroForceParameters")
      .def(py::init<>())
      .def_readwrite("nCell", &HydroForceParameters::nCell)
      .def_readwrite("deltaZ", &HydroForceParameters::deltaZ)
      .def_readwrite("zRef", &HydroForceParameters::zRef)
      .def_readwrite("densFluid", &HydroForceParameters::densFluid)
      .def_readwrite("viscoDyn", &HydroForceParameters::viscoDyn)
      .def_readwrite("expoRZ", &HydroForceParameters::expoRZ)
      .def_readwrite("lift", &HydroForceParameters::lift)
      .def_readwrite("Cl", &HydroForceParameters::Cl)
      .def_readwrite("steadyFlow", &HydroForceParameters::steadyFlow)
      .def_readwrite("gravity", &HydroForceParameters::gravity)
      .def_readwrite("vCell", &HydroForceParameters::vCell)
      .def_readwrite("periodZ", &HydroForceParameters::periodZ)
      .def_readwrite("ignoreOutside", &HydroForceParameters::ignoreOutside)
      .def_readwrite("velFluct", &HydroForceParameters::velFluct)
      .def_readwrite("bedElevation", &HydroForceParameters::bedElevation)
      .def_readwrite("unCorrelatedFluctuations", &HydroForceParameters::unCorrelatedFluctuations)
      .def_readwrite("kappa", &HydroForceParameters::kappa)
      .def("validate", &HydroForceParameters::validate);

  py::class_<HydroForce>(m, "HydroForce")
      .def(py::init<const HydroForceParameters&>())
      .def("parameters", &HydroForce::parameters)
      .def("setParameters", &HydroForce::setParameters)
      .def("setVxFluid", [](HydroForce& h, const Array& v) { h.setVxFluid(span(v)); })
      .def("setPhiPart", [](HydroForce& h, const Array& v) { h.setPhiPart(span(v)); })
      .def("setReynoldStresses", [](HydroForce& h, const Array& v) { h.setReynoldStresses(span(v)); })
      .def("vxFluid", [](const HydroForce& h) { return array(h.vxFluid()); })
      .def("phiPart", [](const HydroForce& h) { return array(h.phiPart()); })
      .def("reynoldStresses", [](const HydroForce& h) { return array(h.reynoldStresses()); })
      .def("action",
           [](HydroForce& h, const Array& pos, const Array& vel, const Array& radius, py::array_t<double>& forces,
              const IdArray& ids, double dt) {
             // The forces are written in place: they must be the scene's own contiguous array.
             if (forces.ndim() != 2 || forces.shape(1) != 3 || !(forces.flags() & py::array::c_style)
                 || !forces.writeable())
               throw py::value_error("forces must be a writable C-contiguous array of shape (bodies, 3)");
             h.action(particles(pos, vel, radius), idSpan(ids),
                      {forces.mutable_data(), static_cast<std::size_t>(forces.size())}, dt);
           })
      .def("force", [](const HydroForce& h, const Array& pos, const Array& vel, const Array& radius,
                       std::int64_t id) { return h.force(particles(pos, vel, radius), id); })
      .def("averageProfile",
           [](const HydroForce& h, const Array& pos, const Array& vel, const Array& radius, const IdArray& ids) {
             const SolidProfile s = h.averageProfile(particles(pos, vel, radius), idSpan(ids));
             py::dict d;
             d["phiPart"] = array(s.phiPart);
             d["vxPart"] = array(s.vxPart);
             d["vyPart"] = array(s.vyPart);
             d["vzPart"] = array(s.vzPart);
             d["averageDrag"] = array(s.averageDrag);
             return d;
           })
      .def("turbulentFluctuation",
           [](HydroForce& h, const Array& pos, const Array& vel, const Array& radius, const IdArray& ids) {
             h.turbulentFluctuation(particles(pos, vel, radius), idSpan(ids));
           })
      .def("fluctuations", [](const HydroForce& h) { return array(h.fluctuations()); })
      .def("fluctuationLife", [](const HydroForce& h) { return array(h.fluctuationLife()); })
      .def("seed", &HydroForce::seed)
      .def_static("sliceVolume", &HydroForce::sliceVolume);

  m.attr("oscillationThreshold") = VansFluid::oscillationThreshold;
  m.def("wallFrictionFactor", &wallFrictionFactor);
}
