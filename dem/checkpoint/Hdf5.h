// HDF5 plumbing of the checkpoints (dem/checkpoint/Checkpoint.cpp and dem/checkpoint/*.cpp; internal, not
// installed): owned identifiers, errors with HDF5's innermost message, quiet error printing,
// and the Writer and Reader of datasets and attributes.
#pragma once

#include "dem/checkpoint/Checkpoint.h"
#include "dem/core/Scene.h"
#include "dem/base/build_config.h"

#include <hdf5.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <functional>
#include <limits>
#include <string>
#include <utility>
#include <vector>

namespace talus::dem::checkpoint
{
static_assert(sizeof(Vec3) == 3 * sizeof(double), "Vec3 arrays are written as (n, 3) doubles");

// ----------------------------------------------------------------------------------------------
// HDF5 plumbing: owned identifiers, errors, quiet error printing.

/// An HDF5 identifier closed on destruction (unless released or already closed).
class Id
{
public:
  using Closer = herr_t (*)(hid_t);
  Id() = default;
  Id(hid_t id, Closer closer) : id_(id), closer_(closer) {}
  Id(const Id&) = delete;
  Id& operator=(const Id&) = delete;
  Id(Id&& other) noexcept : id_(std::exchange(other.id_, H5I_INVALID_HID)), closer_(other.closer_) {}
  Id& operator=(Id&& other) noexcept
  {
    if (this != &other)
    {
      close();
      id_ = std::exchange(other.id_, H5I_INVALID_HID);
      closer_ = other.closer_;
    }
    return *this;
  }
  ~Id() { close(); }

  /// @return the identifier (H5I_INVALID_HID once closed or moved from); still owned here
  [[nodiscard]] hid_t get() const { return id_; }
  /// @return whether it holds an identifier
  [[nodiscard]] bool valid() const { return id_ >= 0; }
  /// Close now (later calls do nothing).
  /// @return HDF5's status, negative on failure
  herr_t close()
  {
    herr_t status = 0;
    if (id_ >= 0 && closer_)
      status = closer_(id_);
    id_ = H5I_INVALID_HID;
    return status;
  }

private:
  hid_t id_ = H5I_INVALID_HID;
  Closer closer_ = nullptr;
};

/// Skip HDF5's exit handler, when we are the first to use HDF5 in the process. HDF5 1.10 leaks
/// internal free-list blocks on some error paths (a checksum failure while reading a damaged
/// file), and its exit handler then prints "infinite loop closing library" and a line of
/// garbage. Checkpoint files are always closed before our functions return, so the handler has
/// nothing to do for us.
inline void skipExitHandler()
{
  static const bool done = [] {
    H5dont_atexit();
    return true;
  }();
  (void)done;
}

/// Switches off HDF5's printing of its error stack for the guard's lifetime (restored after).
class QuietErrors
{
public:
  /// Turn the printing off, remembering HDF5's handler (skipExitHandler too).
  QuietErrors()
  {
    skipExitHandler();
    H5Eget_auto2(H5E_DEFAULT, &func_, &data_);
    H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr);
  }
  QuietErrors(const QuietErrors&) = delete;
  QuietErrors& operator=(const QuietErrors&) = delete;
  ~QuietErrors() { H5Eset_auto2(H5E_DEFAULT, func_, data_); }

private:
  H5E_auto2_t func_ = nullptr;
  void* data_ = nullptr;
};

/// The most specific message of HDF5's current error stack, or "" if it is empty.
/// @return the message, with its minor code's text; the stack is cleared
inline std::string hdf5Detail()
{
  std::string detail;
  auto walk = [](unsigned n, const H5E_error2_t* err, void* out) -> herr_t {
    if (n == 0 && err != nullptr && err->desc != nullptr)
    {
      auto& text = *static_cast<std::string*>(out);
      text = err->desc;
      char minor[256] = {};
      if (H5Eget_msg(err->min_num, nullptr, minor, sizeof(minor)) > 0 && text.find(minor) == std::string::npos)
        text += std::string(" [") + minor + "]";
    }
    return 0;
  };
  H5Ewalk2(H5E_DEFAULT, H5E_WALK_UPWARD, walk, &detail);
  H5Eclear2(H5E_DEFAULT);
  return detail;
}

