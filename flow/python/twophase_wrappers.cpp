// Python bindings of the quasi-static two-phase flow (flow/twophase/): no logic, only the mapping
// of C++ names to Python. The typed, documented API with Yade's names is
// talus.flow.twophase.TwoPhaseFlowEngine.
#include "flow/pore/PoreFlow.h"
#include "flow/twophase/TwoPhaseFlow.h"
#include "flow/python/ArrayRows.h"

#include <pybind11/eigen.h>
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <vector>

namespace py = pybind11;
using talus::flow::python::rows;
using namespace talus::flow::twophase;
using talus::flow::pore::PoreFlow;
using talus::flow::pore::Vec3;

namespace
{
using Array = py::array_t<double, py::array::c_style | py::array::forcecast>;

Array copy(const std::vector<double>& v)
{
  return Array(static_cast<py::ssize_t>(v.size()), v.data());
}

/// A per-pore flag or value of the pore states as numpy.
template <class F>
Array perPore(const TwoPhaseFlow& t, F f)
{
  std::vector<double> v(t.pores().size());
  for (std::size_t c = 0; c < v.size(); ++c)
    v[c] = f(t.pores()[c]);
  return copy(v);
}
} // namespace

void registerTwoPhase(py::module_& m)
{
  py::class_<TwoPhaseParameters>(m, "TwoPhaseParameters")
      .def(py::init<>())
      .def_readwrite("surfaceTension", &TwoPhaseParameters::surfaceTension)
      .def_readwrite("entryPressureMethod", &TwoPhaseParameters::entryPressureMethod)
      .def_readwrite("isPhaseTrapped", &TwoPhaseParameters::isPhaseTrapped)
      .def_readwrite("isInvadeBoundary", &TwoPhaseParameters::isInvadeBoundary)
      .def_readwrite("drainageFirst", &TwoPhaseParameters::drainageFirst)
      .def_readwrite("isDrainageActivated", &TwoPhaseParameters::isDrainageActivated)
      .def_readwrite("isImbibitionActivated", &TwoPhaseParameters::isImbibitionActivated)
      .def_readwrite("recursiveInvasion", &TwoPhaseParameters::recursiveInvasion)
      .def_readwrite("isCellLabelActivated", &TwoPhaseParameters::isCellLabelActivated)
      .def_readwrite("useFastInvasion", &TwoPhaseParameters::useFastInvasion);

  py::class_<Interface>(m, "PhaseInterface")
      .def_readonly("inner", &Interface::inner)
      .def_readonly("outer", &Interface::outer)
      .def_readonly("area", &Interface::area)
      .def_readonly("facet", &Interface::facet)
      .def_readwrite("volume", &Interface::volume)
      .def_readwrite("capillaryPressure", &Interface::capillaryPressure);

  m.def("mspRadius", &mspRadius);
  m.def("inscribedRadius", &inscribedRadius);

  py::class_<TwoPhaseFlow>(m, "TwoPhaseFlow")
      .def(py::init<>())
      .def("initialize", [](TwoPhaseFlow& t, const PoreFlow& flow, const TwoPhaseParameters& params) {
             t.initialize(flow.network(), params, flow.params.bndCondIsPressure, flow.params.bndCondValue);
           })
      .def("invasion", &TwoPhaseFlow::invasion)
      .def("saturation", &TwoPhaseFlow::saturation)
      .def("minDrainagePc", &TwoPhaseFlow::minDrainagePc)
      .def("maxImbibitionPc", &TwoPhaseFlow::maxImbibitionPc)
      .def("initialized", &TwoPhaseFlow::initialized)
      .def("setParameters", &TwoPhaseFlow::setParameters)
      .def("throatRadii", [](const TwoPhaseFlow& t) { return copy(t.throatRadii()); })
      .def("bodyRadii", [](const TwoPhaseFlow& t) { return copy(t.bodyRadii()); })
      .def("bodyVolumes", [](const TwoPhaseFlow& t) { return copy(t.bodyVolumes()); })
      .def("pressures", [](const TwoPhaseFlow& t) { return copy(t.pressures()); })
      .def("saturations", [](const TwoPhaseFlow& t) { return perPore(t, [](const PoreState& s) { return s.saturation; }); })
      .def("flags", [](const TwoPhaseFlow& t, const std::string& which) {
        // the per-pore flags by Yade's names (getCellIsWRes ...), as 0/1
        if (which == "isWRes")
          return perPore(t, [](const PoreState& s) { return double(s.wReservoir); });
        if (which == "isNWRes")
          return perPore(t, [](const PoreState& s) { return double(s.nwReservoir); });
        if (which == "isTrapW")
          return perPore(t, [](const PoreState& s) { return double(s.trappedW); });
        if (which == "isTrapNW")
          return perPore(t, [](const PoreState& s) { return double(s.trappedNW); });
        if (which == "hasInterface")
          return perPore(t, [](const PoreState& s) { return double(s.hasInterface); });
        if (which == "Pcondition")
          return perPore(t, [](const PoreState& s) { return double(s.imposed); });
        throw py::value_error("unknown pore flag " + which);
      })
      .def("poreCount", [](const TwoPhaseFlow& t) { return t.pores().size(); })
      .def("labels", [](const TwoPhaseFlow& t) { return t.labels(); })
      .def("label", [](const TwoPhaseFlow& t, std::size_t i) { return t.labels().at(i); })
      .def("barycentres", [](const TwoPhaseFlow& t) { return rows(t.barycentres()); })
      .def("updateCellLabels", &TwoPhaseFlow::updateCellLabels)
      .def("clusterCount", [](const TwoPhaseFlow& t) { return t.clusters().size(); })
      .def("cluster", [](const TwoPhaseFlow& t, int k) {
        // the scalars and pores of cluster k; its interfaces through interface()
        if (k < 0 || static_cast<std::size_t>(k) >= t.clusters().size())
          throw py::index_error("cluster index " + std::to_string(k) + " out of range");
        const PhaseCluster& c = t.clusters()[static_cast<std::size_t>(k)];
        return py::dict(py::arg("label") = c.label, py::arg("volume") = c.volume, py::arg("entryRadius") = c.entryRadius,
                        py::arg("entryPore") = c.entryPore, py::arg("interfacialArea") = c.interfacialArea,
                        py::arg("pores") = c.pores, py::arg("nInterfaces") = c.interfaces.size());
      })
      .def("interfaces", [](const TwoPhaseFlow& t, int k, int cellId) {
        // Yade's getInterfaces() rows (inner, outer, area, rank), those of inner pore cellId (-1: all),
        // built here: scripts call it every step
        if (k < 0 || static_cast<std::size_t>(k) >= t.clusters().size())
          throw py::index_error("cluster index " + std::to_string(k) + " out of range");
        const std::vector<Interface>& list = t.clusters()[static_cast<std::size_t>(k)].interfaces;
        py::list rows;
        for (std::size_t rank = 0; rank < list.size(); ++rank)
          if (cellId == -1 || list[rank].inner == cellId)
            rows.append(py::make_tuple(list[rank].inner, list[rank].outer, list[rank].area, rank));
        return rows;
      })
      .def("interface", py::overload_cast<int, int>(&TwoPhaseFlow::interface), py::return_value_policy::reference_internal)
      // the meniscus volume, read and set once per interface and step by injection scripts
      .def("interfaceVolume", [](const TwoPhaseFlow& t, int k, int i) { return t.interface(k, i).volume; })
      .def("setInterfaceVolume", [](TwoPhaseFlow& t, int k, int i, double v) { t.interface(k, i).volume = v; })
      .def("outvadePore", &TwoPhaseFlow::outvadePore)
      .def("invadePore", &TwoPhaseFlow::invadePore)
      .def("invadePoreFast", &TwoPhaseFlow::invadePoreFast)
      .def("setHasInterface", &TwoPhaseFlow::setHasInterface)
      .def("updatePressure", &TwoPhaseFlow::updatePressure)
      .def("setSaturation", &TwoPhaseFlow::setSaturation)
      .def("setReservoir", &TwoPhaseFlow::setReservoir)
      .def("setBodyRadius", &TwoPhaseFlow::setBodyRadius)
      .def("setThroatRadius", &TwoPhaseFlow::setThroatRadius)
      .def("solveClusterPressure", &TwoPhaseFlow::solveClusterPressure)
      .def("interfaceConductance", &TwoPhaseFlow::interfaceConductance)
      .def("interfaceFlux", &TwoPhaseFlow::interfaceFlux)
      .def("updateInterfaceVolumes", &TwoPhaseFlow::updateInterfaceVolumes)
      .def("boundaryFlux", &TwoPhaseFlow::boundaryFlux)
      .def("poreFlux", &TwoPhaseFlow::poreFlux)
      .def("capillaryForces", [](const TwoPhaseFlow& t) { return rows(t.capillaryForces()); });
}
