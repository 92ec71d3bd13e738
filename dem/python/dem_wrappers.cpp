// Python bindings of dem/: no logic here, only the mapping of C++ names to Python. Defaults,
// docstrings and Yade-style conveniences live in the talus.dem Python layer.
#include "dem/engines/CallbackEngine.h"
#include "dem/engines/ParallelEngine.h"
#include "dem/contact/Collider.h"
#include "dem/laws/ContactLaw.h"
#include "dem/engines/ForceResetter.h"
#include "dem/engines/InteractionLoop.h"
#include "dem/measure/Measurements.h"
#include "dem/engines/NewtonIntegrator.h"
#include "dem/measure/Probe.h"
#include "dem/core/Scene.h"
#include "dem/base/Threads.h"
#include "dem/base/build_config.h"

#include <pybind11/eigen.h>
#include <pybind11/functional.h>
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <algorithm>
#include <string>
#include <tuple>
#include <vector>

namespace py = pybind11;
using namespace talus::dem;

namespace
{
/// Zero-copy (n, 3) view of a vector of Vec3 owned by `owner` (kept alive by the view).
py::array_t<double> view3(std::vector<Vec3>& v, py::handle owner)
{
  return py::array_t<double>({static_cast<py::ssize_t>(v.size()), py::ssize_t{3}},
                             {static_cast<py::ssize_t>(sizeof(Vec3)), static_cast<py::ssize_t>(sizeof(double))},
                             v.empty() ? nullptr : v.front().data(), owner);
}

template <class T>
py::array_t<T> view1(std::vector<T>& v, py::handle owner)
{
  return py::array_t<T>({static_cast<py::ssize_t>(v.size())}, {static_cast<py::ssize_t>(sizeof(T))},
                        v.empty() ? nullptr : v.data(), owner);
}

/// The same view, read-only: properties that engines cache must change through the Scene.
template <class A>
A readOnly(A array)
{
  py::detail::array_proxy(array.ptr())->flags &= ~py::detail::npy_api::NPY_ARRAY_WRITEABLE_;
  return array;
}

/// A list of engines or laws set from Python, refused if an item is None (an empty pointer the
/// step would dereference).
template <class T>
std::vector<std::shared_ptr<T>> noneRefused(const std::vector<std::shared_ptr<T>>& items, const char* what)
{
  for (std::size_t k = 0; k < items.size(); ++k)
    if (!items[k])
      throw py::type_error(std::string(what) + ": item " + std::to_string(k) + " is None");
  return items;
}

/// One contact as a dict of Yade's geometry and physics names (a copy, for scripts).
py::dict contactDict(const Contact& c)
{
  py::dict d;
  d["id1"] = c.id1;
  d["id2"] = c.id2;
  d["isReal"] = c.real;
  d["normal"] = c.normal;
  d["contactPoint"] = c.contactPoint;
  d["penetrationDepth"] = c.penetration;
  d["refR1"] = c.refR1;
  d["refR2"] = c.refR2;
  d["shearInc"] = c.shearIncrement;
  d["cellDist"] = c.cellDist;
  d["kn"] = c.kn;
  d["ks"] = c.ks;
  d["cn"] = c.cn;
  d["cs"] = c.cs;
  d["tangensOfFrictionAngle"] = c.tanPhi;
  d["normalForce"] = c.normalForce;
  d["shearForce"] = c.shearForce;
  d["force"] = c.force;
  return d;
}

} // namespace