/// Where a checkpoint lives, for messages: "checkpoint 'run.h5'" or "saveTmp slot 'init'".
class Context
{
public:
  /// @param what how messages name the checkpoint ("checkpoint 'run.h5'")
  explicit Context(std::string what) : what_(std::move(what)) {}

  /// Throw CheckpointError with our message and, if any, HDF5's innermost one.
  /// @param message what failed ("cannot read /bodies/pos")
  /// @param withHdf5 append HDF5's message (false for our own checks of a readable file)
  /// @throws CheckpointError always
  [[noreturn]] void fail(const std::string& message, bool withHdf5 = true) const
  {
    std::string text = what_ + ": " + message;
    if (withHdf5)
    {
      const std::string detail = hdf5Detail();
      if (!detail.empty())
        text += " (HDF5: " + detail + ")";
    }
    throw CheckpointError(text);
  }
  /// Fail unless an HDF5 status or identifier is non-negative.
  /// @param status the HDF5 call's result
  /// @param doing the message if it failed
  /// @return status
  /// @throws CheckpointError if status < 0
  template <class T>
  T check(T status, const std::string& doing) const
  {
    if (status < 0)
      fail(doing);
    return status;
  }
  /// Own an identifier an HDF5 call returned, failing if it is invalid.
  /// @param id the call's result
  /// @param closer the H5?close function for its kind
  /// @param doing the message if it failed
  /// @return the owned identifier
  /// @throws CheckpointError if id < 0
  Id checkId(hid_t id, Id::Closer closer, const std::string& doing) const
  {
    if (id < 0)
      fail(doing);
    return Id(id, closer);
  }
  /// @return how messages name the checkpoint
  [[nodiscard]] const std::string& what() const { return what_; }

private:
  std::string what_;
};

/// @param s a name
/// @return s in single quotes, for messages
inline std::string quoted(const std::string& s) { return "'" + s + "'"; }

// ----------------------------------------------------------------------------------------------
// Writing.

/// Raise one error on every process writing a file together when any has one (collective):
/// each passes its own message (empty: none), and all throw CheckpointError with one of them.
using Agree = std::function<void(const std::string& localError)>;

/// The rows of a dataset one process writes when several processes write one file (parallel
/// HDF5): rows [offset, offset + count) of `total`, count being the rows handed to the writer.
struct Rows
{
  hsize_t offset = 0, total = 0;
};

/// Writes the datasets and attributes of a checkpoint into an open file. Every member throws
/// CheckpointError naming the path, with HDF5's message, when HDF5 refuses.
///
/// Several processes may write one file together (parallel HDF5, collective transfers): each
/// calls every member alike, in the same order, with the same attributes; a dataset of rows
/// (bodies, contacts: a writer made by rows()) gets each process's rows at its offset, any
/// other dataset is written by the one process that `writesWhole`.
class Writer
{
public:
  /// `checksums`: numeric datasets chunked with a Fletcher-32 checksum (files), or contiguous
  /// (in-memory images, which nothing can damage).
  /// @param file the open file, not owned (it must outlive the writer)
  /// @param ctx names the checkpoint in errors; must outlive the writer
  /// @param checksums chunk numeric datasets with a Fletcher-32 checksum
  /// @param transfer the transfer property list of H5Dwrite (collective when several processes write)
  /// @param writesWhole whether this process writes the datasets that are not split in rows
  /// @param together when several processes write: the check after each dataset, so that a
  ///        write failing on one process stops all before the next collective call (must
  ///        outlive the writer)
  Writer(hid_t file, const Context& ctx, bool checksums, hid_t transfer = H5P_DEFAULT, bool writesWhole = true,
         const Agree* together = nullptr)
      : file_(file), ctx_(ctx), checksums_(checksums), transfer_(transfer), writesWhole_(writesWhole),
        together_(together)
  {
  }

