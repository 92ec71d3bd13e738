// Python bindings of the quasi-static two-phase flow (flow/twophase/): no logic, only the mapping
// of C++ names to Python. The typed, documented API with Yade's names is
// talus.flow.twophase.TwoPhaseFlowEngine.
#include "flow/pore/PoreFlow.h"
#include "flow/twophase/TwoPhaseFlow.h"

#include <pybind11/eigen.h>
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <vector>

namespace py = pybind11;
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
      .def_readwrite("recursiveInvasion", &TwoPhaseParameters::recursiveInvasion);

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
        if (which == "Pcondition")
          return perPore(t, [](const PoreState& s) { return double(s.imposed); });
        throw py::value_error("unknown pore flag " + which);
      })
      .def("capillaryForces", [](const TwoPhaseFlow& t) {
        const std::vector<Vec3> f = t.capillaryForces();
        Array a({static_cast<py::ssize_t>(f.size()), py::ssize_t{3}});
        auto out = a.mutable_unchecked<2>();
        for (std::size_t i = 0; i < f.size(); ++i)
          for (py::ssize_t d = 0; d < 3; ++d)
            out(static_cast<py::ssize_t>(i), d) = f[i][d];
        return a;
      });
}
