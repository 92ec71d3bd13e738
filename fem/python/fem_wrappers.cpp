// Python bindings of fem/ (talus._fem): mapping only. The Python-side API is talus.fem.
#include "fem/GaussPointRVEs.h"
#include "dem/checkpoint/Checkpoint.h"

#include <pybind11/eigen.h>
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <memory>
#include <span>
#include <string>
#include <variant>
#include <vector>

namespace py = pybind11;
using talus::fem::GaussPointRVEs;
using talus::fem::RVE;
using talus::fem::RVEEngines;

namespace
{
using Array = py::array_t<double, py::array::c_style | py::array::forcecast>;

/// A Gauss point's RVE: a checkpoint file name or a talus._dem.Scene (copied).
using Source = std::variant<std::string, std::shared_ptr<talus::dem::Scene>>;

std::unique_ptr<GaussPointRVEs> make(const std::vector<Source>& sources, const std::string& law, double damping)
{
  const RVEEngines engines{law, damping};
  std::vector<std::unique_ptr<RVE>> rves(sources.size());
  // Serial: HDF5 (the checkpoint reader) is not thread-safe.
  for (std::size_t p = 0; p < sources.size(); ++p)
  {
    try
    {
      if (const auto* path = std::get_if<std::string>(&sources[p]))
        rves[p] = std::make_unique<RVE>(RVE::load(*path, engines));
      else if (const auto& scene = std::get<1>(sources[p]))
        rves[p] = std::make_unique<RVE>(*scene, engines, "of Gauss point " + std::to_string(p));
      else
        throw std::invalid_argument("no scene (None) and no checkpoint path");
    }
    catch (const std::exception& e)
    {
      throw std::invalid_argument("Gauss point " + std::to_string(p) + ": " + e.what());
    }
  }
  return std::make_unique<GaussPointRVEs>(std::move(rves));
}

int dimensionOf(const Array& grads, std::size_t points)
{
  if (grads.ndim() != 3 || grads.shape(1) != grads.shape(2) || (grads.shape(1) != 2 && grads.shape(1) != 3))
    throw std::invalid_argument("displacement gradients must be an array of shape (points, 3, 3) or (points, 2, 2)");
  if (static_cast<std::size_t>(grads.shape(0)) != points)
    throw std::invalid_argument("got displacement gradients for " + std::to_string(grads.shape(0))
                                + " Gauss points, but there are " + std::to_string(points) + " RVEs");
  return static_cast<int>(grads.shape(1));
}
} // namespace

PYBIND11_MODULE(_fem, m)
{
  m.doc() = "Talus FEMxDEM: periodic DEM RVEs at Gauss points (C++ core of talus.fem)";
  py::module_::import("talus._dem"); // the Scene type, for RVEs built from live scenes

  m.def("subStepVelocityGradient", &talus::dem::subStepVelocityGradient, py::arg("grad"), py::arg("k"),
        py::arg("nSteps"), py::arg("dt"));

  py::class_<GaussPointRVEs>(m, "GaussPointRVEs")
      .def(py::init(&make), py::arg("sources"), py::arg("law"), py::arg("damping"))
      .def("__len__", &GaussPointRVEs::size)
      .def(
          "deform",
          [](GaussPointRVEs& self, const Array& grads, const py::array_t<int, py::array::c_style | py::array::forcecast>& nSteps) {
            const int dim = dimensionOf(grads, self.size());
            py::gil_scoped_release release;
            self.deform({grads.data(), static_cast<std::size_t>(grads.size())}, dim,
                        std::span<const int>(nSteps.data(), static_cast<std::size_t>(nSteps.size())));
          },
          py::arg("grads"), py::arg("nSteps"))
      .def(
          "getStressAndTangent",
          [](const GaussPointRVEs& self, int dim, bool yadeForm) {
            const auto n = static_cast<py::ssize_t>(self.size());
            const py::ssize_t v = dim == 3 ? 6 : 3;
            Array stress({n, static_cast<py::ssize_t>(dim), static_cast<py::ssize_t>(dim)}), tangent({n, v, v});
            {
              py::gil_scoped_release release;
              self.getStressAndTangent({stress.mutable_data(), static_cast<std::size_t>(stress.size())},
                                       {tangent.mutable_data(), static_cast<std::size_t>(tangent.size())}, dim,
                                       yadeForm ? talus::dem::TangentForm::Yade : talus::dem::TangentForm::Full);
            }
            return py::make_tuple(stress, tangent);
          },
          py::arg("dim"), py::arg("yadeForm"))
      .def("states",
           [](const GaussPointRVEs& self) {
             const auto s = self.states();
             const auto n = static_cast<py::ssize_t>(s.size());
             Array porosity({n}), voidRatio({n}), coordination({n}), fabric({n, py::ssize_t{3}, py::ssize_t{3}}),
                 rotation({n, py::ssize_t{3}});
             for (py::ssize_t p = 0; p < n; ++p)
             {
               const auto& x = s[static_cast<std::size_t>(p)];
               porosity.mutable_at(p) = x.porosity;
               voidRatio.mutable_at(p) = x.voidRatio;
               coordination.mutable_at(p) = x.coordination;
               for (py::ssize_t i = 0; i < 3; ++i)
               {
                 rotation.mutable_at(p, i) = x.meanRotation[i];
                 for (py::ssize_t j = 0; j < 3; ++j)
                   fabric.mutable_at(p, i, j) = x.fabric(i, j);
               }
             }
             py::dict d;
             d["porosity"] = porosity;
             d["voidRatio"] = voidRatio;
             d["coordination"] = coordination;
             d["fabric"] = fabric;
             d["rotation"] = rotation;
             return d;
           })
      .def("commit", [](GaussPointRVEs& self) { py::gil_scoped_release r; self.commit(); })
      .def("rollback", [](GaussPointRVEs& self) { py::gil_scoped_release r; self.rollback(); })
      .def("hasTrial", [](GaussPointRVEs& self, std::size_t p) { return self.rve(p).hasTrial(); })
      .def("iter", [](GaussPointRVEs& self, std::size_t p) { return self.rve(p).scene().iter; })
      .def("cellSize", [](GaussPointRVEs& self, std::size_t p) { return talus::dem::Mat3(self.rve(p).scene().cell.hSize); })
      .def("dt", [](GaussPointRVEs& self, std::size_t p) { return self.rve(p).scene().dt; })
      .def(
          "save",
          [](GaussPointRVEs& self, std::size_t p, const std::string& path) {
            talus::dem::saveCheckpoint(self.rve(p).scene(), path);
          },
          py::arg("point"), py::arg("path"));
}