  /// A writer of datasets split in rows among the processes: each dataset's first axis has
  /// `rows->total` entries, of which this process writes the ones given to it at `rows->offset`.
  /// @param rows this process's rows; null: the datasets are whole (one process)
  /// @return the writer, writing into the same file
  [[nodiscard]] Writer rows(const Rows* rows) const
  {
    Writer w = *this;
    w.rows_ = rows;
    return w;
  }

  /// @param path the new group's absolute path; its parent must exist
  /// @return the group, open
  /// @throws CheckpointError if it cannot be created (it exists already, no parent)
  Id group(const std::string& path) const
  {
    return ctx_.checkId(H5Gcreate2(file_, path.c_str(), H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT), H5Gclose,
                        "cannot create group " + path);
  }

  /// A scalar attribute of `obj` (the three overloads below: double, int64, string).
  /// @param obj the group or dataset it is attached to
  /// @param name its name (must not exist yet)
  /// @param fileType, memType its type in the file and of `value` in memory
  /// @param value the value
  /// @throws CheckpointError if HDF5 refuses
  void attribute(hid_t obj, const char* name, hid_t fileType, hid_t memType, const void* value) const
  {
    const Id space = ctx_.checkId(H5Screate(H5S_SCALAR), H5Sclose, "cannot create a dataspace");
    const Id attr = ctx_.checkId(H5Acreate2(obj, name, fileType, space.get(), H5P_DEFAULT, H5P_DEFAULT), H5Aclose,
                                 std::string("cannot create attribute ") + name);
    ctx_.check(H5Awrite(attr.get(), memType, value), std::string("cannot write attribute ") + name);
  }
  /// @param obj, name, value as above, stored as a little-endian 64-bit float
  /// @throws CheckpointError if HDF5 refuses
  void attribute(hid_t obj, const char* name, double value) const
  {
    attribute(obj, name, H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE, &value);
  }
  /// @param obj, name, value as above, stored as a little-endian 64-bit integer
  /// @throws CheckpointError if HDF5 refuses
  void attribute(hid_t obj, const char* name, std::int64_t value) const
  {
    attribute(obj, name, H5T_STD_I64LE, H5T_NATIVE_INT64, &value);
  }
  /// @param obj, name, value as above, stored as a fixed-length UTF-8 string (at least 1 byte)
  /// @throws CheckpointError if HDF5 refuses
  void attribute(hid_t obj, const char* name, const std::string& value) const
  {
    const Id type = stringType(value.size());
    std::string padded = value;
    padded.resize(std::max<std::size_t>(1, value.size()), '\0');
    attribute(obj, name, type.get(), type.get(), padded.data());
  }

  /// A 1-D dataset of fixed-length UTF-8 strings (as long as the longest, NUL-padded), so that
  /// text is checksummed like numbers. One string of any length holds a text record.
  /// @param path the dataset's absolute path
  /// @param values the strings (any bytes but NUL)
  /// @throws CheckpointError if HDF5 refuses
  void strings(const std::string& path, const std::vector<std::string>& values) const
  {
    std::size_t width = 1;
    for (const std::string& v : values)
      width = std::max(width, v.size());
    const Id type = stringType(width);
    std::string buffer(width * values.size(), '\0');
    for (std::size_t i = 0; i < values.size(); ++i)
      std::copy(values[i].begin(), values[i].end(), buffer.begin() + static_cast<std::ptrdiff_t>(i * width));
    array(path, type.get(), type.get(), {values.size()}, buffer.data());
  }

