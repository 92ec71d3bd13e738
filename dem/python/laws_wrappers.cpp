// Python bindings of the contact models' parameters and state and of the energy tracker.
// Compiled into talus._dem; `talus_wrap_laws(m)` is called from dem_wrappers.cpp. The Python
// API (Yade's functor classes, O.energy) is talus.dem.engines and talus.dem.energy.
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
  // The energies in Yade's names; kinetic and elastic energies are computed now.
  m.def("energy", [](const Scene& s) {
    py::dict d;
    d["kinetic"] = kineticEnergy(s);
    d["elastPotential"] = elasticPotential(s);
    d["gravWork"] = s.energy.gravWork;
    d["nonviscDamp"] = s.energy.nonviscDamp;
    d["plastDissip"] = s.energy.plastDissip;
    d["viscDamp"] = s.energy.viscDamp;
    d["velGradWork"] = s.energy.velGradWork;
    d["kinematicWork"] = s.energy.kinematicWork;
    d["growthWork"] = s.energy.growthWork;
    return d;
  });
  m.def("clear_energy", [](Scene& s) { s.energy.clear(); });
  m.def("kinetic_energy_parts", [](const Scene& s) { return kineticEnergyParts(s); });
  m.def("body_kinetic_energies", [](const Scene& s) { return bodyKineticEnergies(s); });

  // State of the richer contact models, for the real contacts (same order as Scene.contacts()).
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
      {
        const ContactExtra& x = extra[k];
        d["kno"] = x.kno;
        d["kso"] = x.kso;
        d["betan"] = x.betan;
        d["betas"] = x.betas;
        d["twist"] = x.twist;
        d["bending"] = x.bending;
        d["normalAdhesion"] = x.normalAdhesion;
        d["shearAdhesion"] = x.shearAdhesion;
        d["kr"] = x.kr;
        d["ktw"] = x.ktw;
        d["maxRollPl"] = x.maxRollPl;
        d["maxTwistPl"] = x.maxTwistPl;
        d["unp"] = x.unp;
        d["moment_bending"] = x.momentBending;
        d["moment_twist"] = x.momentTwist;
        d["cohesionBroken"] = static_cast<bool>(x.cohesionBroken);
        d["fragile"] = static_cast<bool>(x.fragile);
        d["intactRock"] = static_cast<bool>(x.intactRock);
        d["tensionBroken"] = static_cast<bool>(x.tensionBroken);
        d["mR"] = x.mR;
        d["mRtype"] = static_cast<int>(x.mRtype);
      }
      out.append(d);
    }
    return out;
  });
}
