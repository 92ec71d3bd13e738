// talus._distributed: the MPI domain a scene runs in under `mpirun -np N talus run`
// (talus.dem.distributed sets it up and reads the global answers through it).
#include "dem/core/Scene.h"
#include "dem/distributed/Collective.h"
#include "dem/distributed/collect/Gather.h"
#include "dem/distributed/script/Channel.h"
#include "dem/distributed/script/Snapshot.h"
#include "dem/measure/Energy.h"
#include "dem/measure/Measurements.h"
#include "dem/distributed/MpiDomain.h"

#include <pybind11/eigen.h>
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <algorithm>
#include <limits>
#include <memory>
#include <optional>
#include <stdexcept>

namespace py = pybind11;
using namespace talus::dem;
using namespace talus::dem::distributed;

namespace
{
/// Per global id, the values `value` writes for each body, from the rank owning it (rank 0 for
/// a wall, which every rank holds): the whole scene's on every rank.
template <class Value>
std::vector<double> byGlobalId(const MpiDomain& d, const Scene& s, Value&& value, std::size_t width)
{
  std::vector<double> total(static_cast<std::size_t>(d.globalCount()) * width, 0.0);
  for (std::size_t i = 0; i < s.bodies.size(); ++i)
    if (d.countsBody(i))
      value(i, total.data() + static_cast<std::size_t>(d.globalIdOf(i)) * width);
  d.sum(total);
  return total;
}
} // namespace

