// Python bindings of the pore-scale flow (flow/pore/): no logic, only the mapping of C++ names to
// Python. The typed, documented API with Yade's names is talus.flow.pore.FlowEngine.
#include "dem/core/Scene.h"
#include "flow/pore/FlowCoupling.h"
#include "flow/pore/PoreFlow.h"
#include "flow/pore/VtkOutput.h"
#include "flow/python/ArrayRows.h"

#include <pybind11/eigen.h>
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/functional.h>
#include <pybind11/stl.h>

#include <algorithm>
#include <string>

namespace py = pybind11;
using talus::flow::python::rows;
using namespace talus::flow::pore;

namespace
{
using Array = py::array_t<double, py::array::c_style | py::array::forcecast>;
using IdArray = py::array_t<std::int64_t, py::array::c_style | py::array::forcecast>;

std::vector<PoreSphere> spheres(const Array& pos, const Array& radius, const IdArray& ids)
{
  if (pos.ndim() != 2 || pos.shape(1) != 3)
    throw py::value_error("positions must be an (n, 3) array");
  const auto n = static_cast<std::size_t>(pos.shape(0));
  if (radius.ndim() != 1 || static_cast<std::size_t>(radius.size()) != n || static_cast<std::size_t>(ids.size()) != n)
    throw py::value_error("positions, radii and ids must have the same length");
  std::vector<PoreSphere> s(n);
  for (std::size_t i = 0; i < n; ++i)
    s[i] = PoreSphere{Vec3(pos.at(i, 0), pos.at(i, 1), pos.at(i, 2)), radius.at(i), ids.at(i)};
  return s;
}

/// An (n, 3) array as vectors.
std::vector<Vec3> vectors(const Array& a, const char* what)
{
  if (a.ndim() != 2 || a.shape(1) != 3)
    throw py::value_error(std::string(what) + " must be an (n, 3) array");
  std::vector<Vec3> v(static_cast<std::size_t>(a.shape(0)));
  for (std::size_t i = 0; i < v.size(); ++i)
    v[i] = Vec3(a.at(i, 0), a.at(i, 1), a.at(i, 2));
  return v;
}

/// Per-pore or per-throat values as a numpy array.
template <class T, class F>
Array column(const std::vector<T>& items, F f)
{
  Array a(static_cast<py::ssize_t>(items.size()));
  auto m = a.mutable_unchecked<1>();
  for (std::size_t i = 0; i < items.size(); ++i)
    m(static_cast<py::ssize_t>(i)) = f(items[i]);
  return a;
}
} // namespace