  /// A numeric dataset of shape `dims`, chunked with a Fletcher-32 checksum when not empty
  /// (and checksums are on).
  /// @param path the dataset's absolute path
  /// @param fileType, memType the element type in the file and in memory
  /// @param dims the shape (row-major)
  /// @param data the elements, as many as the shape's product (may be null if 0)
  /// @throws CheckpointError if HDF5 refuses
  void array(const std::string& path, hid_t fileType, hid_t memType, std::vector<hsize_t> dims, const void* data) const
  {
    if (together_ == nullptr)
      return arrayHere(path, fileType, memType, std::move(dims), data);
    std::string error;
    try
    {
      arrayHere(path, fileType, memType, std::move(dims), data);
    }
    catch (const CheckpointError& e)
    {
      error = e.what();
    }
    (*together_)(error);
  }
  /// array() of little-endian 64-bit floats.
  /// @param path, dims, data as array()'s
  /// @throws CheckpointError if HDF5 refuses
  void doubles(const std::string& path, std::vector<hsize_t> dims, const double* data) const
  {
    array(path, H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE, std::move(dims), data);
  }

private:
  /// array() on this process alone.
  void arrayHere(const std::string& path, hid_t fileType, hid_t memType, std::vector<hsize_t> dims, const void* data) const
  {
    const int rank = static_cast<int>(dims.size());
    std::vector<hsize_t> fileDims = dims;
    if (rows_)
      fileDims[0] = rows_->total;
    const Id space = ctx_.checkId(H5Screate_simple(rank, fileDims.data(), nullptr), H5Sclose, "cannot create a dataspace");
    const Id plist = ctx_.checkId(H5Pcreate(H5P_DATASET_CREATE), H5Pclose, "cannot create a property list");
    hsize_t total = 1;
    for (hsize_t d : fileDims)
      total *= d;
    if (total > 0 && checksums_)
    {
      // Chunks of at most ~4 MiB along the first axis, each with its checksum.
      const hsize_t rowBytes = H5Tget_size(memType) * (total / fileDims[0]);
      std::vector<hsize_t> chunk = fileDims;
      chunk[0] = std::clamp<hsize_t>((hsize_t{4} << 20) / std::max<hsize_t>(rowBytes, 1), 1, fileDims[0]);
      ctx_.check(H5Pset_chunk(plist.get(), rank, chunk.data()), "cannot set the chunks of " + path);
      ctx_.check(H5Pset_fletcher32(plist.get()), "cannot set the checksum of " + path);
    }
    // Every element is written: no fill values (which parallel HDF5 would write when the
    // dataset is created, each process on its own, before the collective transfer).
    ctx_.check(H5Pset_fill_time(plist.get(), H5D_FILL_TIME_NEVER), "cannot set the fill time of " + path);
    const Id set = ctx_.checkId(
        H5Dcreate2(file_, path.c_str(), fileType, space.get(), H5P_DEFAULT, plist.get(), H5P_DEFAULT), H5Dclose,
        "cannot create dataset " + path);
    if (total == 0)
      return;
    if (!rows_ && writesWhole_)
    {
      ctx_.check(H5Dwrite(set.get(), memType, H5S_ALL, H5S_ALL, transfer_, data), "cannot write dataset " + path);
      return;
    }
    // This process's part (none, for a whole dataset another process writes): a transfer every
    // process takes part in.
    const bool mine = rows_ != nullptr && dims[0] > 0;
    const Id memory = ctx_.checkId(H5Screate_simple(rank, dims.data(), nullptr), H5Sclose, "cannot create a dataspace");
    if (mine)
    {
      std::vector<hsize_t> start(dims.size(), 0);
      start[0] = rows_->offset;
      ctx_.check(H5Sselect_hyperslab(space.get(), H5S_SELECT_SET, start.data(), nullptr, dims.data(), nullptr),
                 "cannot select the rows of " + path);
    }
    else
    {
      ctx_.check(H5Sselect_none(space.get()), "cannot select the rows of " + path);
      ctx_.check(H5Sselect_none(memory.get()), "cannot select the rows of " + path);
    }
    const char none = 0;
    ctx_.check(H5Dwrite(set.get(), memType, memory.get(), space.get(), transfer_, mine ? data : &none),
               "cannot write dataset " + path);
  }

public:
  /// A 1-D dataset of n little-endian 32-bit integers.
  /// @param path the dataset's absolute path
  /// @param data, n the values
  /// @throws CheckpointError if HDF5 refuses
  void int32s(const std::string& path, const std::int32_t* data, std::size_t n) const
  {
    array(path, H5T_STD_I32LE, H5T_NATIVE_INT32, {n}, data);
  }
  /// A 1-D dataset of n bytes (flags, shape kinds).
  /// @param path the dataset's absolute path
  /// @param data, n the values
  /// @throws CheckpointError if HDF5 refuses
  void uint8s(const std::string& path, const std::uint8_t* data, std::size_t n) const
  {
    array(path, H5T_STD_U8LE, H5T_NATIVE_UINT8, {n}, data);
  }
  /// An (n, 3) dataset of doubles.
  /// @param path the dataset's absolute path
  /// @param v the vectors
  /// @throws CheckpointError if HDF5 refuses
  void vec3s(const std::string& path, const std::vector<Vec3>& v) const
  {
    doubles(path, {v.size(), 3}, v.empty() ? nullptr : v.front().data());
  }

private:
  Id stringType(std::size_t length) const
  {
    Id type = ctx_.checkId(H5Tcopy(H5T_C_S1), H5Tclose, "cannot create a string type");
    ctx_.check(H5Tset_size(type.get(), std::max<std::size_t>(1, length)), "cannot create a string type");
    ctx_.check(H5Tset_strpad(type.get(), H5T_STR_NULLPAD), "cannot create a string type");
    ctx_.check(H5Tset_cset(type.get(), H5T_CSET_UTF8), "cannot create a string type");
    return type;
  }

