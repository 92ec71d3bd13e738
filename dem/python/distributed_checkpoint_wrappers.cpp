// talus._distributed_checkpoint: O.save / O.load of a scene under `mpirun -np N talus run`
// (one file written by every rank; talus.dem.files.io calls it).
#include "dem/core/Scene.h"
#include "dem/distributed/collect/Checkpoint.h"
#include "dem/distributed/MpiDomain.h"

#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <memory>

namespace py = pybind11;
using namespace talus::dem;
using namespace talus::dem::distributed;

PYBIND11_MODULE(_distributed_checkpoint, m)
{
  m.doc() = "Checkpoints of a scene split over MPI ranks (talus.dem.files.io under mpirun)";
  // A CheckpointError (talus._dem's) that every rank raised alike.
  py::register_exception<CollectiveCheckpointError>(m, "CollectiveCheckpointError",
                                                    py::module_::import("talus._dem").attr("CheckpointError"));
  m.def("save", [](const std::shared_ptr<MpiDomain>& domain, Scene& scene, const std::string& path,
                   const CheckpointExtras& extras) {
    py::gil_scoped_release release;
    saveCheckpoint(MPI_COMM_WORLD, domain.get(), scene, path, extras);
  }, py::arg("domain"), py::arg("scene"), py::arg("path"), py::arg("extras"),
        "Write the checkpoint of `scene`, split by `domain` (None: whole on every rank, written by rank 0), to "
        "`path`: one file written by every rank (collective)");
  m.def("load", [](Scene& scene, const std::string& path) {
    CheckpointExtras extras;
    {
      py::gil_scoped_release release;
      extras = loadCheckpoint(MPI_COMM_WORLD, scene, path);
    }
    return extras;
  }, py::arg("scene"), py::arg("path"),
        "Read the checkpoint at `path` into `scene` on every rank, the scene split again at its next step (collective)");
}
