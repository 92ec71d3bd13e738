#pragma once

#include "dem/checkpoint/Checkpoint.h"

#include <mpi.h>

#include <string>

namespace talus::dem::distributed
{
class MpiDomain;

/// A checkpoint error raised on every rank alike, with one message (the lowest failing rank's):
/// each rank may report it and stop on its own, none is left waiting for the others.
struct CollectiveCheckpointError : CheckpointError
{
  using CheckpointError::CheckpointError;
};

/// Write the checkpoint of a scene split over the ranks of `comm` (collective): one file, in the
/// layout of the serial checkpoint (dem/checkpoint/Checkpoint.h), written by every rank with
/// parallel HDF5. The bodies go to "I/O order" first: rank r takes the global ids
/// [r N / P, (r + 1) N / P) (its own from its copy for the bodies every rank holds, walls and
/// facets, their forces summed over the ranks; the others' from their owners) and writes them as
/// one slab; each contact goes once (from the rank that counts it: the owner of its first body,
/// or of its sphere when the first is replicated) to the rank of its first body's slab, so the
/// file's contacts are sorted by (id1, id2) as a serial file's. A file written at any rank count
/// is read like a serial one. Erased bodies (no rank holds them) are written as erased slots
/// with zero state. The text records are process 0's.
///
/// Atomic as the serial save: written to a temporary file beside `path`, renamed by rank 0 only
/// once every rank has written and closed it; a failure on any rank leaves a file at `path` as
/// it was.
///
/// Before the split (no domain), every rank holds the whole scene: process 0 writes it with the
/// serial writer, the others wait for the outcome.
/// @param comm the ranks of the domain (every one calls it)
/// @param domain the split of `scene`; null: the scene is whole on every rank
/// @param scene this rank's part (its bodies are lent to the row exchange and given back)
/// @param path the checkpoint file
/// @param extras text records stored under `/extras` (process 0's are written)
/// @throws CollectiveCheckpointError on every rank, naming the file and the cause
void saveCheckpoint(MPI_Comm comm, const MpiDomain* domain, Scene& scene, const std::string& path,
                    const CheckpointExtras& extras);

/// Read a checkpoint, serial or written by saveCheckpoint at any rank count, into `scene` on
/// every rank of `comm` (collective): every rank reads the whole file (as every rank builds the
/// whole scene from a script) and the scene is split again when its next step starts
/// (`scene.domain` is dropped). Every rank reads the same file, so all fail alike; the error is
/// still agreed on, so that none goes on alone.
/// @param comm the ranks (every one calls it)
/// @param scene restored (untouched where the file is refused)
/// @param path the checkpoint file
/// @return the text records stored under `/extras`
/// @throws CollectiveCheckpointError on every rank, naming the file and what is wrong
CheckpointExtras loadCheckpoint(MPI_Comm comm, Scene& scene, const std::string& path);
} // namespace talus::dem::distributed
