// Python bindings of the heat conduction between particles (flow/thermal/): no logic, only the
// mapping of C++ names to Python. The typed, documented API with Yade's names is
// talus.flow.thermal.ThermalEngine.
#include "dem/core/Scene.h"
#include "flow/thermal/ConductionSchedule.h"
#include "flow/thermal/ParticleConduction.h"
#include "flow/thermal/PoreHeat.h"
#include "flow/thermal/ThermalExpansion.h"

#include <pybind11/eigen.h>
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

namespace py = pybind11;
using namespace talus::flow::thermal;

namespace
{
using Array = py::array_t<double, py::array::c_style | py::array::forcecast>;

/// A per-body array as numpy (a copy: the owner grows with the scene).
Array copy(const std::vector<double>& v)
{
  return Array(static_cast<py::ssize_t>(v.size()), v.data());
}

/// Replace a per-body array by `values`, one per body.
void assign(std::vector<double>& target, const Array& values, const char* name)
{
  if (values.ndim() != 1 || static_cast<std::size_t>(values.size()) != target.size())
    throw py::value_error(std::string(name) + " needs one value per body (" + std::to_string(target.size()) + ")");
  target.assign(values.data(), values.data() + values.size());
}
} // namespace

void registerThermal(py::module_& m)
{
  py::enum_<ContactConductance>(m, "ContactConductance")
      .value("Radii", ContactConductance::Radii)
      .value("Kern", ContactConductance::Kern);

  py::class_<HeatModel, std::shared_ptr<HeatModel>>(m, "HeatModel")
      .def("stableTimeStep", &HeatModel::stableTimeStep)
      .def("limitingPart", &HeatModel::limitingPart);

  // The scene type is registered by talus._dem (imported first by the talus package).
  py::class_<ParticleConduction, HeatModel, std::shared_ptr<ParticleConduction>>(m, "ParticleConduction")
      .def(py::init([](const std::shared_ptr<talus::dem::Scene>& scene) {
             if (!scene)
               throw std::invalid_argument("ParticleConduction: scene is None");
             return std::make_shared<ParticleConduction>(talus::dem::ParticleExchange(*scene));
           }),
           py::arg("scene"), py::keep_alive<1, 2>())
      .def_readwrite("initialTemperature", &ParticleConduction::initialTemperature)
      .def_readwrite("defaultConductivity", &ParticleConduction::defaultConductivity)
      .def_readwrite("defaultHeatCapacity", &ParticleConduction::defaultHeatCapacity)
      .def_readwrite("particleDensity", &ParticleConduction::particleDensity)
      .def_readwrite("conductance", &ParticleConduction::conductance)
      .def("resize", &ParticleConduction::resize)
      // -1 for a body not covered yet (added since the last step): no boundary holds it
      .def("boundaryAt", [](const ParticleConduction& c, std::size_t i) {
        return i < c.boundary.size() ? static_cast<int>(c.boundary[i]) : -1;
      })
      .def("boundaries", [](const ParticleConduction& c) { return std::vector<int>(c.boundary.begin(), c.boundary.end()); })
      .def("imposeTemperature", &ParticleConduction::imposeTemperature, py::arg("boundary"), py::arg("ids"), py::arg("value"))
      .def("imposeHeatFlux", &ParticleConduction::imposeHeatFlux, py::arg("boundary"), py::arg("ids"), py::arg("rates"))
      .def("heatFlux", [](const ParticleConduction& c, int k) {
        if (k < 0 || k >= kBoundaries)
          throw py::index_error("boundary index must be 0..5");
        return c.heatFlux(k);
      })
      .def("clearBoundaries", &ParticleConduction::clearBoundaries)
      .def("computeRates", &ParticleConduction::computeRates)
      .def("advance", &ParticleConduction::advance, py::arg("dt"))
      .def("limitingBody", &ParticleConduction::limitingBody)
      .def("heatCapacityOf", &ParticleConduction::heatCapacityOf, py::arg("id"))
      .def("boundaryFlux", [](const ParticleConduction& c) { return c.boundaryFlux(); })
      .def("boundaryHeat", [](const ParticleConduction& c) { return c.boundaryHeat(); })
      .def("setBoundaryHeat", [](ParticleConduction& c, const std::array<double, kBoundaries>& v) { c.boundaryHeat() = v; });

  py::class_<FluidHeatParameters>(m, "FluidHeatParameters")
      .def(py::init<>())
      .def_readwrite("fluidK", &FluidHeatParameters::fluidK)
      .def_readwrite("fluidCp", &FluidHeatParameters::fluidCp)
      .def_readwrite("fluidRho", &FluidHeatParameters::fluidRho)
      .def_readwrite("nusseltK", &FluidHeatParameters::nusseltK)
      .def_readwrite("poreReynolds", &FluidHeatParameters::poreReynolds)
      .def_readwrite("porosity", &FluidHeatParameters::porosity)
      .def_readwrite("advection", &FluidHeatParameters::advection)
      .def_readwrite("fluidConduction", &FluidHeatParameters::fluidConduction)
      .def_readwrite("ignoreFictitious", &FluidHeatParameters::ignoreFictitious)
      .def_readwrite("areaFactor", &FluidHeatParameters::areaFactor)
      .def_readwrite("minimumDistance", &FluidHeatParameters::minimumDistance)
      .def_readwrite("thermalPorosity", &FluidHeatParameters::thermalPorosity);

  py::class_<PoreHeat, HeatModel, std::shared_ptr<PoreHeat>>(m, "PoreHeat")
      .def(py::init([](const std::shared_ptr<ParticleConduction>& particles, const std::shared_ptr<talus::flow::pore::PoreFlow>& flow) {
             if (!particles || !flow)
               throw std::invalid_argument("PoreHeat: particles or flow is None");
             return std::make_shared<PoreHeat>(*particles, flow);
           }),
           py::arg("particles"), py::arg("flow"), py::keep_alive<1, 2>())
      .def_readwrite("params", &PoreHeat::params)
      .def_readwrite("initialTemperature", &PoreHeat::initialTemperature)
      .def("setBoundary", &PoreHeat::setBoundary, py::arg("boundary"), py::arg("held"), py::arg("value"))
      .def("sync", &PoreHeat::sync)
      .def("temperatures", [](PoreHeat& h) {
        h.sync();
        return copy(h.temperatures());
      })
      .def("setTemperature", &PoreHeat::setTemperature, py::arg("pore"), py::arg("value"))
      .def("poreNusseltK", [](const PoreHeat& h) { return copy(h.poreNusseltK()); })
      .def("resetPoreNusselt", &PoreHeat::resetPoreNusselt)
      .def("temperatureAt", &PoreHeat::temperatureAt, py::arg("x"));

  py::class_<ExpansionParameters>(m, "ExpansionParameters")
      .def(py::init<>())
      .def_readwrite("particles", &ExpansionParameters::particles)
      .def_readwrite("solidVolume", &ExpansionParameters::solidVolume)
      .def_readwrite("fluid", &ExpansionParameters::fluid)
      .def_readwrite("fluidBeta", &ExpansionParameters::fluidBeta)
      .def_readwrite("porosityFactor", &ExpansionParameters::porosityFactor);

  py::class_<ThermalExpansion, std::shared_ptr<ThermalExpansion>>(m, "ThermalExpansion")
      .def(py::init([](const std::shared_ptr<ParticleConduction>& particles, const std::shared_ptr<talus::dem::Scene>& scene) {
             if (!particles || !scene)
               throw std::invalid_argument("ThermalExpansion: particles or scene is None");
             return std::make_shared<ThermalExpansion>(*particles, talus::dem::ParticleExchange(*scene));
           }),
           py::arg("particles"), py::arg("scene"), py::keep_alive<1, 2>(), py::keep_alive<1, 3>())
      .def_readwrite("params", &ThermalExpansion::params)
      .def_readwrite("defaultAlpha", &ThermalExpansion::defaultAlpha)
      .def("resize", &ThermalExpansion::resize)
      .def("marks", [](const ThermalExpansion& e) { return copy(e.sphereMark); })
      .def("setMarks", [](ThermalExpansion& e, const Array& v) { assign(e.sphereMark, v, "marks"); })
      .def("mark", [](ThermalExpansion& e, const std::shared_ptr<PoreHeat>& fluid) { e.mark(fluid.get()); },
           py::arg("fluid").none(true))
      .def("apply",
           [](ThermalExpansion& e, double span, const std::shared_ptr<PoreHeat>& fluid,
              const std::shared_ptr<talus::flow::pore::PoreFlow>& flow) { e.apply(span, fluid.get(), flow.get()); },
           py::arg("span"), py::arg("fluid").none(true), py::arg("flow").none(true))
      .def("lastVolumeRates", [](const ThermalExpansion& e) { return copy(e.lastVolumeRates()); });

  py::class_<ConductionSchedule::Counters>(m, "ConductionCounters")
      .def(py::init<>())
      .def_readwrite("runs", &ConductionSchedule::Counters::runs)
      .def_readwrite("sinceRun", &ConductionSchedule::Counters::sinceRun)
      .def_readwrite("period", &ConductionSchedule::Counters::period)
      .def_readwrite("timeSinceRun", &ConductionSchedule::Counters::timeSinceRun)
      .def_readwrite("thermalDT", &ConductionSchedule::Counters::thermalDT)
      .def_readwrite("maxTimeStep", &ConductionSchedule::Counters::maxTimeStep);

  py::class_<ConductionSchedule>(m, "ConductionSchedule")
      .def(py::init<>())
      .def_readwrite("tsSafetyFactor", &ConductionSchedule::tsSafetyFactor)
      .def("step", &ConductionSchedule::step, py::arg("model"), py::arg("dt"))
      .def("conductionIterPeriod", &ConductionSchedule::conductionIterPeriod)
      .def("thermalDT", &ConductionSchedule::thermalDT)
      .def("maxTimeStep", &ConductionSchedule::maxTimeStep)
      .def("substeps", &ConductionSchedule::substeps)
      .def("counters", &ConductionSchedule::counters)
      .def("setCounters", &ConductionSchedule::setCounters);
}
