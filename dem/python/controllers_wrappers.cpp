// Python bindings of the time stepper and the stress/strain controllers. Compiled into
// talus._dem; `talus_wrap_controllers(m)` is called from dem_wrappers.cpp. The Python API
// (Yade's names, defaults, doneHook strings) is talus.dem.control.controllers.
#include "dem/engines/GlobalStiffnessTimeStepper.h"
#include "dem/control/Peri3dController.h"
#include "dem/control/PeriIsoCompressor.h"
#include "dem/control/PeriTriaxController.h"
#include "dem/impose/SampleOperations.h"
#include "dem/core/Scene.h"
#include "dem/control/TriaxialStressController.h"

#include <pybind11/eigen.h>
#include <pybind11/functional.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

namespace py = pybind11;
using namespace talus::dem;

void talus_wrap_controllers(py::module_& m)
{
  py::class_<GlobalStiffnessTimeStepper, Engine, std::shared_ptr<GlobalStiffnessTimeStepper>>(m, "GlobalStiffnessTimeStepper")
      .def(py::init<>())
      .def_readwrite("active", &GlobalStiffnessTimeStepper::active)
      .def_readwrite("viscEl", &GlobalStiffnessTimeStepper::viscEl)
      .def_readwrite("timestepSafetyCoefficient", &GlobalStiffnessTimeStepper::timestepSafetyCoefficient)
      .def_readwrite("defaultDt", &GlobalStiffnessTimeStepper::defaultDt)
      .def_readwrite("maxDt", &GlobalStiffnessTimeStepper::maxDt)
      .def_readwrite("timeStepUpdateInterval", &GlobalStiffnessTimeStepper::timeStepUpdateInterval)
      .def_readwrite("previousDt", &GlobalStiffnessTimeStepper::previousDt)
      .def_readwrite("computedOnce", &GlobalStiffnessTimeStepper::computedOnce)
      .def("stiffnessTimeStep", &GlobalStiffnessTimeStepper::stiffnessTimeStep);
  m.def("rayleighWaveTimeStep", &rayleighWaveTimeStep);
  m.def("growParticles", &growParticles);
  m.def("setContactFriction", &setContactFriction);

  py::class_<PeriTriaxController, Engine, std::shared_ptr<PeriTriaxController>>(m, "PeriTriaxController")
      .def(py::init<>())
      .def_readwrite("goal", &PeriTriaxController::goal)
      .def_readwrite("stressMask", &PeriTriaxController::stressMask)
      .def_readwrite("maxStrainRate", &PeriTriaxController::maxStrainRate)
      .def_readwrite("maxUnbalanced", &PeriTriaxController::maxUnbalanced)
      .def_readwrite("absStressTol", &PeriTriaxController::absStressTol)
      .def_readwrite("relStressTol", &PeriTriaxController::relStressTol)
      .def_readwrite("growDamping", &PeriTriaxController::growDamping)
      .def_readwrite("globUpdate", &PeriTriaxController::globUpdate)
      .def_readwrite("dynCell", &PeriTriaxController::dynCell)
      .def_readwrite("mass", &PeriTriaxController::mass)
      .def_readwrite("doneHook", &PeriTriaxController::doneHook)
      .def_readwrite("stress", &PeriTriaxController::stress)
      .def_readwrite("strain", &PeriTriaxController::strain)
      .def_readwrite("strainRate", &PeriTriaxController::strainRate)
      .def_readwrite("stiff", &PeriTriaxController::stiff)
      .def_readwrite("stressTensor", &PeriTriaxController::stressTensor)
      .def_readwrite("prevGrow", &PeriTriaxController::prevGrow)
      .def_readwrite("maxBodySpan", &PeriTriaxController::maxBodySpan)
      .def_readwrite("currUnbalanced", &PeriTriaxController::currUnbalanced)
      .def_readwrite("externalWork", &PeriTriaxController::externalWork);

  using P3 = Peri3dController;
  py::class_<P3, Engine, std::shared_ptr<P3>>(m, "Peri3dController")
      .def(py::init<>())
      .def_readwrite("goal", &P3::goal)
      .def_readwrite("stressMask", &P3::stressMask)
      .def_readwrite("nSteps", &P3::nSteps)
      .def_readwrite("maxStrainRate", &P3::maxStrainRate)
      .def_readwrite("maxStrain", &P3::maxStrain)
      .def_readwrite("mod", &P3::mod)
      .def_readwrite("youngEstimation", &P3::youngEstimation)
      .def_readwrite("poissonEstimation", &P3::poissonEstimation)
      .def_readwrite("paths", &P3::paths)
      .def_readwrite("doneHook", &P3::doneHook)
      .def_readwrite("progress", &P3::progress)
      .def_readwrite("stress", &P3::stress)
      .def_readwrite("strain", &P3::strain)
      .def_readwrite("strainRate", &P3::strainRate)
      .def_readwrite("stressRate", &P3::stressRate)
      .def_readwrite("stressIdeal", &P3::stressIdeal)
      .def_readwrite("stressGoal", &P3::stressGoal)
      .def_readwrite("strainGoal", &P3::strainGoal)
      .def_readwrite("ps", &P3::ps)
      .def_readwrite("pe", &P3::pe)
      .def_readwrite("pathSizes", &P3::pathSizes)
      .def_readwrite("pathsCounter", &P3::pathsCounter)
      .def_readwrite("lenPs", &P3::lenPs)
      .def_readwrite("lenPe", &P3::lenPe);

  py::class_<PeriIsoCompressor, Engine, std::shared_ptr<PeriIsoCompressor>>(m, "PeriIsoCompressor")
      .def(py::init<>())
      .def_readwrite("stresses", &PeriIsoCompressor::stresses)
      .def_readwrite("charLen", &PeriIsoCompressor::charLen)
      .def_readwrite("maxSpan", &PeriIsoCompressor::maxSpan)
      .def_readwrite("maxUnbalanced", &PeriIsoCompressor::maxUnbalanced)
      .def_readwrite("globalUpdateInt", &PeriIsoCompressor::globalUpdateInt)
      .def_readwrite("maxDisplPerStep", &PeriIsoCompressor::maxDisplPerStep)
      .def_readwrite("keepProportions", &PeriIsoCompressor::keepProportions)
      .def_readwrite("doneHook", &PeriIsoCompressor::doneHook)
      .def_readwrite("state", &PeriIsoCompressor::state)
      .def_readwrite("sigma", &PeriIsoCompressor::sigma)
      .def_readwrite("avgStiffness", &PeriIsoCompressor::avgStiffness)
      .def_readwrite("currUnbalanced", &PeriIsoCompressor::currUnbalanced);

  using T = TriaxialStressController;
  py::class_<T, Engine, std::shared_ptr<T>>(m, "TriaxialStressController")
      .def(py::init<>())
      .def_readwrite("wallIds", &T::wallIds)
      .def_readwrite("wallActivated", &T::wallActivated)
      .def_readwrite("goal1", &T::goal1)
      .def_readwrite("goal2", &T::goal2)
      .def_readwrite("goal3", &T::goal3)
      .def_readwrite("stressMask", &T::stressMask)
      .def_readwrite("internalCompaction", &T::internalCompaction)
      .def_readwrite("maxMultiplier", &T::maxMultiplier)
      .def_readwrite("finalMaxMultiplier", &T::finalMaxMultiplier)
      .def_readwrite("max_vel", &T::max_vel)
      .def_readwrite("stressDamping", &T::stressDamping)
      .def_readwrite("strainDamping", &T::strainDamping)
      .def_readwrite("thickness", &T::thickness)
      .def_readwrite("stiffnessUpdateInterval", &T::stiffnessUpdateInterval)
      .def_readwrite("radiusControlInterval", &T::radiusControlInterval)
      .def_readwrite("computeStressStrainInterval", &T::computeStressStrainInterval)
      .def_readwrite("updatePorosity", &T::updatePorosity)
      .def_readwrite("stressVectors", &T::stress)
      .def_readwrite("force", &T::force)
      .def_readwrite("stiffness", &T::stiffness)
      .def_readwrite("previousTranslation", &T::previousTranslation)
      .def_readwrite("strain", &T::strain)
      .def_readwrite("volumetricStrain", &T::volumetricStrain)
      .def_readwrite("meanStress", &T::meanStress)
      .def_readwrite("porosity", &T::porosity)
      .def_readwrite("boxVolume", &T::boxVolume)
      .def_readwrite("particlesVolume", &T::particlesVolume)
      .def_readwrite("width", &T::width)
      .def_readwrite("height", &T::height)
      .def_readwrite("depth", &T::depth)
      .def_readwrite("width0", &T::width0)
      .def_readwrite("height0", &T::height0)
      .def_readwrite("depth0", &T::depth0)
      .def_readwrite("externalWork", &T::externalWork)
      .def_readwrite("previousStress", &T::previousStress)
      .def_readwrite("previousMultiplier", &T::previousMultiplier)
      .def_readwrite("first", &T::first)
      .def("computeStressStrain", &T::computeStressStrain);
}