void registerPoreFlow(py::module_& m)
{
  py::class_<FlowParameters>(m, "PoreFlowParameters")
      .def(py::init<>())
      .def_readwrite("permeabilityFactor", &FlowParameters::permeabilityFactor)
      .def_readwrite("viscosity", &FlowParameters::viscosity)
      .def_readwrite("clampKValues", &FlowParameters::clampKValues)
      .def_readwrite("minKdivKmean", &FlowParameters::minKdivKmean)
      .def_readwrite("maxKdivKmean", &FlowParameters::maxKdivKmean)
      .def_readwrite("slipBoundary", &FlowParameters::slipBoundary)
      .def_readwrite("bndCondIsPressure", &FlowParameters::bndCondIsPressure)
      .def_readwrite("bndCondValue", &FlowParameters::bndCondValue)
      .def_readwrite("boundaryUseMaxMin", &FlowParameters::boundaryUseMaxMin)
      .def_readwrite("wallPosition", &FlowParameters::wallPosition)
      .def_readwrite("useSolver", &FlowParameters::useSolver)
      .def_readwrite("tolerance", &FlowParameters::tolerance)
      .def_readwrite("multigridTolerance", &FlowParameters::multigridTolerance)
      .def_readwrite("relax", &FlowParameters::relax)
      .def_readwrite("fluidBulkModulus", &FlowParameters::fluidBulkModulus)
      .def_readwrite("pZero", &FlowParameters::pZero)
      .def_readwrite("periodic", &FlowParameters::periodic)
      .def_readwrite("cellSize", &FlowParameters::cellSize)
      .def_readwrite("duplicateThreshold", &FlowParameters::duplicateThreshold)
      .def_readwrite("gradP", &FlowParameters::gradP)
      .def_readwrite("hasBoundary", &FlowParameters::hasBoundary)
      .def_readwrite("yadeInsertionOrder", &FlowParameters::yadeInsertionOrder)
      .def_readwrite("concurrentTriangulation", &FlowParameters::concurrentTriangulation)
      .def_readwrite("alphaBound", &FlowParameters::alphaBound)
      .def_readwrite("alphaBoundValue", &FlowParameters::alphaBoundValue)
      .def_readwrite("viscousShear", &FlowParameters::viscousShear)
      .def_readwrite("shearLubrication", &FlowParameters::shearLubrication)
      .def_readwrite("normalLubrication", &FlowParameters::normalLubrication)
      .def_readwrite("eps", &FlowParameters::eps)
      .def_readwrite("stiffness", &FlowParameters::stiffness);

  py::class_<PressureSolver::Counters>(m, "PoreSolverCounters")
      .def_readonly("analyses", &PressureSolver::Counters::analyses)
      .def_readonly("factorizations", &PressureSolver::Counters::factorizations)
      .def_readonly("analyseSeconds", &PressureSolver::Counters::analyseSeconds)
      .def_readonly("factorizeSeconds", &PressureSolver::Counters::factorizeSeconds)
      .def_readonly("multigridSetups", &PressureSolver::Counters::multigridSetups)
      .def_readonly("multigridIterations", &PressureSolver::Counters::multigridIterations)
      .def_readonly("multigridSeconds", &PressureSolver::Counters::multigridSeconds);

  py::class_<PoreFlow, std::shared_ptr<PoreFlow>>(m, "PoreFlow")
      .def(py::init<>())
      .def_readwrite("params", &PoreFlow::params)
      .def(
          "build", [](PoreFlow& f, const Array& pos, const Array& r, const IdArray& ids) { f.build(spheres(pos, r, ids)); },
          py::arg("positions"), py::arg("radii"), py::arg("ids"))
      .def("updateConductances", &PoreFlow::updateConductances)
      .def(
          "moveVertices",
          [](PoreFlow& f, const Array& pos, const std::array<double, kBoundaries>& walls, double dt) {
            f.moveVertices(vectors(pos, "positions"), walls, dt);
          },
          py::arg("positions"), py::arg("boundaryPositions"), py::arg("dt"))
      .def("setTimeStep", &PoreFlow::setTimeStep)
      .def("maxVolumetricStrain", &PoreFlow::maxVolumetricStrain)
      .def("invertedPores", &PoreFlow::invertedPores)
      .def("volumeRates", [](const PoreFlow& f) { return Array(static_cast<py::ssize_t>(f.volumeRates().size()), f.volumeRates().data()); })
      .def("solverCounters", &PoreFlow::solverCounters)
      .def("boundaryPositions", [](const PoreFlow& f) {
        std::array<double, kBoundaries> b{};
        for (int k = 0; k < kBoundaries; ++k)
          b[static_cast<std::size_t>(k)] = f.network().boundaries[static_cast<std::size_t>(k)].position;
        return b;
      })
      .def("imposePressure", &PoreFlow::imposePressure)
      .def("setImposedPressure", &PoreFlow::setImposedPressure)
      .def("imposeFlux", &PoreFlow::imposeFlux)
      .def("clearImposedFlux", &PoreFlow::clearImposedFlux)
      .def("saveVtk", [](const PoreFlow& f, const std::string& base, const std::vector<PoreField>& fields, bool withBoundaries) { return saveVtk(f, base, fields, withBoundaries); },
           py::arg("base"), py::arg("poreFields") = std::vector<PoreField>{}, py::arg("withBoundaries") = true)
      .def("poreVelocities", [](const PoreFlow& f) { return rows(f.poreVelocities()); })
      .def("clearImposedPressure", &PoreFlow::clearImposedPressure)
      .def("getCellFlux", &PoreFlow::getCellFlux)
      .def("solve", &PoreFlow::solve)
      .def("built", &PoreFlow::built)
      .def("factorized", &PoreFlow::factorized)
      .def("lastIterations", &PoreFlow::lastIterations)
      .def("boundaryFlux", &PoreFlow::boundaryFlux)
      .def("porePressure", &PoreFlow::porePressure)
      .def("samplePermeability", &PoreFlow::samplePermeability)
      .def("periodicPermeability", &PoreFlow::periodicPermeability)
      .def("nImages", [](const PoreFlow& f) { return f.network().vertices.size() - kBoundaries - f.network().sphereCount(); })
      .def("throatPeriods", [](const PoreFlow& f) {
        const auto& t = f.network().throats;
        py::array_t<int> a({static_cast<py::ssize_t>(t.size()), py::ssize_t{3}});
        auto out = a.mutable_unchecked<2>();
        for (std::size_t i = 0; i < t.size(); ++i)
          for (int d = 0; d < 3; ++d)
            out(static_cast<py::ssize_t>(i), d) = t[i].period[d];
        return a;
      })
      .def("averageVelocity", &PoreFlow::averageVelocity)
      .def("globalConductance", &PoreFlow::globalConductance)
      .def("locate", [](const PoreFlow& f, const Vec3& x) { return locatePore(f.network(), x); })
      .def("pressures", [](const PoreFlow& f) { return Array(static_cast<py::ssize_t>(f.pressures().size()), f.pressures().data()); })
      .def("hiddenSpheres", [](const PoreFlow& f) { return f.network().hiddenSpheres; })
      .def("vertexSpheres",
           [](const PoreFlow& f) {
             // x, y, z, radius of every vertex (boundaries first, then the spheres)
             const auto& v = f.network().vertices;
             Eigen::MatrixX4d out(static_cast<Eigen::Index>(v.size()), 4);
             for (std::size_t i = 0; i < v.size(); ++i)
               out.row(static_cast<Eigen::Index>(i)) << v[i].pos.x(), v[i].pos.y(), v[i].pos.z(), v[i].radius;
             return out;
           })
      .def("alphaShape",
           [](const PoreFlow& f) {
             // the alpha used, the pores outside the shape, the body ids of the spheres on it
             const AlphaBoundary& a = f.alphaShape();
             std::vector<std::int64_t> onBoundary;
             for (std::size_t v = 0; v < a.boundaryVertices.size(); ++v)
               if (a.boundaryVertices[v])
                 onBoundary.push_back(f.network().vertices[v].id);
             return py::make_tuple(a.alpha, std::vector<bool>(a.exteriorPores.begin(), a.exteriorPores.end()),
                                   onBoundary);
           })
      .def("nCells", [](const PoreFlow& f) { return f.network().pores.size(); })
      .def("nThroats", [](const PoreFlow& f) { return f.network().throats.size(); })
      .def("poreVolumes", [](const PoreFlow& f) { return column(f.network().pores, [](const Pore& p) { return p.volume; }); })
      .def("poreVoidVolumes", [](PoreFlow& f) {
        f.updateVoidVolumes();
        return column(f.network().pores, [](const Pore& p) { return p.voidVolume; });
      })
      .def("poreCentres", [](const PoreFlow& f) {
        const auto& pores = f.network().pores;
        Array a({static_cast<py::ssize_t>(pores.size()), py::ssize_t{3}});
        auto out = a.mutable_unchecked<2>();
        for (std::size_t i = 0; i < pores.size(); ++i)
          for (py::ssize_t d = 0; d < 3; ++d)
            out(static_cast<py::ssize_t>(i), d) = pores[i].centre[d];
        return a;
      })
      .def("poreBarycentre", [](const PoreFlow& f, std::size_t i) {
        if (i >= f.network().pores.size())
          throw py::index_error("getCellBarycenter: no pore " + std::to_string(i));
        return interiorPoint(f.network(), f.network().pores[i]);
      })
      .def("poreVertexIds", [](const PoreFlow& f) {
        // Yade's numbering: boundaries 0..5, spheres by body id.
        const auto& net = f.network();
        py::array_t<std::int64_t> a({static_cast<py::ssize_t>(net.pores.size()), py::ssize_t{4}});
        auto out = a.mutable_unchecked<2>();
        for (std::size_t i = 0; i < net.pores.size(); ++i)
          for (int k = 0; k < 4; ++k)
            out(static_cast<py::ssize_t>(i), k) = net.vertices[static_cast<std::size_t>(net.pores[i].vertices[k])].id;
        return a;
      })
      .def("boundarySphereIds", [](const PoreFlow& f, int k) {
        // body ids of the spheres sharing a pore with boundary k (vertex k), in ascending order
        if (k < 0 || k >= kBoundaries)
          throw py::index_error("boundary index must be 0..5");
        const auto& net = f.network();
        std::vector<std::int64_t> ids;
        for (const auto& pore : net.pores)
          if (std::find(pore.vertices.begin(), pore.vertices.end(), k) != pore.vertices.end())
            for (const auto v : pore.vertices)
              if (v >= kBoundaries)
                ids.push_back(net.vertices[static_cast<std::size_t>(v)].id);
        std::sort(ids.begin(), ids.end());
        ids.erase(std::unique(ids.begin(), ids.end()), ids.end());
        return ids;
      })
      .def("poreNeighbours", [](const PoreFlow& f) {
        const auto& pores = f.network().pores;
        py::array_t<int> a({static_cast<py::ssize_t>(pores.size()), py::ssize_t{4}});
        auto out = a.mutable_unchecked<2>();
        for (std::size_t i = 0; i < pores.size(); ++i)
          for (int k = 0; k < 4; ++k)
            out(static_cast<py::ssize_t>(i), k) = pores[i].neighbours[k];
        return a;
      })
      .def("throatPores", [](const PoreFlow& f) {
        const auto& t = f.network().throats;
        py::array_t<int> a({static_cast<py::ssize_t>(t.size()), py::ssize_t{2}});
        auto out = a.mutable_unchecked<2>();
        for (std::size_t i = 0; i < t.size(); ++i)
          for (int k = 0; k < 2; ++k)
            out(static_cast<py::ssize_t>(i), k) = t[i].pores[static_cast<std::size_t>(k)];
        return a;
      })
      // rows as poreVertexIds numbers them: 0..5 the boundaries, then the spheres in input order
      .def("vertexForces", [](const PoreFlow& f) { return rows(f.vertexForces()); })
      .def(
          "computeViscousForces",
          [](PoreFlow& f, const Array& vel, const Array& angVel, double dt) {
            f.computeViscousForces(vectors(vel, "velocities"), vectors(angVel, "angular velocities"), dt);
          },
          py::arg("velocities"), py::arg("angularVelocities"), py::arg("dt"))
      // rows: the spheres in input order
      .def("shearLubForces", [](const PoreFlow& f) { return rows(f.lubrication().shearForces()); })
      .def("shearLubTorques", [](const PoreFlow& f) { return rows(f.lubrication().shearTorques()); })
      .def("normalLubForces", [](const PoreFlow& f) { return rows(f.lubrication().normalForces()); })
      .def("spherePairs", [](const PoreFlow& f) {
        // body ids of each pair and the area of its power-diagram face
        std::vector<std::array<std::int64_t, 2>> ids;
        std::vector<double> areas;
        const auto& net = f.network();
        for (const SpherePair& p : f.lubrication().pairs())
        {
          ids.push_back({net.vertices[static_cast<std::size_t>(p.a)].id, net.vertices[static_cast<std::size_t>(p.b)].id});
          areas.push_back(p.faceArea);
        }
        return py::make_tuple(ids, areas);
      })
      .def("vertexIds", [](const PoreFlow& f) {
        // boundaries and spheres (not the periodic images, which come after them)
        std::vector<std::int64_t> ids;
        const auto& net = f.network();
        for (std::size_t v = 0; v < kBoundaries + net.sphereCount(); ++v)
          ids.push_back(net.vertices[v].id);
        return ids;
      })
      .def("throatConductances", [](const PoreFlow& f) { return column(f.network().throats, [](const Throat& t) { return t.conductance; }); })
      .def("throatAreas", [](const PoreFlow& f) { return column(f.network().throats, [](const Throat& t) { return t.area; }); })
      .def("throatFluidAreas", [](const PoreFlow& f) { return column(f.network().throats, [](const Throat& t) { return t.fluidArea; }); })
      .def("throatHydraulicRadii", [](const PoreFlow& f) { return column(f.network().throats, [](const Throat& t) { return t.hydraulicRadius; }); })
      .def("throatLengths", [](const PoreFlow& f) { return column(f.network().throats, [](const Throat& t) { return t.length; }); });

  // The scene type is registered by talus._dem (imported first by the talus package).
  py::class_<FlowCoupling, std::shared_ptr<FlowCoupling>>(m, "PoreFlowCoupling")
      .def(py::init([](const std::shared_ptr<talus::dem::Scene>& scene, const std::shared_ptr<PoreFlow>& flow) {
             if (!scene || !flow)
               throw std::invalid_argument(std::string("PoreFlowCoupling: ") + (scene ? "flow" : "scene") + " is None");
             return std::make_shared<FlowCoupling>(talus::dem::ParticleExchange(*scene), flow);
           }),
           py::arg("scene"), py::arg("flow"), py::keep_alive<1, 2>())
      .def_readwrite("wallIds", &FlowCoupling::wallIds)
      .def_readwrite("meshUpdateInterval", &FlowCoupling::meshUpdateInterval)
      .def_readwrite("defTolerance", &FlowCoupling::defTolerance)
      .def_readwrite("blockHook", &FlowCoupling::blockHook)
      .def_readwrite("multithread", &FlowCoupling::multithread)
      .def_readwrite("backgroundSteps", &FlowCoupling::backgroundSteps)
      .def_readwrite("decoupleForces", &FlowCoupling::decoupleForces)
      .def("rebuildPending", &FlowCoupling::rebuildPending)
      .def("strainRebuilds", &FlowCoupling::strainRebuilds)
      .def("step", &FlowCoupling::step)
      .def("requestRebuild", &FlowCoupling::requestRebuild)
      .def("rebuilds", &FlowCoupling::rebuilds)
      .def("forces", [](const FlowCoupling& c) { return rows(c.forces()); })
      .def("torques", [](const FlowCoupling& c) { return rows(c.torques()); });
}