  hid_t file_;
  const Context& ctx_;
  bool checksums_;
  hid_t transfer_;
  bool writesWhole_;
  const Agree* together_;
  const Rows* rows_ = nullptr;
};

/// Reads a checkpoint's datasets and attributes from an open file, checking shapes and types.
/// Every member throws CheckpointError naming the path: missing objects ("not a complete Talus
/// checkpoint"), wrong shapes or types, and what HDF5 refuses (a checksum that fails: corrupted
/// data).
class Reader
{
public:
  /// @param file the open file, not owned (it must outlive the reader)
  /// @param ctx names the checkpoint in errors; must outlive the reader
  Reader(hid_t file, const Context& ctx) : file_(file), ctx_(ctx) {}

  /// True if the object at `path` exists (every parent group checked first).
  /// @param path an absolute path
  /// @return whether it exists
  /// @throws CheckpointError if HDF5 cannot tell
  [[nodiscard]] bool exists(const std::string& path) const
  {
    if (path == "/")
      return true;
    std::size_t at = 0;
    while ((at = path.find('/', at + 1)) != std::string::npos)
      if (ctx_.check(H5Lexists(file_, path.substr(0, at).c_str(), H5P_DEFAULT), "cannot read " + path) == 0)
        return false;
    return ctx_.check(H5Lexists(file_, path.c_str(), H5P_DEFAULT), "cannot read " + path) > 0;
  }
  /// @param path an absolute path
  /// @return the object (group or dataset), open
  /// @throws CheckpointError if it is missing or cannot be opened
  Id open(const std::string& path) const
  {
    if (!exists(path))
      ctx_.fail("missing " + path + " (not a complete Talus checkpoint)", false);
    return ctx_.checkId(H5Oopen(file_, path.c_str(), H5P_DEFAULT), H5Oclose, "cannot open " + path);
  }