PYBIND11_MODULE(_distributed, m)
{
  m.doc() = "The DEM over MPI ranks: the domain of a scene under mpirun (talus.dem.distributed)";
  py::register_exception<CollectiveError>(m, "CollectiveError", PyExc_RuntimeError);
  m.def("init", [] {
    int initialised = 0;
    MPI_Initialized(&initialised);
    if (!initialised)
    {
      int provided = 0;
      MPI_Init_thread(nullptr, nullptr, MPI_THREAD_FUNNELED, &provided);
    }
    int rank = 0, ranks = 1;
    MPI_Comm_rank(MPI_COMM_WORLD, &rank);
    MPI_Comm_size(MPI_COMM_WORLD, &ranks);
    openScriptChannel();
    return py::make_tuple(rank, ranks);
  });
  m.attr("snapshot_doubles") = snapshotDoubles;
  m.def("script_gather", [](const py::array_t<double, py::array::c_style | py::array::forcecast>& mine, double patience,
                            const std::string& waiting) {
    std::vector<double> all = gatherOnScriptChannel(std::span<const double>(mine.data(), static_cast<std::size_t>(mine.size())),
                                                    patience, waiting);
    const auto width = static_cast<py::ssize_t>(mine.size());
    py::array_t<double> table({static_cast<py::ssize_t>(all.size()) / std::max<py::ssize_t>(width, 1), width});
    std::copy(all.begin(), all.end(), table.mutable_data());
    return table;
  }, py::arg("mine"), py::arg("patience"), py::arg("waiting"),
     "Every rank's `mine` (one length on all), a row per rank, on every rank, over the script's own channel "
     "(collective: talus.dem.split.by_id); a rank the others leave alone for `patience` seconds prints `waiting` "
     "and ends the run");
  m.def("finalize", [] {
    int initialised = 0, finalised = 0;
    MPI_Initialized(&initialised);
    MPI_Finalized(&finalised);
    if (initialised && !finalised)
      MPI_Finalize();
  });
  m.def("abort", [](int code) { MPI_Abort(MPI_COMM_WORLD, code); });
  m.def("barrier", [] { MPI_Barrier(MPI_COMM_WORLD); });
  m.def("all_agree", [](bool local) {
    int all = local ? 1 : 0;
    MPI_Allreduce(MPI_IN_PLACE, &all, 1, MPI_INT, MPI_LAND, MPI_COMM_WORLD);
    return all != 0;
  }, "True on every rank when `local` is true on all (collective)");
  m.def("smallest", [](double local) {
    MPI_Allreduce(MPI_IN_PLACE, &local, 1, MPI_DOUBLE, MPI_MIN, MPI_COMM_WORLD);
    return local;
  }, "The smallest of every rank's `local` (collective): a scene not split yet (built in slabs)");
  m.def("gather_rows", [](const py::array_t<double, py::array::c_style | py::array::forcecast>& local, int root) {
    // Every rank's rows of one width, one after the other in rank order: what each rank holds of
    // the whole scene (its own bodies) put together where it is written or read whole.
    if (local.ndim() != 2)
      throw std::invalid_argument("gather_rows: a table of rows (2 dimensions) is needed");
    int rank = 0, ranks = 1;
    MPI_Comm_rank(MPI_COMM_WORLD, &rank);
    MPI_Comm_size(MPI_COMM_WORLD, &ranks);
    const auto width = static_cast<int>(local.shape(1));
    const int mine = static_cast<int>(local.size());
    std::vector<int> counts(static_cast<std::size_t>(ranks)), starts(static_cast<std::size_t>(ranks), 0);
    const bool everyRank = root < 0;
    if (everyRank)
      MPI_Allgather(&mine, 1, MPI_INT, counts.data(), 1, MPI_INT, MPI_COMM_WORLD);
    else
      MPI_Gather(&mine, 1, MPI_INT, counts.data(), 1, MPI_INT, root, MPI_COMM_WORLD);
    std::int64_t total = 0;
    for (std::size_t r = 0; r < counts.size(); ++r)
    {
      starts[r] = static_cast<int>(total);
      total += counts[r];
    }
    if (total > std::numeric_limits<int>::max())
      throw std::overflow_error("gather_rows: more than 2^31 numbers");
    const bool receives = everyRank || rank == root;
    py::array_t<double> all({static_cast<py::ssize_t>(receives && width ? total / width : 0), static_cast<py::ssize_t>(width)});
    if (everyRank)
      MPI_Allgatherv(local.data(), mine, MPI_DOUBLE, all.mutable_data(), counts.data(), starts.data(), MPI_DOUBLE,
                     MPI_COMM_WORLD);
    else
      MPI_Gatherv(local.data(), mine, MPI_DOUBLE, receives ? all.mutable_data() : nullptr, counts.data(), starts.data(),
                  MPI_DOUBLE, root, MPI_COMM_WORLD);
    return all;
  }, py::arg("local"), py::arg("root"),
     "Every rank's rows (a table of one width) in rank order, on rank `root` (an empty table elsewhere) or on "
     "every rank when `root` is negative (collective)");

  py::class_<MpiDomain, std::shared_ptr<MpiDomain>>(m, "Domain")
      .def_property_readonly("rank", &MpiDomain::rank)
      .def_property_readonly("ranks", &MpiDomain::ranks)
      .def_property_readonly("globalCount", &MpiDomain::globalCount)
      .def_property_readonly("ghostDistance", &MpiDomain::ghostDistance)
      .def_property_readonly("hasClumps", &MpiDomain::hasClumps)
      .def("rowOf", &MpiDomain::rowOf)
      .def("owns", [](const MpiDomain& d, std::int64_t row) { return row >= 0 && d.owns(static_cast<std::size_t>(row)); })
      .def("sum", [](const MpiDomain& d, std::vector<double> v) {
        d.sum(v);
        return v;
      })
      .def("min", [](const MpiDomain& d, double v) { return d.min(v); })
      .def("minima", [](const MpiDomain& d, std::vector<double> v) {
        d.min(v);
        return v;
      }, "Element-wise minima over the ranks (collective)")
      .def("traffic", [](const MpiDomain& d) {
        const MpiDomain::Traffic& t = d.traffic();
        py::dict out;
        out["updates"] = t.updates;
        out["update_bytes"] = t.updateBytes;
        out["update_messages"] = t.updateMessages;
        out["rebuilds"] = t.rebuilds;
        out["rebuild_bytes"] = t.rebuildBytes;
        out["migrated_bodies"] = t.migratedBodies;
        out["migrated_contacts"] = t.migratedContacts;
        out["update_seconds"] = t.updateSeconds;
        out["rebuild_seconds"] = t.rebuildSeconds;
        out["reduction_seconds"] = t.reductionSeconds;
        out["split_seconds"] = t.splitSeconds;
        out["wait_cpu_seconds"] = t.waitCpuSeconds;
        return out;
      })
      .def("resetTraffic", &MpiDomain::resetTraffic)
      .def("updateGhosts", &MpiDomain::afterIntegration,
           "Send the owned bodies' state to their ghosts (collective): what a script wrote into its bodies between "
           "two steps reaches the other ranks' copies before the next contacts are computed")
      .def_property("rebalanceThreshold", [](const MpiDomain& d) { return d.balance().threshold(); },
                    &MpiDomain::setRebalanceThreshold,
                    "Measured imbalance above which the ranks partition again (every rank sets the same)")
      .def("balance", [](const MpiDomain& d) {
        const Balance::Stats& b = d.balance().stats();
        py::dict out;
        out["compute_seconds"] = d.computeSeconds();
        out["slowest_seconds"] = b.slowestSeconds;
        out["mean_seconds"] = b.meanSeconds;
        out["rebalances"] = b.rebalances;
        out["imbalance_before"] = b.imbalanceBefore;
        out["imbalance_after"] = b.imbalanceAfter;
        out["per_body_seconds"] = b.perBody;
        out["per_contact_seconds"] = b.perContact;
        out["threshold"] = d.balance().threshold();
        py::list intervals;
        for (const Balance::Interval& i : b.intervals)
          intervals.append(py::make_tuple(i.iter, i.steps, i.imbalance, i.rebalanced));
        out["intervals"] = intervals;
        return out;
      }, "The load measured at the re-detections: this rank's compute seconds, the rest the same on every rank")
      .def("load", [](const MpiDomain& d, const Scene& s) {
        // What this rank holds and computes now: its spheres, its ghosts, the contacts it computes
        // and, of those, the ones with a ghost (computed by its owner too).
        py::dict out;
        std::int64_t spheres = 0, withGhost = 0;
        for (std::size_t i = 0; i < s.bodies.size(); ++i)
          spheres += d.owns(i) && !d.replicated(i) && s.bodies.alive[i] ? 1 : 0;
        for (const Contact& c : s.contacts.list)
          withGhost += !d.owns(static_cast<std::size_t>(c.id1)) || !d.owns(static_cast<std::size_t>(c.id2)) ? 1 : 0;
        out["spheres"] = spheres;
        out["ghosts"] = static_cast<std::int64_t>(d.ghosts());
        out["contacts"] = static_cast<std::int64_t>(s.contacts.list.size());
        out["ghost_contacts"] = withGhost;
        py::list regions;
        for (const Box& r : d.regions())
          regions.append(py::make_tuple(r.min, r.max));
        out["regions"] = regions;
        return out;
      }, "This rank's spheres, ghosts, contacts computed (with a ghost among them) and every rank's region")
      .def("erase", [](MpiDomain& d, Scene& s, std::int64_t id, bool members) { return d.erase(s, id, members); },
           py::arg("scene"), py::arg("id"), py::arg("eraseClumpMembers") = false,
           "Erase body `id` on every rank (every rank calls it with the same ids); False if erased already")
      .def("ownedBodies", [](const MpiDomain& d, const Scene& s) {
        std::vector<std::int64_t> rows, ids;
        for (std::size_t i = 0; i < s.bodies.size(); ++i)
          if (d.owns(i) && !d.replicated(i))
          {
            rows.push_back(static_cast<std::int64_t>(i));
            ids.push_back(d.globalIdOf(i));
          }
        return py::make_tuple(py::array_t<std::int64_t>(static_cast<py::ssize_t>(rows.size()), rows.data()),
                              py::array_t<std::int64_t>(static_cast<py::ssize_t>(ids.size()), ids.data()));
      }, "The rows of the bodies this rank owns (the walls, which every rank holds, left out) and their global "
         "ids, both ascending")
      .def("rowsActedOn", [](const MpiDomain& d, const py::array_t<std::int64_t, py::array::c_style | py::array::forcecast>& ids) {
        std::vector<std::int64_t> rows;
        rows.reserve(static_cast<std::size_t>(ids.size()));
        for (py::ssize_t k = 0; k < ids.size(); ++k)
          if (const std::int64_t row = d.rowOf(ids.data()[k]);
              row >= 0 && (d.owns(static_cast<std::size_t>(row)) || d.replicated(static_cast<std::size_t>(row))))
            rows.push_back(row);
        return py::array_t<std::int64_t>(static_cast<py::ssize_t>(rows.size()), rows.data());
      }, "The rows of the bodies of `ids` this rank acts on, in the order of `ids`: those it owns and the walls, "
         "facets and boxes (every rank holds them); erased bodies and other ranks' left out")
      .def("snapshots", [](const MpiDomain& d, const Scene& s,
                           const py::array_t<std::int64_t, py::array::c_style | py::array::forcecast>& rows) {
        py::array_t<double> table({static_cast<py::ssize_t>(rows.size()), static_cast<py::ssize_t>(snapshotDoubles)});
        for (py::ssize_t k = 0; k < rows.size(); ++k)
          snapshotOf(d, s, static_cast<std::size_t>(rows.data()[k]), table.mutable_data() + k * static_cast<py::ssize_t>(snapshotDoubles));
        return table;
      }, "The snapshots of rows `rows` (a row of script/Snapshot.h's numbers each)")
      .def("readById", [](const MpiDomain& d, const Scene& s, std::int64_t id, double patience, const std::string& rule) {
        ScriptRead read = readById(d, s, id, patience, rule);
        const auto width = static_cast<py::ssize_t>(placeDoubles + snapshotDoubles);
        py::array_t<double> rows({static_cast<py::ssize_t>(read.rows.size()) / width, width});
        std::copy(read.rows.begin(), read.rows.end(), rows.mutable_data());
        return py::make_tuple(read.local, read.row, read.agreed, rows);
      }, "O.bodies[id] as every rank reads it (talus.dem.split.by_id): (local, row here or -1, whether every rank "
         "read it, every rank's place, id, sent flag and snapshot)")
      .def("positions", [](const MpiDomain& d, const Scene& s) {
        std::vector<double> all = byGlobalId(d, s, [&](std::size_t i, double* out) {
          for (int k = 0; k < 3; ++k)
            out[k] = s.bodies.pos[i][k];
        }, 3);
        py::array_t<double> a({static_cast<py::ssize_t>(d.globalCount()), py::ssize_t{3}});
        std::copy(all.begin(), all.end(), a.mutable_data());
        return a;
      }, "Positions of every body by global id, on every rank (collective)")
      .def("gather", [](const MpiDomain& d, const Scene& s, const std::vector<GlobalId>& ids) {
        const std::vector<double> state = gatherBodies(d, s, ids);
        py::array_t<double> a({static_cast<py::ssize_t>(ids.size()), static_cast<py::ssize_t>(gatheredDoubles)});
        std::copy(state.begin(), state.end(), a.mutable_data());
        return a;
      }, "The state of bodies `ids`, a row of gatheredDoubles each, on every rank (collective)")
      .def("bodyStressTensors", [](const MpiDomain& d, const Scene& s) {
        // A rank holds every contact of the bodies it owns: their tensors are whole there.
        const std::vector<Mat3> local = bodyStressTensors(s);
        std::vector<double> all = byGlobalId(d, s, [&](std::size_t i, double* out) {
          Eigen::Map<Mat3>{out} = local[i];
        }, 9);
        py::array_t<double> a({static_cast<py::ssize_t>(d.globalCount()), py::ssize_t{3}, py::ssize_t{3}});
        for (std::size_t k = 0; k < static_cast<std::size_t>(d.globalCount()); ++k)
          Eigen::Map<Eigen::Matrix<double, 3, 3, Eigen::RowMajor>>(a.mutable_data() + 9 * k) = Eigen::Map<const Mat3>(all.data() + 9 * k);
        return a;
      }, "Yade's bodyStressTensors of every body by global id, on every rank (collective)")
      .def("forceOf", [](const MpiDomain& d, const Scene& s, std::int64_t id) {
        // Walls are held by every rank, each with the force of its own spheres' contacts.
        std::vector<double> ft(6, 0.0);
        const std::int64_t row = d.rowOf(id);
        if (row >= 0 && d.owns(static_cast<std::size_t>(row)))
          for (int k = 0; k < 3; ++k)
          {
            ft[static_cast<std::size_t>(k)] = s.bodies.force[static_cast<std::size_t>(row)][k];
            ft[static_cast<std::size_t>(k) + 3] = s.bodies.torque[static_cast<std::size_t>(row)][k];
          }
        d.sum(ft);
        return ft;
      }, "Force and torque of body `id` summed over the ranks holding it as their own (collective)")
      .def("globalIds", [](const MpiDomain& d, std::vector<std::int64_t> rows) {
        for (std::int64_t& r : rows)
          r = r >= 0 ? d.globalIdOf(static_cast<std::size_t>(r)) : r;
        return rows;
      }, "The global ids of rows `rows` here (a negative entry, no row, stays)")
      .def("counted", [](const MpiDomain& d, const Scene& s) {
        py::array_t<bool> out(static_cast<py::ssize_t>(s.bodies.size()));
        for (std::size_t i = 0; i < s.bodies.size(); ++i)
          out.mutable_data()[i] = d.countsBody(i);
        return out;
      }, "Per row, whether sums over bodies count it on this rank (each body on one rank)")
      .def("kineticEnergy", [](const MpiDomain& d, const Scene& s) {
        std::vector<double> e{kineticEnergy(s)}; // the bodies this rank counts (a clump with its members once)
        d.sum(e);
        return e[0];
      }, "Total kinetic energy of the dynamic bodies (collective)");

  m.def("attach", [](const std::shared_ptr<Scene>& scene, const std::string& method,
                     const std::optional<py::array_t<std::int64_t>>& globalIds,
                     const std::optional<py::array_t<std::uint8_t>>& own, std::int64_t count) {
    PartitionSettings settings;
    settings.method = method;
    std::optional<HeldRows> held;
    if (globalIds)
    {
      if (!own || own->size() != globalIds->size() || globalIds->size() != static_cast<py::ssize_t>(scene->bodies.size()))
        throw std::invalid_argument("attach: global_ids and own need one entry per row of the scene");
      held = HeldRows{{globalIds->data(), globalIds->data() + globalIds->size()}, {own->data(), own->data() + own->size()},
                      count};
    }
    auto domain = std::make_shared<MpiDomain>(MPI_COMM_WORLD, *scene, settings, held ? &*held : nullptr);
    scene->domain = domain;
    return domain;
  }, py::arg("scene"), py::arg("method") = "RCB", py::arg("global_ids") = py::none(), py::arg("own") = py::none(),
        py::arg("count") = 0,
        "Split `scene` over the ranks of MPI_COMM_WORLD (collective): built whole on every rank, or in slabs "
        "(each row's global id, whether it is of this rank's slab only, and the whole scene's body count)");
}
