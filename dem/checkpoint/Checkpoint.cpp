// HDF5 checkpoints of a Scene (compiled only when Talus is configured with HDF5): saving to a
// file atomically (written beside it, synced, renamed), loading (read and checked in full
// before the scene is touched), and the in-memory images of saveTmp/loadTmp. What the file
// holds is written and read by dem/checkpoint/ (WriteScene.cpp, ReadScene.cpp, Layout.h).
//
// Every HDF5 call is checked; HDF5's own printing of errors is switched off while a checkpoint
// is written or read, and the innermost message of its error stack is appended to ours instead.
#include "dem/checkpoint/Checkpoint.h"

#include "dem/checkpoint/Layout.h"
#include "dem/checkpoint/Temporaries.h"
#include "dem/checkpoint/Together.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <filesystem>

namespace talus::dem
{
using namespace checkpoint;

namespace
{
/// Move what was read into the scene. Vectors are copy-assigned so their storage is reused
/// when large enough (numpy views of the body arrays stay valid).
void commit(Scene& scene, const Loaded& in)
{
  scene.dt = in.dt;
  scene.time = in.time;
  scene.iter = in.iter;
  scene.clearFailedStep();
  scene.maxOverlapRatio = in.maxOverlapRatio;
  scene.maxEnergyGrowth = in.maxEnergyGrowth;
  scene.periodic = in.periodic;
  scene.cell = in.cell;
  // In place: Python holds references to the scene's materials (a deque, so appending keeps
  // them valid); only the references past the new count become invalid.
  const std::size_t kept = std::min(scene.materials.size(), in.materials.size());
  std::copy(in.materials.begin(), in.materials.begin() + static_cast<std::ptrdiff_t>(kept), scene.materials.begin());
  scene.materials.resize(kept);
  scene.materials.insert(scene.materials.end(), in.materials.begin() + static_cast<std::ptrdiff_t>(kept),
                         in.materials.end());
  // The block and particle contacts' settings belong to the engines (Ig2_PB_PB_ScGeom,
  // Ig2_PP_PP_ScGeom), not to the file.
  const BlockContactSettings blockContact = scene.bodies.blockContact;
  const ParticleContactSettings particleContact = scene.bodies.particleContact;
  scene.bodies = in.bodies;
  scene.bodies.blockContact = blockContact;
  scene.bodies.particleContact = particleContact;
  scene.contacts.list = in.contacts;
  scene.contacts.extra = in.contactExtra;
  scene.contacts.index(scene.bodies.size());
  scene.energy = in.energy;
  // Above both the scene's counters (its engines have seen those) and the saved ones.
  scene.bodiesVersion = std::max(scene.bodiesVersion, in.bodiesVersion) + 1;
  scene.bodyPropertiesVersion = std::max(scene.bodyPropertiesVersion, in.bodyPropertiesVersion) + 1;
}

/// File access properties of checkpoint files: the HDF5 1.10 object formats (checksummed
/// superblock and object headers, compact chunk indexes), readable by HDF5 1.10 and later.
Id fileAccess(const Context& ctx)
{
  Id fapl = ctx.checkId(H5Pcreate(H5P_FILE_ACCESS), H5Pclose, "cannot create a property list");
  ctx.check(H5Pset_libver_bounds(fapl.get(), H5F_LIBVER_V110, H5F_LIBVER_V110), "cannot set the file format");
  return fapl;
}

/// In-memory files (core driver). They keep the earliest formats: HDF5 1.10's
/// H5Fget_file_image returns a corrupted image for files with a checksummed superblock.
Id coreFileAccess(const Context& ctx)
{
  Id fapl = ctx.checkId(H5Pcreate(H5P_FILE_ACCESS), H5Pclose, "cannot create a property list");
  ctx.check(H5Pset_fapl_core(fapl.get(), std::size_t{1} << 20, 0), "cannot set up an in-memory file");
  return fapl;
}

std::string errnoText(int code) { return std::strerror(code); }

/// Make a written file durable before it replaces the old one.
void syncPath(const std::string& path, bool directory, const Context& ctx)
{
  const int fd = ::open(path.c_str(), (directory ? O_DIRECTORY : 0) | O_RDONLY | O_CLOEXEC);
  if (fd < 0)
  {
    if (directory)
      return; // best effort: some file systems do not open folders
    ctx.fail("cannot reopen " + quoted(path) + " to sync it: " + errnoText(errno), false);
  }
  const int status = ::fsync(fd);
  const int code = errno;
  ::close(fd);
  if (status != 0 && !directory)
    ctx.fail("cannot sync " + quoted(path) + " to disk: " + errnoText(code), false);
}

std::atomic<unsigned> uniqueCounter{0};

Loaded readFile(hid_t file, const Context& ctx)
{
  Loaded in;
  readScene(file, in, ctx);
  validate(in, ctx);
  return in;
}

/// The folder a checkpoint is saved in, once the target is checked (a name, in a folder that
/// exists, not itself a folder).
std::filesystem::path targetFolder(const std::string& path, const Context& ctx)
{
  namespace fs = std::filesystem;
  if (path.empty())
    ctx.fail("the file name is empty", false);
  const fs::path target(path);
  const fs::path folder = target.has_parent_path() ? target.parent_path() : fs::path(".");
  std::error_code ec;
  if (!fs::is_directory(folder, ec))
    ctx.fail("cannot write: the folder " + quoted(folder.string()) + " does not exist", false);
  if (fs::is_directory(target, ec))
    ctx.fail("cannot write: it is a folder", false);
  return folder;
}

/// Replace `path` by the written `temporary`: synced, renamed, the folder synced.
void replaceWith(const std::string& temporary, const std::string& path, const std::filesystem::path& folder,
                 const Context& ctx)
{
  syncPath(temporary, false, ctx);
  if (std::rename(temporary.c_str(), path.c_str()) != 0)
    ctx.fail("cannot replace the file with the new checkpoint: " + errnoText(errno), false);
  syncPath(folder.string(), true, ctx);
}
} // namespace

void saveCheckpoint(const Scene& scene, const std::string& path, const CheckpointExtras& extras)
{
  const Context ctx("checkpoint " + quoted(path));
  const QuietErrors quiet;
  const std::filesystem::path folder = targetFolder(path, ctx);
  removeStaleTemporaries(folder);
  const std::string temporary = temporaryPath(folder, std::filesystem::path(path));
  try
  {
    {
      const Id fapl = fileAccess(ctx);
      Id file = ctx.checkId(H5Fcreate(temporary.c_str(), H5F_ACC_EXCL, H5P_DEFAULT, fapl.get()), H5Fclose,
                            "cannot create the temporary file " + quoted(temporary));
      writeScene(file.get(), scene, extras, ctx, true);
      ctx.check(H5Fflush(file.get(), H5F_SCOPE_LOCAL), "cannot write (disk full?)");
      ctx.check(file.close(), "cannot finish writing (disk full?)");
    }
    replaceWith(temporary, path, folder, ctx);
  }
  catch (...)
  {
    ::unlink(temporary.c_str());
    throw;
  }
}

#ifdef H5_HAVE_PARALLEL
void checkpoint::saveCheckpointTogether(MPI_Comm comm, const Scene& part, const Slabs& slabs, const std::string& path,
                                        const CheckpointExtras& extras, const Agree& agree)
{
  const Context ctx("checkpoint " + quoted(path));
  const QuietErrors quiet;
  int rank = 0;
  MPI_Comm_rank(comm, &rank);
  // Process 0 checks the target and names the temporary file (its process id in the name).
  std::string error, temporary;
  std::filesystem::path folder;
  auto attempt = [&](auto&& step) {
    try
    {
      step();
    }
    catch (const CheckpointError& e)
    {
      error = e.what();
    }
  };
  if (rank == 0)
    attempt([&] {
      folder = targetFolder(path, ctx);
      removeStaleTemporaries(folder);
      temporary = temporaryPath(folder, std::filesystem::path(path));
    });
  agree(error);
  int length = static_cast<int>(temporary.size());
  MPI_Bcast(&length, 1, MPI_INT, 0, comm);
  temporary.resize(static_cast<std::size_t>(length));
  MPI_Bcast(temporary.data(), length, MPI_CHAR, 0, comm);

  // A process whose write failed removes the temporary file at once: the others may be held in
  // HDF5's own collective calls, and the run may end before process 0 would.
  const Agree afterEachDataset = [&](const std::string& localError) {
    if (!localError.empty())
      ::unlink(temporary.c_str());
    agree(localError);
  };
  attempt([&] {
    const Id fapl = fileAccess(ctx);
    ctx.check(H5Pset_fapl_mpio(fapl.get(), comm, MPI_INFO_NULL), "cannot set up parallel writing");
    Id file = ctx.checkId(H5Fcreate(temporary.c_str(), H5F_ACC_EXCL, H5P_DEFAULT, fapl.get()), H5Fclose,
                          "cannot create the temporary file " + checkpoint::quoted(temporary));
    // Collective transfers: the checksummed (filtered) datasets need them.
    const Id transfer = ctx.checkId(H5Pcreate(H5P_DATASET_XFER), H5Pclose, "cannot create a property list");
    ctx.check(H5Pset_dxpl_mpio(transfer.get(), H5FD_MPIO_COLLECTIVE), "cannot set up collective writing");
    writeScene(Writer(file.get(), ctx, true, transfer.get(), rank == 0, &afterEachDataset), file.get(), part, extras,
               ctx, &slabs);
    ctx.check(H5Fflush(file.get(), H5F_SCOPE_GLOBAL), "cannot write (disk full?)");
    ctx.check(file.close(), "cannot finish writing (disk full?)");
  });
  // Every process has written and closed its part before the file replaces the old one.
  try
  {
    agree(error);
  }
  catch (...)
  {
    if (rank == 0)
      ::unlink(temporary.c_str());
    throw;
  }
  if (rank == 0)
    attempt([&] {
      try
      {
        replaceWith(temporary, path, folder, ctx);
      }
      catch (...)
      {
        ::unlink(temporary.c_str());
        throw;
      }
    });
  agree(error);
}
#endif

CheckpointExtras loadCheckpoint(Scene& scene, const std::string& path)
{
  const Context ctx("checkpoint " + quoted(path));
  const QuietErrors quiet;
  struct stat st
  {
  };
  if (::stat(path.c_str(), &st) != 0)
    ctx.fail(errno == ENOENT ? std::string("no such file") : "cannot access it: " + errnoText(errno), false);
  if (S_ISDIR(st.st_mode))
    ctx.fail("it is a folder, not a checkpoint file", false);
  {
    const std::filesystem::path file(path);
    removeStaleTemporaries(file.has_parent_path() ? file.parent_path() : std::filesystem::path("."));
  }
  if (H5Fis_hdf5(path.c_str()) <= 0)
  {
    H5Eclear2(H5E_DEFAULT);
    ctx.fail("not an HDF5 file (a Talus checkpoint is written by O.save)", false);
  }
  const Id fapl = fileAccess(ctx);
  const Id file = ctx.checkId(H5Fopen(path.c_str(), H5F_ACC_RDONLY, fapl.get()), H5Fclose,
                              "cannot open it: the file is truncated or corrupted");
  const Loaded in = readFile(file.get(), ctx);
  commit(scene, in);
  return in.extras;
}

std::vector<std::uint8_t> saveCheckpointImage(const Scene& scene, const CheckpointExtras& extras)
{
  const Context ctx("in-memory checkpoint");
  const QuietErrors quiet;
  const Id fapl = coreFileAccess(ctx);
  const std::string name = "talus-image-" + std::to_string(::getpid()) + "-" + std::to_string(uniqueCounter++);
  Id file = ctx.checkId(H5Fcreate(name.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, fapl.get()), H5Fclose,
                        "cannot create an in-memory file");
  writeScene(file.get(), scene, extras, ctx, false);
  ctx.check(H5Fflush(file.get(), H5F_SCOPE_LOCAL), "cannot flush the in-memory file");
  const ssize_t size = ctx.check(H5Fget_file_image(file.get(), nullptr, 0), "cannot get the in-memory file");
  std::vector<std::uint8_t> image(static_cast<std::size_t>(size));
  ctx.check(H5Fget_file_image(file.get(), image.data(), image.size()), "cannot get the in-memory file");
  ctx.check(file.close(), "cannot close the in-memory file");
  return image;
}

CheckpointExtras loadCheckpointImage(Scene& scene, const std::vector<std::uint8_t>& image, const std::string& name)
{
  const Context ctx(name);
  const QuietErrors quiet;
  static constexpr std::array<std::uint8_t, 8> signature = {0x89, 'H', 'D', 'F', '\r', '\n', 0x1a, '\n'};
  if (image.size() < signature.size() || !std::equal(signature.begin(), signature.end(), image.begin()))
    ctx.fail("not an HDF5 image", false);
  const Id fapl = coreFileAccess(ctx);
  ctx.check(H5Pset_file_image(fapl.get(), const_cast<std::uint8_t*>(image.data()), image.size()),
            "cannot use the image");
  const std::string fileName = "talus-image-" + std::to_string(::getpid()) + "-" + std::to_string(uniqueCounter++);
  const Id file = ctx.checkId(H5Fopen(fileName.c_str(), H5F_ACC_RDONLY, fapl.get()), H5Fclose,
                              "cannot open it: the image is truncated or corrupted");
  const Loaded in = readFile(file.get(), ctx);
  commit(scene, in);
  return in.extras;
}
} // namespace talus::dem
