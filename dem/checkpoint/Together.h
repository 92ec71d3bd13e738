// One checkpoint file written by several processes together (parallel HDF5; internal, not
// installed): the layout of saveCheckpoint, each process writing its rows of the bodies and
// contacts, with the same atomic replacement of the target.
#pragma once

#include "dem/checkpoint/Layout.h"

#ifdef H5_HAVE_PARALLEL
namespace talus::dem::checkpoint
{
/// Write the checkpoint of a scene spread over the processes of `comm` (collective): process 0
/// checks the target and names a temporary file beside it; every process writes its rows
/// (`slabs`) of `part` into it with collective transfers; only once every process has written
/// and closed it does process 0 sync it and rename it over `path`. A failure on any process
/// removes the temporary file and leaves a file at `path` as it was.
/// @param comm the processes writing (every one calls it)
/// @param part this process's rows of the bodies and contacts (global ids), and what every
///        process holds alike (clock, settings, materials, shape tables, cell, energy)
/// @param slabs where this process's rows go in the file
/// @param path the checkpoint file
/// @param extras the text records, the same on every process
/// @param agree the collective check between the steps and after each dataset (Agree: every
///        process throws the lowest failing process's message)
/// @throws CheckpointError on every process, with one message
void saveCheckpointTogether(MPI_Comm comm, const Scene& part, const Slabs& slabs, const std::string& path,
                            const CheckpointExtras& extras, const Agree& agree);
} // namespace talus::dem::checkpoint
#endif