  /// @param objPath the object's absolute path
  /// @param name the attribute's name
  /// @return whether the object has it
  /// @throws CheckpointError if the object is missing
  bool hasAttribute(const std::string& objPath, const char* name) const
  {
    return ctx_.check(H5Aexists(open(objPath).get(), name), "cannot read attributes of " + objPath) > 0;
  }
  /// @param objPath the object's absolute path
  /// @param name the attribute's name
  /// @return the attribute, open
  /// @throws CheckpointError if the object or the attribute is missing
  Id openAttribute(const std::string& objPath, const char* name) const
  {
    const Id obj = open(objPath);
    const htri_t has = ctx_.check(H5Aexists(obj.get(), name), "cannot read attributes of " + objPath);
    if (has == 0)
      ctx_.fail("missing attribute " + std::string(name) + " of " + objPath + " (not a complete Talus checkpoint)",
                false);
    return ctx_.checkId(H5Aopen(obj.get(), name, H5P_DEFAULT), H5Aclose,
                        "cannot open attribute " + std::string(name) + " of " + objPath);
  }

  /// A scalar numeric attribute, of class `cls`, converted to the memory type.
  /// @param objPath the object's absolute path
  /// @param name the attribute's name
  /// @param cls the class it must have (H5T_FLOAT, H5T_INTEGER)
  /// @param memType the memory type of T
  /// @return the value
  /// @throws CheckpointError if it is missing, not a scalar of that class, or unreadable
  template <class T>
  T number(const std::string& objPath, const char* name, H5T_class_t cls, hid_t memType) const
  {
    const std::string what = "attribute " + std::string(name) + " of " + objPath;
    const Id attr = openAttribute(objPath, name);
    const Id type = ctx_.checkId(H5Aget_type(attr.get()), H5Tclose, "cannot read " + what);
    const Id space = ctx_.checkId(H5Aget_space(attr.get()), H5Sclose, "cannot read " + what);
    if (H5Tget_class(type.get()) != cls || H5Sget_simple_extent_npoints(space.get()) != 1)
      ctx_.fail(what + " has the wrong type", false);
    T value{};
    ctx_.check(H5Aread(attr.get(), memType, &value), "cannot read " + what);
    return value;
  }
  /// @param objPath, name as number()'s
  /// @return a float attribute's value
  /// @throws CheckpointError as number()
  double real(const std::string& objPath, const char* name) const
  {
    return number<double>(objPath, name, H5T_FLOAT, H5T_NATIVE_DOUBLE);
  }
  /// @param objPath, name as number()'s
  /// @return an integer attribute's value
  /// @throws CheckpointError as number()
  std::int64_t integer(const std::string& objPath, const char* name) const
  {
    return number<std::int64_t>(objPath, name, H5T_INTEGER, H5T_NATIVE_INT64);
  }

  /// A string attribute (fixed or variable length).
  /// @param objPath the object's absolute path
  /// @param name the attribute's name
  /// @return the string, up to its first NUL
  /// @throws CheckpointError if it is missing or not a single string
  std::string stringAttribute(const std::string& objPath, const char* name) const
  {
    const std::string what = "attribute " + std::string(name) + " of " + objPath;
    const Id attr = openAttribute(objPath, name);
    const Id type = ctx_.checkId(H5Aget_type(attr.get()), H5Tclose, "cannot read " + what);
    if (H5Tget_class(type.get()) != H5T_STRING)
      ctx_.fail(what + " is not a string", false);
    const Id space = ctx_.checkId(H5Aget_space(attr.get()), H5Sclose, "cannot read " + what);
    if (H5Sget_simple_extent_npoints(space.get()) != 1)
      ctx_.fail(what + " is not a single string", false);
    if (H5Tis_variable_str(type.get()) > 0)
    {
      const Id mem = variableStringType(type.get());
      char* p = nullptr;
      ctx_.check(H5Aread(attr.get(), mem.get(), &p), "cannot read " + what);
      std::string out = p ? p : "";
      H5free_memory(p);
      return out;
    }
    std::string buffer(H5Tget_size(type.get()), '\0');
    ctx_.check(H5Aread(attr.get(), type.get(), buffer.data()), "cannot read " + what);
    return buffer.substr(0, std::strlen(buffer.c_str()));
  }

