// Python bindings of Yade's triaxial test engines built on the TriaxialStressController.
// Compiled into talus._dem; `talus_wrap_triaxial(m)` is called from dem_wrappers.cpp after the
// controllers. The Python API (Yade's names, defaults, files) is talus.dem.control.triaxial.
#include "dem/core/Scene.h"
#include "dem/control/ThreeDTriaxialEngine.h"
#include "dem/control/TriaxialCompressionEngine.h"

#include <pybind11/eigen.h>
#include <pybind11/functional.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

namespace py = pybind11;
using namespace talus::dem;

void talus_wrap_triaxial(py::module_& m)
{
  using C = TriaxialCompressionEngine;
  py::class_<C, TriaxialStressController, std::shared_ptr<C>>(m, "TriaxialCompressionEngine")
      .def(py::init<>())
      .def_readwrite("strainRate", &C::strainRate)
      .def_readwrite("StabilityCriterion", &C::StabilityCriterion)
      .def_readwrite("translationAxis", &C::translationAxis)
      .def_readwrite("autoCompressionActivation", &C::autoCompressionActivation)
      .def_readwrite("autoUnload", &C::autoUnload)
      .def_readwrite("autoStopSimulation", &C::autoStopSimulation)
      .def_readwrite("testEquilibriumInterval", &C::testEquilibriumInterval)
      .def_readwrite("sigmaIsoCompaction", &C::sigmaIsoCompaction)
      .def_readwrite("sigmaLateralConfinement", &C::sigmaLateralConfinement)
      .def_readwrite("Key", &C::Key)
      .def_readwrite("noFiles", &C::noFiles)
      .def_readwrite("frictionAngleDegree", &C::frictionAngleDegree)
      .def_readwrite("epsilonMax", &C::epsilonMax)
      .def_readwrite("fixedPoroCompaction", &C::fixedPoroCompaction)
      .def_readwrite("fixedPorosity", &C::fixedPorosity)
      .def_readwrite("isAxisymetric", &C::isAxisymetric)
      .def_readwrite("currentState", &C::currentState)
      .def_readwrite("previousState", &C::previousState)
      .def_readwrite("currentStrainRate", &C::currentStrainRate)
      .def_readwrite("UnbalancedForce", &C::UnbalancedForce)
      .def_readwrite("previousSigmaIso", &C::previousSigmaIso)
      .def_readwrite("sigma_iso", &C::sigma_iso)
      .def_readwrite("maxStress", &C::maxStress)
      .def_readwrite("uniaxialEpsilonCurr", &C::uniaxialEpsilonCurr)
      .def_readwrite("firstRun", &C::firstRun)
      .def_readwrite("saveHook", &C::saveHook)
      .def_static("stateName", &C::stateName);

  using D = ThreeDTriaxialEngine;
  py::class_<D, TriaxialStressController, std::shared_ptr<D>>(m, "ThreeDTriaxialEngine")
      .def(py::init<>())
      .def_readwrite("strainRate", &D::strainRate)
      .def_readwrite("currentStrainRate", &D::currentStrainRate)
      .def_readwrite("stressControl", &D::stressControl)
      .def_readwrite("strainRateDamping", &D::strainRateDamping)
      .def_readwrite("frictionAngleDegree", &D::frictionAngleDegree)
      .def_readwrite("updateFrictionAngle", &D::updateFrictionAngle)
      .def_readwrite("UnbalancedForce", &D::UnbalancedForce)
      .def_readwrite("Key", &D::Key)
      .def_readwrite("firstRun", &D::firstRun);
}
