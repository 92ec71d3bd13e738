// Python bindings of the contact models' parameters and state and of the energy tracker.
// Compiled into talus._dem; `talus_wrap_laws(m)` is called from dem_wrappers.cpp. The Python
// API (Yade's functor classes, O.energy) is talus.dem.step.engines and talus.dem.analysis.energy.
#include "dem/laws/ContactLaw.h"
#include "dem/measure/Energy.h"
#include "dem/core/Scene.h"

#include <pybind11/eigen.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <algorithm>
#include <optional>
#include <string>
#include <tuple>
#include <type_traits>

namespace py = pybind11;
using namespace talus::dem;

/// Add the contact-law and energy functions to the compiled module talus._dem.
void talus_wrap_laws(py::module_& m);

void talus_wrap_laws(py::module_& m)
{
  m.def("law_set_parameter", [](ContactLaw& law, const std::string& name, double value) { law.setParameter(name, value); });
  m.def("law_parameter", [](const ContactLaw& law, const std::string& name) { return law.parameter(name); });
  // A MatchMaker resolved: (material id 1, id 2, value) triples and the value of other pairs
  // (None: such a pair is an error).
  m.def("law_set_pair_parameter", [](ContactLaw& law, const std::string& name,
                                     const std::vector<std::tuple<int, int, double>>& matches, std::optional<double> fallback) {
    PairParameter p;
    for (const auto& [a, b, value] : matches)
      p.matches[{std::min(a, b), std::max(a, b)}] = value;
    p.fallback = fallback;
    law.setPairParameter(name, p);
  });
  m.def("law_parameter_names", [](const ContactLaw& law) { return law.parameterNames(); });

  m.def("track_energy", [](const Scene& s) { return s.energy.enabled; });
  m.def("set_track_energy", [](Scene& s, bool on) { s.energy.enabled = on; });
  // The energies in Yade's names (with `kinSplit`, the kinetic energy's two parts instead of
  // it); kinetic and elastic energies are computed now. Split over processes, the whole scene's
  // (collective).
  m.def("energy", [](const Scene& s, bool kinSplit) {
    const EnergyValues v = energyValues(s);
    py::dict d;
    if (kinSplit)
    {
      d["kinTrans"] = v.kinTrans;
      d["kinRot"] = v.kinRot;
    }
    else
      d["kinetic"] = v.kinetic;
    d["elastPotential"] = v.elastPotential;
    d["gravWork"] = v.gravWork;
    d["nonviscDamp"] = v.nonviscDamp;
    d["plastDissip"] = v.plastDissip;
    d["viscDamp"] = v.viscDamp;
    d["velGradWork"] = v.velGradWork;
    d["kinematicWork"] = v.kinematicWork;
    d["growthWork"] = v.growthWork;
    return d;
  }, py::arg("scene"), py::arg("kinSplit") = false);
  m.def("clear_energy", [](Scene& s) { s.energy.clear(); });
  m.def("body_kinetic_energies", [](const Scene& s) { return bodyKineticEnergies(s); });

  // State of the richer contact models, for the real contacts (same order as Scene.contacts()):
  // every field the contact-law parts declare (core/ContactExtra.h), by its Python name; Quat
  // as (w, x, y, z).
  m.def("contact_extra", [](const Scene& s) {
    py::list out;
    const auto& list = s.contacts.list;
    const ContactExtra* extra = s.contacts.extraState();
    for (std::size_t k = 0; k < list.size(); ++k)
    {
      if (!list[k].real)
        continue;
      py::dict d;
      if (extra)
        forEachContactStateField([&](const auto& f) {
          const auto& value = extra[k].*f.member;
          using T = std::remove_cvref_t<decltype(value)>;
          if constexpr (std::is_same_v<T, Quat>)
            d[f.python] = py::make_tuple(value.w(), value.x(), value.y(), value.z());
          else if constexpr (std::is_same_v<T, std::uint8_t>)
            d[f.python] = f.flag ? py::cast(value != 0) : py::cast(static_cast<int>(value));
          else
            d[f.python] = value;
        });
      out.append(d);
    }
    return out;
  });
}