  /// Strings of a 1-D dataset of fixed-length strings (as Writer::strings writes them).
  /// @param path the dataset's absolute path
  /// @return the strings, NUL padding removed
  /// @throws CheckpointError if it is missing, not such a dataset, or corrupted
  std::vector<std::string> strings(const std::string& path) const
  {
    const std::vector<hsize_t> d = dims(path);
    const Id set = open(path);
    const Id type = ctx_.checkId(H5Dget_type(set.get()), H5Tclose, "cannot read " + path);
    if (d.size() != 1 || H5Tget_class(type.get()) != H5T_STRING || H5Tis_variable_str(type.get()) != 0)
      ctx_.fail(path + " is not a list of fixed-length strings", false);
    const std::size_t size = H5Tget_size(type.get());
    std::string buffer(size * d[0], '\0');
    if (d[0] > 0)
      ctx_.check(H5Dread(set.get(), type.get(), H5S_ALL, H5S_ALL, H5P_DEFAULT, buffer.data()),
                 "cannot read " + path + " (corrupted data)");
    std::vector<std::string> out(d[0]);
    for (std::size_t i = 0; i < out.size(); ++i)
      out[i] = std::string(buffer.data() + i * size, strnlen(buffer.data() + i * size, size));
    return out;
  }

  /// Shape of a dataset.
  /// @param path the dataset's absolute path
  /// @return its dimensions (row-major)
  /// @throws CheckpointError if it is missing
  std::vector<hsize_t> dims(const std::string& path) const
  {
    const Id set = open(path);
    const Id space = ctx_.checkId(H5Dget_space(set.get()), H5Sclose, "cannot read " + path);
    const int rank = ctx_.check(H5Sget_simple_extent_ndims(space.get()), "cannot read " + path);
    std::vector<hsize_t> out(static_cast<std::size_t>(rank));
    ctx_.check(H5Sget_simple_extent_dims(space.get(), out.data(), nullptr), "cannot read " + path);
    return out;
  }

