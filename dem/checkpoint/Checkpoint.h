#pragma once

#include <cstdint>
#include <map>
#include <stdexcept>
#include <string>
#include <vector>

namespace talus::dem
{
class Scene;

/// True when this build writes and reads checkpoints (Talus was configured with HDF5). Without
/// HDF5 the functions below are declared but not defined: callers test this flag first.
#ifdef TALUS_HAVE_HDF5
inline constexpr bool haveCheckpoints = true;
#else
inline constexpr bool haveCheckpoints = false;
#endif

/// Layout version written in the root attribute `format_version`. Version 8 stores the real
/// contacts only; version 7 (every candidate pair) has the same layout and is read as well.
inline constexpr int checkpointFormatVersion = 8;
/// The oldest version read back.
inline constexpr int oldestCheckpointFormatVersion = 7;
/// Value of the root attribute `magic` of every Talus checkpoint.
inline constexpr const char* checkpointMagic = "talus-checkpoint";

/// Named text records stored beside the scene, under `/extras` (the Python layer keeps its
/// engine list there, as JSON). Names are letters, digits, '_' and '-'.
using CheckpointExtras = std::map<std::string, std::string>;

/// A checkpoint could not be written or read. The message names the file (or memory slot) and
/// what is wrong with it.
class CheckpointError : public std::runtime_error
{
public:
  using std::runtime_error::runtime_error;
};

/// Write everything a run needs to continue bit-identically: the clock (dt, time, iter), the
/// scene's settings (maxOverlapRatio), the periodic cell, every material, every body array
/// (erased slots, blocked DOFs, external forces, every shape included) and the real
/// contacts in list order with their full state (ids, kind, real, fresh, law, periodic image,
/// geometry, physics, shear history, forces) with the richer models' state (Contacts::extra),
/// and the energy tracker. Engines are not stored (they are Python
/// objects; the Python layer stores their parameters in `extras`).
///
/// The write is atomic: the checkpoint goes to a temporary file in the target's folder, is
/// flushed, synced and closed, and only then renamed over `path`. On failure the temporary file
/// is removed, an existing file at `path` is left untouched, and CheckpointError is thrown.
/// The temporary files that saves killed mid-write left in the folder are removed first (those
/// of processes of this host that no longer run); loadCheckpoint does the same.
///
/// HDF5 layout: root attributes `magic`, `format_version`,
/// `talus_version`; groups `clock`, `settings`, `energy`, `cell`, `materials`, `bodies` (with
/// `walls`, `facets`, `boxes`, `clumps`, `blocks`, `particles`: Potential Blocks and Particles
/// with their derived geometry), `contacts` (with `extra`), `extras` (docs/dem-io.md lists every
/// dataset). Numeric datasets are chunked with a Fletcher-32 checksum, and the object headers
/// carry metadata checksums, so corruption is detected when reading.
/// @param[in] scene the scene to save
/// @param[in] path the checkpoint file (conventionally `*.h5`); its folder must exist
/// @param[in] extras text records stored under `/extras`
/// @throws CheckpointError naming the file and the cause
void saveCheckpoint(const Scene& scene, const std::string& path, const CheckpointExtras& extras = {});

/// Restore a checkpoint written by saveCheckpoint into `scene` (bodies, materials, contacts,
/// clock). Engines are left as they are. The file is read and checked completely before the
/// scene changes, so on error the scene is untouched. Body arrays keep their storage when the
/// body count does not grow (array views handed out before stay valid); materials are assigned
/// in place, so references to the first min(old, new) materials stay valid. `bodiesVersion` and
/// `bodyPropertiesVersion` are set above both their current and their saved values, so every
/// engine refreshes its caches and the collider re-detects at the next step.
/// @param[in,out] scene the scene restored into
/// @param[in] path the checkpoint file
/// @return the text records stored under `/extras`
/// @throws CheckpointError naming the file and what is wrong (missing, not HDF5, truncated,
///         corrupted, not a Talus checkpoint, other format version, inconsistent content)
CheckpointExtras loadCheckpoint(Scene& scene, const std::string& path);

/// The same checkpoint as saveCheckpoint, built in memory (HDF5 core driver): the bytes of an
/// HDF5 file. Used by saveTmp/loadTmp.
/// @param[in] scene the scene to save
/// @param[in] extras text records stored under `/extras`
/// @return the bytes of the HDF5 file
/// @throws CheckpointError naming the cause
std::vector<std::uint8_t> saveCheckpointImage(const Scene& scene, const CheckpointExtras& extras = {});

/// Restore a checkpoint from the bytes made by saveCheckpointImage (or read from a file).
/// @param[in,out] scene the scene restored into (untouched on error)
/// @param[in] image the bytes of the HDF5 file
/// @param[in] name what to call the image in error messages (e.g. "saveTmp slot 'init'")
/// @return the text records stored under `/extras`
/// @throws CheckpointError as loadCheckpoint
CheckpointExtras loadCheckpointImage(Scene& scene, const std::vector<std::uint8_t>& image, const std::string& name);
} // namespace talus::dem
