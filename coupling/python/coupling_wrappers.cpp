// Python bindings of coupling/: only the mapping of C++ names to Python. The engine logic
// (hooks, sub-stepping, checks) lives in talus.coupling.foam.
#include "coupling/FoamLink.h"
#include "coupling/ParticleRecords.h"

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <algorithm>
#include <optional>
#include <span>
#include <string>

namespace py = pybind11;
using namespace talus::coupling;

namespace
{
using Array = py::array_t<double, py::array::c_style | py::array::forcecast>;

std::span<const double> values(const Array& a, py::ssize_t columns, const char* name)
{
  const bool ok = columns == 1 ? a.ndim() == 1 : (a.ndim() == 2 && a.shape(1) == columns);
  if (!ok)
    throw py::value_error(std::string(name) + (columns == 1 ? " must be a 1D array" : " must have shape (particles, 3)"));
  return {a.data(), static_cast<std::size_t>(a.size())};
}
} // namespace

PYBIND11_MODULE(_coupling, m)
{
  m.doc() = "CFD-DEM coupling with OpenFOAM over MPI (use talus.coupling)";
  py::class_<FoamSettings>(m, "FoamSettings")
    .def(py::init<>())
    .def_readwrite("solver", &FoamSettings::solver)
    .def_readwrite("caseDir", &FoamSettings::caseDir)
    .def_readwrite("nProcs", &FoamSettings::nProcs)
    .def_readwrite("rhoFluid", &FoamSettings::rhoFluid)
    .def_readwrite("nu", &FoamSettings::nu)
    .def_readwrite("gravity", &FoamSettings::gravity)
    .def_readwrite("couplingInterval", &FoamSettings::couplingInterval)
    .def_readwrite("timeout", &FoamSettings::timeout)
    .def_readwrite("demAcrossProcesses", &FoamSettings::demAcrossProcesses)
    .def_readwrite("environment", &FoamSettings::environment);

  py::class_<FoamLink>(m, "FoamLink")
    .def(py::init<const FoamSettings&, int>(), py::arg("settings"), py::arg("nParticles"))
    .def_property_readonly("fluidDt", &FoamLink::fluidDt)
    .def_property_readonly("dragReynoldsLimit", &FoamLink::dragReynoldsLimit)
    .def_property_readonly("fluidProcs", &FoamLink::fluidProcs)
    .def_property_readonly("nCells", &FoamLink::nCells)
    .def_property_readonly("nParticles", &FoamLink::nParticles)
    .def_property_readonly("running", &FoamLink::running)
    .def("exchange",
         [](FoamLink& link, const Array& pos, const Array& vel, const Array& radius,
            const std::optional<py::array_t<std::int64_t, py::array::c_style | py::array::forcecast>>& indices) {
           const auto n = static_cast<py::ssize_t>(radius.size());
           Array forces({n, py::ssize_t{3}}), fluid({n, py::ssize_t{3}}), beta(n);
           std::span<const std::int64_t> index;
           if (indices)
             index = {indices->data(), static_cast<std::size_t>(indices->size())};
           const double re = link.exchange(values(pos, 3, "positions"), values(vel, 3, "velocities"),
                                           values(radius, 1, "radii"),
                                           {forces.mutable_data(), static_cast<std::size_t>(forces.size())},
                                           {beta.mutable_data(), static_cast<std::size_t>(beta.size())},
                                           {fluid.mutable_data(), static_cast<std::size_t>(fluid.size())}, index);
           return py::make_tuple(forces, re, beta, fluid);
         },
         py::arg("positions"), py::arg("velocities"), py::arg("radii"), py::arg("indices") = py::none())
    .def_property_readonly("boxes", &FoamLink::boxes)
    .def_property_readonly("lastMessages", [](const FoamLink& l) { return l.lastExchange().messages; })
    .def_property_readonly("lastFluidPeers", [](const FoamLink& l) { return l.lastExchange().fluidPeers; })
    .def_property_readonly("lastDemDoubles", [](const FoamLink& l) { return l.lastExchange().demDoubles; })
    .def_property_readonly("lastExchangeSeconds", [](const FoamLink& l) { return l.lastExchange().seconds; })
    .def_property_readonly("lastWaitSeconds", [](const FoamLink& l) { return l.lastExchange().waitSeconds; })
    .def_property_readonly("lastWaitCpuSeconds", [](const FoamLink& l) { return l.lastExchange().waitCpuSeconds; })
    .def_property_readonly("lastFluidExchangeSeconds",
                           [](const FoamLink& l) { return l.lastExchange().fluidExchangeSeconds; })
    .def_property_readonly("lastFluidStepSeconds", [](const FoamLink& l) { return l.lastExchange().fluidStepSeconds; })
    .def_property_readonly("lastFluidExchangeCpuSeconds",
                           [](const FoamLink& l) { return l.lastExchange().fluidExchangeCpuSeconds; })
    .def_property_readonly("lastFluidStepCpuSeconds",
                           [](const FoamLink& l) { return l.lastExchange().fluidStepCpuSeconds; })
    .def("stop", &FoamLink::stop);

  using Ids = py::array_t<std::int64_t, py::array::c_style | py::array::forcecast>;
  py::class_<ParticleRecords>(m, "ParticleRecords")
    .def(py::init<int>(), py::arg("width"))
    .def("store",
         [](ParticleRecords& r, const Ids& ids, const Array& values) {
           r.store({ids.data(), static_cast<std::size_t>(ids.size())},
                   {values.data(), static_cast<std::size_t>(values.size())});
         },
         py::arg("ids"), py::arg("values"))
    .def("hand_over",
         [](ParticleRecords& r, const Ids& ids) { r.handOver({ids.data(), static_cast<std::size_t>(ids.size())}); },
         py::arg("ids"))
    .def_property_readonly("values",
                           [](const ParticleRecords& r) {
                             const auto n = static_cast<py::ssize_t>(r.ids().size());
                             Array a({n, static_cast<py::ssize_t>(r.width())});
                             std::copy(r.values().begin(), r.values().end(), a.mutable_data());
                             return a;
                           })
    .def_property_readonly("lastSent", &ParticleRecords::lastSent);

  // noconvert: the per-body arrays are the scene's own storage, never a converted copy.
  m.def(
    "add_force_change",
    [](const Array& forces, const Array& applied, const py::array_t<std::int64_t, py::array::c_style>& ids,
       py::array_t<double, py::array::c_style>& persistent, py::array_t<double, py::array::c_style>& step) {
      addForceChange(values(forces, 3, "forces"), values(applied, 3, "applied"),
                     {ids.data(), static_cast<std::size_t>(ids.size())},
                     {persistent.mutable_data(), static_cast<std::size_t>(persistent.size())},
                     {step.mutable_data(), static_cast<std::size_t>(step.size())});
    },
    py::arg("forces"), py::arg("applied"), py::arg("ids").noconvert(), py::arg("persistent").noconvert(),
    py::arg("step").noconvert());
  m.def("finalize_mpi", &finalizeMpi);
}