  /// A numeric dataset that must have shape `expect` and type class `cls`, read into `out`.
  /// @param path the dataset's absolute path
  /// @param cls the class it must have (H5T_FLOAT, H5T_INTEGER)
  /// @param memType the memory type of `out`'s elements
  /// @param expect the shape it must have
  /// @param out room for the product of `expect` elements
  /// @throws CheckpointError for another shape or class, or corrupted data
  void array(const std::string& path, H5T_class_t cls, hid_t memType, const std::vector<hsize_t>& expect, void* out) const
  {
    const std::vector<hsize_t> found = dims(path);
    if (found != expect)
      ctx_.fail(path + " has shape " + shape(found) + ", expected " + shape(expect), false);
    const Id set = open(path);
    const Id type = ctx_.checkId(H5Dget_type(set.get()), H5Tclose, "cannot read " + path);
    if (H5Tget_class(type.get()) != cls)
      ctx_.fail(path + " has the wrong element type", false);
    hsize_t total = 1;
    for (hsize_t d : expect)
      total *= d;
    if (total > 0)
      ctx_.check(H5Dread(set.get(), memType, H5S_ALL, H5S_ALL, H5P_DEFAULT, out),
                 "cannot read " + path + " (corrupted data)");
  }
  /// array() of doubles.
  /// @param path, expect, out as array()'s
  /// @throws CheckpointError as array()
  void doubles(const std::string& path, const std::vector<hsize_t>& expect, double* out) const
  {
    array(path, H5T_FLOAT, H5T_NATIVE_DOUBLE, expect, out);
  }
  template <class T>
  /// A 1-D dataset of 32-bit integers of out.size() elements.
  /// @param path the dataset's absolute path
  /// @param out sized by the caller (the expected length), filled
  /// @throws CheckpointError as array()
  void int32s(const std::string& path, std::vector<T>& out) const
  {
    static_assert(sizeof(T) == 4);
    array(path, H5T_INTEGER, H5T_NATIVE_INT32, {out.size()}, out.data());
  }
  template <class T>
  /// A 1-D dataset of bytes of out.size() elements.
  /// @param path the dataset's absolute path
  /// @param out sized by the caller (the expected length), filled
  /// @throws CheckpointError as array()
  void uint8s(const std::string& path, std::vector<T>& out) const
  {
    static_assert(sizeof(T) == 1);
    array(path, H5T_INTEGER, H5T_NATIVE_UINT8, {out.size()}, out.data());
  }
  /// An (out.size(), 3) dataset of doubles.
  /// @param path the dataset's absolute path
  /// @param out sized by the caller (the expected count), filled
  /// @throws CheckpointError as array()
  void vec3s(const std::string& path, std::vector<Vec3>& out) const
  {
    doubles(path, {out.size(), 3}, out.empty() ? nullptr : out.front().data());
  }
  /// @param path a (3, 3) dataset of doubles, row-major
  /// @return the matrix
  /// @throws CheckpointError as array()
  Mat3 matrix(const std::string& path) const
  {
    std::array<double, 9> a{};
    doubles(path, {3, 3}, a.data());
    Mat3 m;
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j)
        m(i, j) = a[static_cast<std::size_t>(3 * i + j)];
    return m;
  }

  /// Names of the members of a group.
  /// @param path the group's absolute path
  /// @return the names, in name order
  /// @throws CheckpointError if the group is missing or cannot be listed
  std::vector<std::string> members(const std::string& path) const
  {
    const Id group = ctx_.checkId(H5Gopen2(file_, path.c_str(), H5P_DEFAULT), H5Gclose, "cannot open " + path);
    H5G_info_t info;
    ctx_.check(H5Gget_info(group.get(), &info), "cannot read " + path);
    std::vector<std::string> names;
    for (hsize_t i = 0; i < info.nlinks; ++i)
    {
      const ssize_t size =
          ctx_.check(H5Lget_name_by_idx(group.get(), ".", H5_INDEX_NAME, H5_ITER_INC, i, nullptr, 0, H5P_DEFAULT),
                     "cannot list " + path);
      std::string name(static_cast<std::size_t>(size) + 1, '\0');
      ctx_.check(H5Lget_name_by_idx(group.get(), ".", H5_INDEX_NAME, H5_ITER_INC, i, name.data(), name.size(),
                                    H5P_DEFAULT),
                 "cannot list " + path);
      name.resize(static_cast<std::size_t>(size));
      names.push_back(name);
    }
    return names;
  }

private:
  static std::string shape(const std::vector<hsize_t>& d)
  {
    std::string s = "(";
    for (std::size_t i = 0; i < d.size(); ++i)
      s += (i ? ", " : "") + std::to_string(d[i]);
    return s + ")";
  }
  /// Memory type for variable-length strings of the file type `like` (same character set:
  /// HDF5 does not convert between ASCII and UTF-8).
  Id variableStringType(hid_t like) const
  {
    Id type = ctx_.checkId(H5Tcopy(H5T_C_S1), H5Tclose, "cannot create a string type");
    ctx_.check(H5Tset_size(type.get(), H5T_VARIABLE), "cannot create a string type");
    ctx_.check(H5Tset_cset(type.get(), H5Tget_cset(like)), "cannot create a string type");
    return type;
  }

  hid_t file_;
  const Context& ctx_;
};
} // namespace talus::dem::checkpoint
