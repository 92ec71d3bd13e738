// Python bindings of dem/: no logic here, only the mapping of C++ names to Python.
#include "dem/build_config.h"

#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <string>
#include <tuple>
#include <vector>

namespace py = pybind11;

PYBIND11_MODULE(_dem, m)
{
  m.doc() = "Compiled core of talus.dem (use the talus package, not this module)";
  m.def("version", [] { return std::string(talus::version()); });
  m.def("build_config", [] {
    std::vector<std::tuple<std::string, std::string, bool, std::string>> rows;
    for (const talus::BuildEntry& e : talus::build_config())
      rows.emplace_back(e.kind, e.name, e.enabled, e.note);
    return rows;
  });
}