PYBIND11_MODULE(_dem, m)
{
  m.doc() = "Compiled core of talus.dem (use the talus package, not this module)";
  void talus_wrap_io(py::module_&); talus_wrap_io(m); // checkpoints and export arrays: io_wrappers.cpp
  void talus_wrap_pack(py::module_&); talus_wrap_pack(m); // SpherePack: pack_wrappers.cpp
  void talus_wrap_laws(py::module_&); talus_wrap_laws(m); // contact models, energy: laws_wrappers.cpp
  m.def("version", [] { return std::string(talus::version()); });
  m.def("threadCount", &threadCount);
  m.def("setThreadCount", [](int n) {
    if (n < 1)
      throw std::invalid_argument("the number of threads must be at least 1, got " + std::to_string(n));
    setThreadCount(n);
  });
  m.def("build_config", [] {
    std::vector<std::tuple<std::string, std::string, bool, std::string>> rows;
    for (const talus::BuildEntry& e : talus::build_config())
      rows.emplace_back(e.kind, e.name, e.enabled, e.note);
    return rows;
  });
  m.def("contact_law_names", &contactLawNames);

  py::enum_<MaterialKind>(m, "MaterialKind")
      .value("Frict", MaterialKind::Frict)
      .value("ViscEl", MaterialKind::ViscEl)
      .value("CohFrict", MaterialKind::CohFrict);
  py::class_<Material>(m, "Material")
      .def(py::init<>())
      .def_readwrite("kind", &Material::kind)
      .def_readwrite("label", &Material::label)
      .def_readwrite("density", &Material::density)
      .def_readwrite("young", &Material::young)
      .def_readwrite("poisson", &Material::poisson)
      .def_readwrite("frictionAngle", &Material::frictionAngle)
      .def_readwrite("tc", &Material::tc)
      .def_readwrite("en", &Material::en)
      .def_readwrite("et", &Material::et)
      .def_readwrite("kn", &Material::kn)
      .def_readwrite("cn", &Material::cn)
      .def_readwrite("ks", &Material::ks)
      .def_readwrite("cs", &Material::cs)
      .def_readwrite("normalCohesion", &Material::normalCohesion)
      .def_readwrite("shearCohesion", &Material::shearCohesion)
      .def_readwrite("alphaKr", &Material::alphaKr)
      .def_readwrite("alphaKtw", &Material::alphaKtw)
      .def_readwrite("etaRoll", &Material::etaRoll)
      .def_readwrite("etaTwist", &Material::etaTwist)
      .def_readwrite("isCohesive", &Material::isCohesive)
      .def_readwrite("momentRotationLaw", &Material::momentRotationLaw)
      .def_readwrite("fragile", &Material::fragile)
      .def_readwrite("mR", &Material::mR)
      .def_readwrite("mRtype", &Material::mRtype)
      .def_readwrite("lubrication", &Material::lubrication)
      .def_readwrite("viscoDyn", &Material::viscoDyn)
      .def_readwrite("roughnessScale", &Material::roughnessScale)
      .def("validate", &Material::validate);

  py::class_<Engine, std::shared_ptr<Engine>>(m, "Engine")
      .def_property_readonly("typeName", &Engine::typeName)
      .def_readwrite("label", &Engine::label)
      .def_readwrite("dead", &Engine::dead)
      .def_readwrite("execTime", &Engine::execTime)
      .def_readwrite("execCount", &Engine::execCount)
      .def_property_readonly("timingDeltasData",
                             [](const Engine& e) {
                               py::list data;
                               const TimingDeltas& t = e.timingDeltas;
                               for (std::size_t k = 0; k < t.labels.size(); ++k)
                                 data.append(py::make_tuple(t.labels[k], t.nsec[k], t.count[k]));
                               return data;
                             })
      .def("resetTimingDeltas", [](Engine& e) { e.timingDeltas.reset(); });
  py::class_<ForceResetter, Engine, std::shared_ptr<ForceResetter>>(m, "ForceResetter").def(py::init<>());
  py::class_<Collider, Engine, std::shared_ptr<Collider>>(m, "Collider")
      .def(py::init<>())
      .def_readwrite("verletDist", &Collider::verletDist)
      .def_readwrite("allowBiggerThanPeriod", &Collider::allowBiggerThanPeriod)
      .def_readwrite("avoidSelfInteractionMask", &Collider::avoidSelfInteractionMask)
      .def_readonly("rebuilds", &Collider::rebuilds)
      .def("boundOf", [](const Collider& c, const Scene& scene, BodyId id) -> py::object {
        const auto bound = c.boundOf(scene, id);
        if (!bound)
          return py::none();
        return py::make_tuple(bound->min, bound->max, bound->refPos, bound->sweepLength);
      });
  py::class_<ContactLaw, std::shared_ptr<ContactLaw>>(m, "ContactLaw")
      .def_property_readonly("typeName", &ContactLaw::typeName)
      .def_property_readonly("physicsName", &ContactLaw::physicsName);
  m.def("make_contact_law", [](const std::string& name) { return std::shared_ptr<ContactLaw>(makeContactLaw(name)); });
  py::class_<InteractionLoop, Engine, std::shared_ptr<InteractionLoop>>(m, "InteractionLoop")
      .def(py::init<>())
      .def_property(
          "laws", [](const InteractionLoop& l) { return l.laws; },
          [](InteractionLoop& l, const std::vector<std::shared_ptr<ContactLaw>>& laws) { l.laws = noneRefused(laws, "InteractionLoop.laws"); });
  py::class_<NewtonIntegrator, Engine, std::shared_ptr<NewtonIntegrator>>(m, "NewtonIntegrator")
      .def(py::init<>())
      .def_readwrite("gravity", &NewtonIntegrator::gravity)
      .def_readwrite("damping", &NewtonIntegrator::damping)
      .def_readwrite("dampGravity", &NewtonIntegrator::dampGravity)
      .def_readwrite("mask", &NewtonIntegrator::mask);
  py::class_<ParallelEngine, Engine, std::shared_ptr<ParallelEngine>>(m, "ParallelEngine")
      .def(py::init<>())
      .def_readwrite("slaves", &ParallelEngine::slaves);
  py::class_<CallbackEngine, Engine, std::shared_ptr<CallbackEngine>>(m, "CallbackEngine")
      .def(py::init<>())
      .def_readwrite("callback", &CallbackEngine::callback)
      .def_readwrite("resumable", &CallbackEngine::resumable)
      .def_readwrite("iterPeriod", &CallbackEngine::iterPeriod)
      .def_readwrite("realPeriod", &CallbackEngine::realPeriod)
      .def_readwrite("virtPeriod", &CallbackEngine::virtPeriod)
      .def_readwrite("virtLast", &CallbackEngine::virtLast)
      .def_readwrite("initRun", &CallbackEngine::initRun)
      .def_readwrite("iterLast", &CallbackEngine::iterLast)
      .def_readwrite("nDone", &CallbackEngine::nDone)
      .def_readwrite("nDo", &CallbackEngine::nDo);

  void talus_wrap_controllers(py::module_&); talus_wrap_controllers(m); // engines: controllers_wrappers.cpp
  void talus_wrap_triaxial(py::module_&); talus_wrap_triaxial(m); // triaxial tests: triaxial_wrappers.cpp

  py::class_<Cell>(m, "Cell")
      .def_readonly("hSize", &Cell::hSize)
      .def_readwrite("velGrad", &Cell::velGrad)
      .def_readwrite("prevVelGrad", &Cell::prevVelGrad)
      .def_readwrite("trsf", &Cell::trsf)
      .def_readwrite("homoDeform", &Cell::homoDeform)
      .def_property_readonly("volume", &Cell::volume);

  m.def("unbalancedForce", &unbalancedForce);
  m.def("loveWeberStress", &loveWeberStress);
  m.def("totalForceInVolume", [](const Scene& s) {
    const auto [force, stiffness] = totalForceInVolume(s);
    return py::make_tuple(force, stiffness);
  });
  m.def("contactStiffnessTangent", [](const Scene& s, double volume, bool yadeForm) {
    return contactStiffnessTangent(s, volume, yadeForm ? TangentForm::Yade : TangentForm::Full);
  });
  m.def("coordinationNumber", &coordinationNumber);
  m.def("fabricTensor", &fabricTensor);
  m.def("bodyStressTensors", &bodyStressTensors);
  m.def("bodies_in_box", &bodiesInBox, py::arg("scene"), py::arg("lo"), py::arg("hi"), py::arg("grow") = 0.0);
  m.def("bodies_touching_sphere", &bodiesTouchingSphere, py::arg("scene"), py::arg("center"), py::arg("radius"),
        py::arg("except") = -1);
  m.def("sphereVolume", &sphereVolume);

  py::class_<Scene, std::shared_ptr<Scene>>(m, "Scene")
      .def(py::init<>())
      .def_readwrite("dt", &Scene::dt)
      .def_readwrite("time", &Scene::time)
      .def_readwrite("iter", &Scene::iter)
      .def_property(
          "engines", [](const Scene& s) { return s.engines; },
          [](Scene& s, const std::vector<std::shared_ptr<Engine>>& engines) { s.setEngines(noneRefused(engines, "Scene.engines")); })
      .def_readonly("nextEngines", &Scene::nextEngines)
      .def_readonly("subStep", &Scene::subStep)
      .def_readwrite("subStepping", &Scene::subStepping)
      .def_readonly("periodic", &Scene::periodic)
      .def("setPeriodic", &Scene::setPeriodic)
      .def("setCellSize", &Scene::setCellSize)
      .def_property_readonly(
          "cell", [](Scene& s) -> Cell& { return s.cell; }, py::return_value_policy::reference_internal)
      .def_readonly("bodiesVersion", &Scene::bodiesVersion)
      .def("addMaterial", &Scene::addMaterial)
      .def(
          "material", [](Scene& s, int i) -> Material& { return s.materials.at(static_cast<std::size_t>(i)); },
          py::return_value_policy::reference_internal)
      .def("materialCount", [](const Scene& s) { return s.materials.size(); })
      .def("addSphere", &Scene::addSphere)
      .def("addWall", &Scene::addWall)
      .def("addFacet", &Scene::addFacet, py::arg("a"), py::arg("b"), py::arg("c"), py::arg("material"),
           py::arg("bounded") = true)
      .def("erase", &Scene::erase)
      .def("clearBodies", &Scene::clearBodies)
      .def("setBlockedDofs", &Scene::setBlockedDofs)
      .def("setDynamic", &Scene::setDynamic)
      .def("setMass", &Scene::setMass)
      .def("setInertia", &Scene::setInertia)
      .def("checkBody", &Scene::checkBody)
      .def("bodyCount", [](const Scene& s) { return s.bodies.size(); })
      .def("pWaveTimeStep", &Scene::pWaveTimeStep)
      .def("contactTimeStep", &Scene::contactTimeStep)
      .def("stiffestSphere",
           [](const Scene& s) {
             const Scene::StiffestSphere best = s.stiffestSphere();
             return py::make_tuple(best.step, best.id);
           })
      .def_readwrite("maxOverlapRatio", &Scene::maxOverlapRatio)
      .def_readwrite("overlapStops", &Scene::overlapStops)
      .def_readwrite("overlapSteps", &Scene::overlapSteps)
      .def_readonly("firstOverlap", &Scene::firstOverlap)
      .def_readwrite("maxEnergyGrowth", &Scene::maxEnergyGrowth)
      .def_readwrite("timingEnabled", &Scene::timingEnabled)
      .def_property_readonly("fusedSteps", [](Scene& s) { return s.stepLoop().sharedSteps(); })
      .def_property_readonly("fusedOtherEnginesSeconds", [](Scene& s) { return s.stepLoop().serialSeconds(); })
      .def("step", &Scene::step, py::call_guard<py::gil_scoped_release>())
      .def(
          "run",
          [](Scene& s, std::int64_t steps) {
            s.run(steps, [] {
              py::gil_scoped_acquire gil;
              if (PyErr_CheckSignals() != 0)
                throw py::error_already_set();
            });
          },
          py::call_guard<py::gil_scoped_release>())
      .def("pause", &Scene::pause)
      .def(
          "runEngine", [](Scene& s, Engine& e) { e.run(s); }, py::arg("engine"),
          "Run one engine once outside a step (Yade's O.runEngine): the clock does not advance.")
      // Zero-copy array views of body state (the particle exchange interface in Python).
      // A view stays valid until bodies are appended (which may move the arrays).
      .def("pos", [](py::object self) { return view3(self.cast<Scene&>().bodies.pos, self); })
      .def("vel", [](py::object self) { return view3(self.cast<Scene&>().bodies.vel, self); })
      .def("angVel", [](py::object self) { return view3(self.cast<Scene&>().bodies.angVel, self); })
      .def("force", [](py::object self) { return view3(self.cast<Scene&>().bodies.force, self); })
      .def("torque", [](py::object self) { return view3(self.cast<Scene&>().bodies.torque, self); })
      .def("extForce", [](py::object self) { return view3(self.cast<Scene&>().bodies.extForce, self); })
      .def("extTorque", [](py::object self) { return view3(self.cast<Scene&>().bodies.extTorque, self); })
      .def("inertia", [](py::object self) { return readOnly(view3(self.cast<Scene&>().bodies.inertia, self)); })
      .def("mass", [](py::object self) { return readOnly(view1(self.cast<Scene&>().bodies.mass, self)); })
      .def("radius", [](py::object self) { return readOnly(view1(self.cast<Scene&>().bodies.radius, self)); })
      // The bodies' heat (Yade's ThermalState: temp, Cp, k, alpha), NaN where not given.
      .def("temperature", [](py::object self) { return view1(self.cast<Scene&>().bodies.temperature, self); })
      .def("heatCapacity", [](py::object self) { return view1(self.cast<Scene&>().bodies.heatCapacity, self); })
      .def("conductivity", [](py::object self) { return view1(self.cast<Scene&>().bodies.conductivity, self); })
      .def("thermalExpansion", [](py::object self) { return view1(self.cast<Scene&>().bodies.thermalExpansion, self); })
      // Bodies the per-body arrays hold room for before their storage moves (and views go stale).
      .def("bodySpareCapacity",
           [](const Scene& s) {
             const Bodies& b = s.bodies;
             std::size_t spare = b.pos.capacity() - b.pos.size();
             for (const std::vector<Vec3>* v : {&b.vel, &b.angVel, &b.force, &b.torque, &b.extForce, &b.extTorque})
               spare = std::min(spare, v->capacity() - v->size());
             for (const std::vector<double>* v :
                  {&b.mass, &b.radius, &b.temperature, &b.heatCapacity, &b.conductivity, &b.thermalExpansion})
               spare = std::min(spare, v->capacity() - v->size());
             return spare;
           })
      .def("blockedDofs", [](py::object self) { return readOnly(view1(self.cast<Scene&>().bodies.blockedDofs, self)); })
      .def("dynamic", [](py::object self) { return readOnly(view1(self.cast<Scene&>().bodies.dynamic, self)); })
      .def("alive", [](py::object self) { return readOnly(view1(self.cast<Scene&>().bodies.alive, self)); })
      .def("materialIds", [](py::object self) { return readOnly(view1(self.cast<Scene&>().bodies.material, self)); })
      .def("shapeKind", [](const Scene& s, BodyId id) {
        s.checkBody(id);
        return shapeName(s.bodies.shape[static_cast<std::size_t>(id)]);
      })
      .def("ori", [](const Scene& s, BodyId id) {
        s.checkBody(id);
        const Quat& q = s.bodies.ori[static_cast<std::size_t>(id)];
        return std::make_tuple(q.w(), q.x(), q.y(), q.z());
      })
      .def("contactCount", [](const Scene& s) { return s.contacts.list.size(); })
      .def("realContactCount", [](const Scene& s) { return s.contacts.countReal(); })
      .def(
          "contacts",
          [](const Scene& s, bool realOnly) {
            // A copy of the contacts (the real ones, or all pairs), for inspection, not hot loops.
            py::list out;
            for (const Contact& c : s.contacts.list)
              if (c.real || !realOnly)
                out.append(contactDict(c));
            return out;
          },
          py::arg("realOnly") = true)
      .def("contact", [](const Scene& s, BodyId id1, BodyId id2) -> py::object {
        // Yade's O.interactions[id1, id2]: the pair in either order, real or only within the skin.
        const ContactList& list = s.contacts.list;
        for (const auto& [a, b] : {std::pair{id1, id2}, std::pair{id2, id1}})
        {
          auto it = std::lower_bound(list.begin(), list.end(), std::pair{a, b}, [](const Contact& c, const std::pair<BodyId, BodyId>& key) {
            return std::pair{c.id1, c.id2} < key;
          });
          if (it != list.end() && it->id1 == a && it->id2 == b)
            return contactDict(*it);
        }
        return py::none();
      })
      .def("contactsOf", [](const Scene& s, BodyId id) {
        // The pairs of one body (real or not), in list order: Yade's O.interactions.withBody.
        py::list out;
        if (id >= 0 && id < s.contacts.indexedBodies())
          for (std::int64_t e = s.contacts.start[static_cast<std::size_t>(id)]; e < s.contacts.start[static_cast<std::size_t>(id) + 1]; ++e)
            out.append(contactDict(s.contacts.list[static_cast<std::size_t>(s.contacts.entries[static_cast<std::size_t>(e)] >> 1)]));
        return out;
      })
      .def("contactCount", [](const Scene& s, bool realOnly) { return realOnly ? s.contacts.countReal() : s.contacts.list.size(); })
      .def("eraseContact", &Scene::eraseContact)
      .def("eraseContacts", [](Scene& s) { s.contacts.removeIf([](const Contact&) { return true; }, s.bodies.size()); });
  void talus_wrap_bodies(py::module_&); talus_wrap_bodies(m); // after Engine, Scene: kinematics, clumps, boxes: bodies_wrappers.cpp
  void talus_wrap_force_engines(py::module_&); talus_wrap_force_engines(m); // force engines, loop callbacks: force_engines_wrappers.cpp
  void talus_wrap_blocks(py::module_&); talus_wrap_blocks(m); // Potential Blocks: blocks_wrappers.cpp
  void talus_wrap_particles(py::module_&); talus_wrap_particles(m); // Potential Particles: particles_wrappers.cpp
}
