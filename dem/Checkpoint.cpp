// HDF5 checkpoints of a Scene (compiled only when Talus is configured with HDF5).
//
// Every HDF5 call is checked; HDF5's own printing of errors is switched off while a checkpoint
// is written or read, and the innermost message of its error stack is appended to ours instead.
#include "dem/Checkpoint.h"

#include "dem/Scene.h"
#include "dem/build_config.h"

#include <hdf5.h>

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <cerrno>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <limits>
#include <string>
#include <utility>

namespace talus::dem
{
namespace
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

  [[nodiscard]] hid_t get() const { return id_; }
  [[nodiscard]] bool valid() const { return id_ >= 0; }
  /// Close now; returns HDF5's status (negative on failure).
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
void skipExitHandler()
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
std::string hdf5Detail()
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
  explicit Context(std::string what) : what_(std::move(what)) {}

  /// Throw CheckpointError with our message and, if any, HDF5's innermost one.
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
  template <class T>
  T check(T status, const std::string& doing) const
  {
    if (status < 0)
      fail(doing);
    return status;
  }
  Id checkId(hid_t id, Id::Closer closer, const std::string& doing) const
  {
    if (id < 0)
      fail(doing);
    return Id(id, closer);
  }
  [[nodiscard]] const std::string& what() const { return what_; }

private:
  std::string what_;
};

std::string quoted(const std::string& s) { return "'" + s + "'"; }

// ----------------------------------------------------------------------------------------------
// Writing.

class Writer
{
public:
  /// `checksums`: numeric datasets chunked with a Fletcher-32 checksum (files), or contiguous
  /// (in-memory images, which nothing can damage).
  Writer(hid_t file, const Context& ctx, bool checksums) : file_(file), ctx_(ctx), checksums_(checksums) {}

  Id group(const std::string& path) const
  {
    return ctx_.checkId(H5Gcreate2(file_, path.c_str(), H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT), H5Gclose,
                        "cannot create group " + path);
  }

  void attribute(hid_t obj, const char* name, hid_t fileType, hid_t memType, const void* value) const
  {
    const Id space = ctx_.checkId(H5Screate(H5S_SCALAR), H5Sclose, "cannot create a dataspace");
    const Id attr = ctx_.checkId(H5Acreate2(obj, name, fileType, space.get(), H5P_DEFAULT, H5P_DEFAULT), H5Aclose,
                                 std::string("cannot create attribute ") + name);
    ctx_.check(H5Awrite(attr.get(), memType, value), std::string("cannot write attribute ") + name);
  }
  void attribute(hid_t obj, const char* name, double value) const
  {
    attribute(obj, name, H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE, &value);
  }
  void attribute(hid_t obj, const char* name, std::int64_t value) const
  {
    attribute(obj, name, H5T_STD_I64LE, H5T_NATIVE_INT64, &value);
  }
  void attribute(hid_t obj, const char* name, const std::string& value) const
  {
    const Id type = stringType(value.size());
    std::string padded = value;
    padded.resize(std::max<std::size_t>(1, value.size()), '\0');
    attribute(obj, name, type.get(), type.get(), padded.data());
  }

  /// A 1-D dataset of fixed-length UTF-8 strings (as long as the longest, NUL-padded), so that
  /// text is checksummed like numbers. One string of any length holds a text record.
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
  void array(const std::string& path, hid_t fileType, hid_t memType, std::vector<hsize_t> dims, const void* data) const
  {
    const int rank = static_cast<int>(dims.size());
    const Id space = ctx_.checkId(H5Screate_simple(rank, dims.data(), nullptr), H5Sclose, "cannot create a dataspace");
    const Id plist = ctx_.checkId(H5Pcreate(H5P_DATASET_CREATE), H5Pclose, "cannot create a property list");
    hsize_t total = 1;
    for (hsize_t d : dims)
      total *= d;
    if (total > 0 && checksums_)
    {
      // Chunks of at most ~4 MiB along the first axis, each with its checksum.
      const hsize_t rowBytes = H5Tget_size(memType) * (total / dims[0]);
      std::vector<hsize_t> chunk = dims;
      chunk[0] = std::clamp<hsize_t>((hsize_t{4} << 20) / std::max<hsize_t>(rowBytes, 1), 1, dims[0]);
      ctx_.check(H5Pset_chunk(plist.get(), rank, chunk.data()), "cannot set the chunks of " + path);
      ctx_.check(H5Pset_fletcher32(plist.get()), "cannot set the checksum of " + path);
    }
    const Id set = ctx_.checkId(
        H5Dcreate2(file_, path.c_str(), fileType, space.get(), H5P_DEFAULT, plist.get(), H5P_DEFAULT), H5Dclose,
        "cannot create dataset " + path);
    if (total > 0)
      ctx_.check(H5Dwrite(set.get(), memType, H5S_ALL, H5S_ALL, H5P_DEFAULT, data), "cannot write dataset " + path);
  }
  void doubles(const std::string& path, std::vector<hsize_t> dims, const double* data) const
  {
    array(path, H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE, std::move(dims), data);
  }
  void int32s(const std::string& path, const std::int32_t* data, std::size_t n) const
  {
    array(path, H5T_STD_I32LE, H5T_NATIVE_INT32, {n}, data);
  }
  void uint8s(const std::string& path, const std::uint8_t* data, std::size_t n) const
  {
    array(path, H5T_STD_U8LE, H5T_NATIVE_UINT8, {n}, data);
  }
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
};

/// Row-major copy of 3x3 matrices (Eigen stores them by column).
std::array<double, 9> rowMajor(const Mat3& m)
{
  std::array<double, 9> out{};
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      out[static_cast<std::size_t>(3 * i + j)] = m(i, j);
  return out;
}

bool validExtraName(const std::string& name)
{
  return !name.empty() && std::all_of(name.begin(), name.end(), [](char ch) {
    return (ch >= 'a' && ch <= 'z') || (ch >= 'A' && ch <= 'Z') || (ch >= '0' && ch <= '9') || ch == '_' || ch == '-';
  });
}

/// The fields stored column by column: one dataset per field, named as the field.
constexpr std::pair<const char*, double Material::*> materialScalars[] = {
    {"density", &Material::density}, {"young", &Material::young}, {"poisson", &Material::poisson},
    {"frictionAngle", &Material::frictionAngle}, {"tc", &Material::tc}, {"en", &Material::en}, {"et", &Material::et},
    {"kn", &Material::kn}, {"cn", &Material::cn}, {"ks", &Material::ks}, {"cs", &Material::cs},
    {"normalCohesion", &Material::normalCohesion}, {"shearCohesion", &Material::shearCohesion},
    {"alphaKr", &Material::alphaKr}, {"alphaKtw", &Material::alphaKtw}, {"etaRoll", &Material::etaRoll},
    {"etaTwist", &Material::etaTwist}};
constexpr std::pair<const char*, bool Material::*> materialFlags[] = {
    {"isCohesive", &Material::isCohesive}, {"momentRotationLaw", &Material::momentRotationLaw},
    {"fragile", &Material::fragile}};
constexpr std::pair<const char*, Vec3 Contact::*> contactVectors[] = {
    {"normal", &Contact::normal}, {"contactPoint", &Contact::contactPoint},
    {"shearIncrement", &Contact::shearIncrement}, {"normalForce", &Contact::normalForce},
    {"shearForce", &Contact::shearForce}, {"force", &Contact::force}};
constexpr std::pair<const char*, double Contact::*> contactScalars[] = {
    {"penetration", &Contact::penetration}, {"refR1", &Contact::refR1}, {"refR2", &Contact::refR2},
    {"kn", &Contact::kn}, {"ks", &Contact::ks}, {"cn", &Contact::cn}, {"cs", &Contact::cs}, {"tanPhi", &Contact::tanPhi}};
// Contacts::extra (the richer contact models' state), one dataset per field under /contacts/extra.
constexpr std::pair<const char*, double ContactExtra::*> extraScalars[] = {
    {"kno", &ContactExtra::kno}, {"kso", &ContactExtra::kso}, {"betan", &ContactExtra::betan},
    {"betas", &ContactExtra::betas}, {"twist", &ContactExtra::twist}, {"normalAdhesion", &ContactExtra::normalAdhesion},
    {"shearAdhesion", &ContactExtra::shearAdhesion}, {"kr", &ContactExtra::kr}, {"ktw", &ContactExtra::ktw},
    {"maxRollPl", &ContactExtra::maxRollPl}, {"maxTwistPl", &ContactExtra::maxTwistPl}, {"unp", &ContactExtra::unp},
    {"unpMax", &ContactExtra::unpMax}};
constexpr std::pair<const char*, Vec3 ContactExtra::*> extraVectors[] = {
    {"bending", &ContactExtra::bending}, {"momentBending", &ContactExtra::momentBending},
    {"momentTwist", &ContactExtra::momentTwist}};
constexpr std::pair<const char*, Quat ContactExtra::*> extraQuats[] = {
    {"initialOrientation1", &ContactExtra::initialOrientation1}, {"initialOrientation2", &ContactExtra::initialOrientation2}};
constexpr std::pair<const char*, std::uint8_t ContactExtra::*> extraBytes[] = {
    {"cohesionBroken", &ContactExtra::cohesionBroken}, {"fragile", &ContactExtra::fragile},
    {"momentRotationLaw", &ContactExtra::momentRotationLaw},
    {"cohesionDisablesFriction", &ContactExtra::cohesionDisablesFriction}, {"intactRock", &ContactExtra::intactRock},
    {"tensionBroken", &ContactExtra::tensionBroken}};
// The energy tracker's accumulated terms, attributes of /energy.
constexpr std::pair<const char*, double EnergyTracker::*> energyTerms[] = {
    {"gravWork", &EnergyTracker::gravWork}, {"nonviscDamp", &EnergyTracker::nonviscDamp},
    {"plastDissip", &EnergyTracker::plastDissip}, {"viscDamp", &EnergyTracker::viscDamp},
    {"velGradWork", &EnergyTracker::velGradWork}, {"kinematicWork", &EnergyTracker::kinematicWork},
    {"growthWork", &EnergyTracker::growthWork}};
// The tracker's imposed displacements of the previous step, datasets of /energy (absent until tracked).
constexpr std::pair<const char*, std::vector<Vec3> EnergyTracker::*> energyHistory[] = {
    {"previousDisplacement", &EnergyTracker::previousDisplacement},
    {"previousRotation", &EnergyTracker::previousRotation}};
constexpr std::pair<const char*, BodyId Contact::*> contactIds[] = {{"id1", &Contact::id1}, {"id2", &Contact::id2}};
constexpr std::pair<const char*, bool Contact::*> contactFlags[] = {{"real", &Contact::real}, {"fresh", &Contact::fresh}};
constexpr std::pair<const char*, std::vector<Vec3> Bodies::*> bodyVectors[] = {
    {"pos", &Bodies::pos},           {"vel", &Bodies::vel},       {"angVel", &Bodies::angVel},
    {"force", &Bodies::force},       {"torque", &Bodies::torque}, {"extForce", &Bodies::extForce},
    {"extTorque", &Bodies::extTorque}, {"inertia", &Bodies::inertia}, {"angMom", &Bodies::angMom}};
constexpr std::pair<const char*, std::vector<double> Bodies::*> bodyScalars[] = {{"mass", &Bodies::mass},
                                                                                  {"radius", &Bodies::radius}};
constexpr std::pair<const char*, std::vector<int> Bodies::*> bodyInts[] = {
    {"shapeIndex", &Bodies::shapeIndex}, {"material", &Bodies::material}, {"clumpId", &Bodies::clumpId}};
constexpr std::pair<const char*, std::vector<std::uint8_t> Bodies::*> bodyBytes[] = {
    {"blockedDofs", &Bodies::blockedDofs}, {"dynamic", &Bodies::dynamic}, {"alive", &Bodies::alive}};
static_assert(sizeof(int) == 4 && sizeof(BodyId) == 4, "int arrays are written as 32-bit integers");

std::string at(const char* group, const char* name) { return std::string(group) + name; }

// Potential Blocks and Particles: every field of their shapes, derived ones included (vertices,
// faces, principal frame, surface samples), so that a restored scene computes the same bits
// as the saved one (recomputing them from the planes would round differently). Lists of
// varying length (planes, vertices, ...) are concatenated over the shapes: shape k owns entries
// [start[k], start[k + 1]) of `<name>` with `<name>Start` (n + 1 entries).
constexpr std::pair<const char*, double PotentialBlockShape::*> blockScalars[] = {
    {"r", &PotentialBlockShape::r}, {"R", &PotentialBlockShape::R}, {"volume", &PotentialBlockShape::volume},
    {"boundingRadius", &PotentialBlockShape::boundingRadius}};
constexpr std::pair<const char*, std::vector<Vec3> PotentialBlockShape::*> blockVectorLists[] = {
    {"normals", &PotentialBlockShape::normals}, {"vertices", &PotentialBlockShape::vertices},
    {"edgeDirections", &PotentialBlockShape::edgeDirections}};
constexpr std::pair<const char*, double PotentialParticleShape::*> particleScalars[] = {
    {"r", &PotentialParticleShape::r}, {"k", &PotentialParticleShape::k}, {"R", &PotentialParticleShape::R},
    {"volume", &PotentialParticleShape::volume}, {"boundingRadius", &PotentialParticleShape::boundingRadius}};
constexpr std::pair<const char*, Vec3 PotentialParticleShape::*> particleVectors[] = {
    {"centroid", &PotentialParticleShape::centroid}, {"inertiaPerDensity", &PotentialParticleShape::inertiaPerDensity}};
constexpr std::pair<const char*, std::vector<Vec3> PotentialParticleShape::*> particleVectorLists[] = {
    {"normals", &PotentialParticleShape::normals}, {"samples", &PotentialParticleShape::samples}};

/// The fields both shape kinds have: per shape the scalars, the boundary flag and the lists of
/// vectors (`vectorLists`), and the plane offsets d beside the normals.
template <class Shape, std::size_t NS, std::size_t NL>
void writeShapeColumns(const Writer& w, const std::string& group, const std::vector<Shape>& shapes,
                       const std::pair<const char*, double Shape::*> (&scalars)[NS],
                       const std::pair<const char*, std::vector<Vec3> Shape::*> (&vectorLists)[NL])
{
  const std::size_t n = shapes.size();
  std::vector<double> column(n);
  for (const auto& [name, field] : scalars)
  {
    for (std::size_t k = 0; k < n; ++k)
      column[k] = shapes[k].*field;
    w.doubles(group + name, {n}, column.data());
  }
  std::vector<std::uint8_t> boundary(n);
  for (std::size_t k = 0; k < n; ++k)
    boundary[k] = shapes[k].isBoundary ? 1 : 0;
  w.uint8s(group + "isBoundary", boundary.data(), n);
  for (const auto& [name, field] : vectorLists)
  {
    std::vector<std::int32_t> start{0};
    std::vector<Vec3> values;
    for (const Shape& s : shapes)
    {
      values.insert(values.end(), (s.*field).begin(), (s.*field).end());
      start.push_back(static_cast<std::int32_t>(values.size()));
    }
    w.int32s(group + name + "Start", start.data(), start.size());
    w.vec3s(group + name, values);
  }
  std::vector<double> d;
  for (const Shape& s : shapes)
    d.insert(d.end(), s.d.begin(), s.d.end());
  w.doubles(group + "d", {d.size()}, d.data());
}

void writePlaneShapes(const Writer& w, const Bodies& b)
{
  {
    const Id g = w.group("/bodies/blocks");
    writeShapeColumns(w, "/bodies/blocks/", b.blocks, blockScalars, blockVectorLists);
    // Faces: a list of faces per block (facePlane beside it), each face a list of vertices.
    std::vector<std::int32_t> faceStart{0}, facePlane, faceVertexStart{0}, faceVertices;
    for (const PotentialBlockShape& s : b.blocks)
    {
      for (const std::vector<int>& face : s.faces)
      {
        faceVertices.insert(faceVertices.end(), face.begin(), face.end());
        faceVertexStart.push_back(static_cast<std::int32_t>(faceVertices.size()));
      }
      facePlane.insert(facePlane.end(), s.facePlane.begin(), s.facePlane.end());
      faceStart.push_back(static_cast<std::int32_t>(faceVertexStart.size() - 1));
    }
    w.int32s("/bodies/blocks/faceStart", faceStart.data(), faceStart.size());
    w.int32s("/bodies/blocks/facePlane", facePlane.data(), facePlane.size());
    w.int32s("/bodies/blocks/faceVerticesStart", faceVertexStart.data(), faceVertexStart.size());
    w.int32s("/bodies/blocks/faceVertices", faceVertices.data(), faceVertices.size());
    // The faces' rock-joint properties, one entry per plane as d.
    std::vector<double> cohesion, tension;
    std::vector<std::uint8_t> intactRock;
    std::vector<std::int32_t> jointType;
    for (const PotentialBlockShape& s : b.blocks)
    {
      cohesion.insert(cohesion.end(), s.cohesion.begin(), s.cohesion.end());
      tension.insert(tension.end(), s.tension.begin(), s.tension.end());
      intactRock.insert(intactRock.end(), s.intactRock.begin(), s.intactRock.end());
      jointType.insert(jointType.end(), s.jointType.begin(), s.jointType.end());
    }
    w.doubles("/bodies/blocks/cohesion", {cohesion.size()}, cohesion.data());
    w.doubles("/bodies/blocks/tension", {tension.size()}, tension.data());
    w.uint8s("/bodies/blocks/intactRock", intactRock.data(), intactRock.size());
    w.int32s("/bodies/blocks/jointType", jointType.data(), jointType.size());
  }
  {
    const Id g = w.group("/bodies/particles");
    writeShapeColumns(w, "/bodies/particles/", b.particles, particleScalars, particleVectorLists);
    const std::size_t n = b.particles.size();
    std::vector<Vec3> column(n);
    for (const auto& [name, field] : particleVectors)
    {
      for (std::size_t k = 0; k < n; ++k)
        column[k] = b.particles[k].*field;
      w.vec3s(at("/bodies/particles/", name), column);
    }
    std::vector<double> axes(9 * n);
    for (std::size_t k = 0; k < n; ++k)
    {
      const std::array<double, 9> a = rowMajor(b.particles[k].axes);
      std::copy(a.begin(), a.end(), axes.begin() + static_cast<std::ptrdiff_t>(9 * k));
    }
    w.doubles("/bodies/particles/axes", {n, 3, 3}, axes.data());
  }
}

void writeScene(hid_t file, const Scene& scene, const CheckpointExtras& extras, const Context& ctx, bool checksums)
{
  const Writer w(file, ctx, checksums);
  {
    const Id root = ctx.checkId(H5Gopen2(file, "/", H5P_DEFAULT), H5Gclose, "cannot open the root group");
    w.attribute(root.get(), "magic", std::string(checkpointMagic));
    w.attribute(root.get(), "format_version", std::int64_t{checkpointFormatVersion});
    w.attribute(root.get(), "talus_version", std::string(talus::version()));
  }

  // Clock and change counters.
  {
    const Id g = w.group("/clock");
    w.attribute(g.get(), "dt", scene.dt);
    w.attribute(g.get(), "time", scene.time);
    w.attribute(g.get(), "iter", scene.iter);
    w.attribute(g.get(), "bodiesVersion", scene.bodiesVersion);
    w.attribute(g.get(), "bodyPropertiesVersion", scene.bodyPropertiesVersion);
  }

  // Settings of the scene itself.
  {
    const Id g = w.group("/settings");
    w.attribute(g.get(), "maxOverlapRatio", scene.maxOverlapRatio);
    w.attribute(g.get(), "maxEnergyGrowth", scene.maxEnergyGrowth);
  }

  // Energy tracker.
  {
    const Id g = w.group("/energy");
    w.attribute(g.get(), "enabled", std::int64_t{scene.energy.enabled ? 1 : 0});
    for (const auto& [name, field] : energyTerms)
      w.attribute(g.get(), name, scene.energy.*field);
    w.attribute(g.get(), "growthReference", scene.energy.growthReference);
    for (const auto& [name, field] : energyHistory)
      if (!(scene.energy.*field).empty())
        w.vec3s(at("/energy/", name), scene.energy.*field);
    if (const std::vector<double>& grown = scene.energy.grownBy; !grown.empty())
      w.doubles("/energy/grownBy", {grown.size()}, grown.data());
  }

  // Periodic cell.
  {
    const Id g = w.group("/cell");
    w.attribute(g.get(), "periodic", std::int64_t{scene.periodic ? 1 : 0});
    w.attribute(g.get(), "homoDeform", std::int64_t{scene.cell.homoDeform ? 1 : 0});
    const std::pair<const char*, const Mat3*> matrices[] = {{"/cell/hSize", &scene.cell.hSize},
                                                            {"/cell/velGrad", &scene.cell.velGrad},
                                                            {"/cell/prevVelGrad", &scene.cell.prevVelGrad},
                                                            {"/cell/trsf", &scene.cell.trsf}};
    for (const auto& [path, m] : matrices)
    {
      const std::array<double, 9> a = rowMajor(*m);
      w.doubles(path, {3, 3}, a.data());
    }
  }

  // Materials: one entry per material, in index order.
  {
    const auto& mats = scene.materials;
    const Id g = w.group("/materials");
    std::vector<std::uint8_t> kind;
    std::vector<std::string> label;
    for (const Material& m : mats)
    {
      kind.push_back(static_cast<std::uint8_t>(m.kind));
      label.push_back(m.label);
    }
    w.uint8s("/materials/kind", kind.data(), kind.size());
    w.strings("/materials/label", label);
    std::vector<double> column(mats.size());
    for (const auto& [name, field] : materialScalars)
    {
      for (std::size_t i = 0; i < mats.size(); ++i)
        column[i] = mats[i].*field;
      w.doubles(at("/materials/", name), {mats.size()}, column.data());
    }
    std::vector<std::uint8_t> flag(mats.size());
    for (const auto& [name, field] : materialFlags)
    {
      for (std::size_t i = 0; i < mats.size(); ++i)
        flag[i] = mats[i].*field ? 1 : 0;
      w.uint8s(at("/materials/", name), flag.data(), flag.size());
    }
  }

  // Bodies: every array, erased slots included (ids are indices).
  {
    const Bodies& b = scene.bodies;
    const std::size_t n = b.size();
    const Id g = w.group("/bodies");
    for (const auto& [name, field] : bodyVectors)
      w.vec3s(at("/bodies/", name), b.*field);
    for (const auto& [name, field] : bodyScalars)
      w.doubles(at("/bodies/", name), {n}, (b.*field).data());
    for (const auto& [name, field] : bodyInts)
      w.int32s(at("/bodies/", name), (b.*field).data(), n);
    for (const auto& [name, field] : bodyBytes)
      w.uint8s(at("/bodies/", name), (b.*field).data(), n);
    std::vector<double> ori(4 * n);
    for (std::size_t i = 0; i < n; ++i)
    {
      const Quat& q = b.ori[i];
      std::copy_n(std::array<double, 4>{q.w(), q.x(), q.y(), q.z()}.begin(), 4, ori.begin() + static_cast<std::ptrdiff_t>(4 * i));
    }
    w.doubles("/bodies/ori", {n, 4}, ori.data());
    std::vector<std::uint8_t> shape(n);
    for (std::size_t i = 0; i < n; ++i)
      shape[i] = static_cast<std::uint8_t>(b.shape[i]);
    w.uint8s("/bodies/shape", shape.data(), n);

    const Id walls = w.group("/bodies/walls");
    std::vector<std::int32_t> axis, sense;
    for (const WallShape& s : b.walls)
    {
      axis.push_back(s.axis);
      sense.push_back(s.sense);
    }
    w.int32s("/bodies/walls/axis", axis.data(), axis.size());
    w.int32s("/bodies/walls/sense", sense.data(), sense.size());

    const Id facets = w.group("/bodies/facets");
    const std::size_t nf = b.facets.size();
    std::vector<double> vertices(9 * nf), normal(3 * nf);
    for (std::size_t f = 0; f < nf; ++f)
    {
      for (std::size_t k = 0; k < 3; ++k)
        for (std::size_t d = 0; d < 3; ++d)
          vertices[9 * f + 3 * k + d] = b.facets[f].vertices[k][static_cast<int>(d)];
      for (std::size_t d = 0; d < 3; ++d)
        normal[3 * f + d] = b.facets[f].normal[static_cast<int>(d)];
    }
    w.doubles("/bodies/facets/vertices", {nf, 3, 3}, vertices.data());
    w.doubles("/bodies/facets/normal", {nf, 3}, normal.data());

    const Id boxes = w.group("/bodies/boxes");
    std::vector<Vec3> extents;
    for (const BoxShape& box : b.boxes)
      extents.push_back(box.extents);
    w.vec3s("/bodies/boxes/extents", extents);

    // Clumps: members of all clumps concatenated; clump k owns entries [start[k], start[k+1]).
    const Id clumps = w.group("/bodies/clumps");
    std::vector<std::int32_t> start{0}, members;
    std::vector<Vec3> relPos;
    std::vector<double> relOri;
    for (const ClumpShape& clump : b.clumps)
    {
      for (std::size_t k = 0; k < clump.members.size(); ++k)
      {
        members.push_back(clump.members[k]);
        relPos.push_back(clump.relPos[k]);
        const Quat& q = clump.relOri[k];
        relOri.insert(relOri.end(), {q.w(), q.x(), q.y(), q.z()});
      }
      start.push_back(static_cast<std::int32_t>(members.size()));
    }
    w.int32s("/bodies/clumps/start", start.data(), start.size());
    w.int32s("/bodies/clumps/members", members.data(), members.size());
    w.vec3s("/bodies/clumps/relPos", relPos);
    w.doubles("/bodies/clumps/relOri", {members.size(), 4}, relOri.data());
    writePlaneShapes(w, b);
  }

  // Contacts: the list in its order, every field of Contact.
  {
    const std::vector<Contact>& list = scene.contacts.list;
    const std::size_t c = list.size();
    const Id g = w.group("/contacts");
    std::vector<std::int32_t> ids(c), cellDist(3 * c);
    for (const auto& [name, field] : contactIds)
    {
      for (std::size_t k = 0; k < c; ++k)
        ids[k] = list[k].*field;
      w.int32s(at("/contacts/", name), ids.data(), c);
    }
    for (std::size_t k = 0; k < c; ++k)
      for (std::size_t d = 0; d < 3; ++d)
        cellDist[3 * k + d] = list[k].cellDist[static_cast<int>(d)];
    w.array("/contacts/cellDist", H5T_STD_I32LE, H5T_NATIVE_INT32, {c, 3}, cellDist.data());
    std::vector<std::uint8_t> bytes(c);
    for (const auto& [name, field] : contactFlags)
    {
      for (std::size_t k = 0; k < c; ++k)
        bytes[k] = list[k].*field ? 1 : 0;
      w.uint8s(at("/contacts/", name), bytes.data(), c);
    }
    for (std::size_t k = 0; k < c; ++k)
      bytes[k] = static_cast<std::uint8_t>(list[k].kind);
    w.uint8s("/contacts/kind", bytes.data(), c);
    for (std::size_t k = 0; k < c; ++k)
      bytes[k] = list[k].law;
    w.uint8s("/contacts/law", bytes.data(), c);
    std::vector<Vec3> column3(c);
    for (const auto& [name, field] : contactVectors)
    {
      for (std::size_t k = 0; k < c; ++k)
        column3[k] = list[k].*field;
      w.vec3s(at("/contacts/", name), column3);
    }
    std::vector<double> column(c);
    for (const auto& [name, field] : contactScalars)
    {
      for (std::size_t k = 0; k < c; ++k)
        column[k] = list[k].*field;
      w.doubles(at("/contacts/", name), {c}, column.data());
    }
    // The richer models' state: as many rows as contacts, or none.
    const std::vector<ContactExtra>& extra = scene.contacts.extra;
    const std::size_t e = extra.size();
    const Id ge = w.group("/contacts/extra");
    column.resize(e);
    for (const auto& [name, field] : extraScalars)
    {
      for (std::size_t k = 0; k < e; ++k)
        column[k] = extra[k].*field;
      w.doubles(at("/contacts/extra/", name), {e}, column.data());
    }
    column3.resize(e);
    for (const auto& [name, field] : extraVectors)
    {
      for (std::size_t k = 0; k < e; ++k)
        column3[k] = extra[k].*field;
      w.vec3s(at("/contacts/extra/", name), column3);
    }
    std::vector<double> quats(4 * e);
    for (const auto& [name, field] : extraQuats)
    {
      for (std::size_t k = 0; k < e; ++k)
      {
        const Quat& q = extra[k].*field;
        quats[4 * k] = q.w(), quats[4 * k + 1] = q.x(), quats[4 * k + 2] = q.y(), quats[4 * k + 3] = q.z();
      }
      w.doubles(at("/contacts/extra/", name), {e, 4}, quats.data());
    }
    bytes.resize(e);
    for (const auto& [name, field] : extraBytes)
    {
      for (std::size_t k = 0; k < e; ++k)
        bytes[k] = extra[k].*field;
      w.uint8s(at("/contacts/extra/", name), bytes.data(), e);
    }
  }

  // Extras: text records of the Python layer.
  {
    const Id g = w.group("/extras");
    for (const auto& [name, value] : extras)
    {
      if (!validExtraName(name))
        ctx.fail("extra record name " + quoted(name) + " is not letters, digits, '_' or '-'", false);
      w.strings("/extras/" + name, {value});
    }
  }
}

// ----------------------------------------------------------------------------------------------
// Reading.

/// Everything a checkpoint holds, read and checked before the scene is touched.
struct Loaded
{
  double dt = 0, time = 0;
  std::int64_t iter = 0, bodiesVersion = 0, bodyPropertiesVersion = 0;
  double maxOverlapRatio = 0;
  double maxEnergyGrowth = 0;
  bool periodic = false;
  Cell cell;
  std::vector<Material> materials;
  Bodies bodies;
  std::vector<Contact> contacts;
  std::vector<ContactExtra> contactExtra;
  EnergyTracker energy;
  CheckpointExtras extras;
};

class Reader
{
public:
  Reader(hid_t file, const Context& ctx) : file_(file), ctx_(ctx) {}

  /// True if the object at `path` exists (every parent group checked first).
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
  Id open(const std::string& path) const
  {
    if (!exists(path))
      ctx_.fail("missing " + path + " (not a complete Talus checkpoint)", false);
    return ctx_.checkId(H5Oopen(file_, path.c_str(), H5P_DEFAULT), H5Oclose, "cannot open " + path);
  }

  bool hasAttribute(const std::string& objPath, const char* name) const
  {
    return ctx_.check(H5Aexists(open(objPath).get(), name), "cannot read attributes of " + objPath) > 0;
  }
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
  double real(const std::string& objPath, const char* name) const
  {
    return number<double>(objPath, name, H5T_FLOAT, H5T_NATIVE_DOUBLE);
  }
  std::int64_t integer(const std::string& objPath, const char* name) const
  {
    return number<std::int64_t>(objPath, name, H5T_INTEGER, H5T_NATIVE_INT64);
  }

  /// A string attribute (fixed or variable length).
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
  void doubles(const std::string& path, const std::vector<hsize_t>& expect, double* out) const
  {
    array(path, H5T_FLOAT, H5T_NATIVE_DOUBLE, expect, out);
  }
  template <class T>
  void int32s(const std::string& path, std::vector<T>& out) const
  {
    static_assert(sizeof(T) == 4);
    array(path, H5T_INTEGER, H5T_NATIVE_INT32, {out.size()}, out.data());
  }
  template <class T>
  void uint8s(const std::string& path, std::vector<T>& out) const
  {
    static_assert(sizeof(T) == 1);
    array(path, H5T_INTEGER, H5T_NATIVE_UINT8, {out.size()}, out.data());
  }
  void vec3s(const std::string& path, std::vector<Vec3>& out) const
  {
    doubles(path, {out.size(), 3}, out.empty() ? nullptr : out.front().data());
  }
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

/// The starts of the lists `<path>` written for `n` shapes (see writePlaneShapes), checked to
/// partition its `entries` entries.
std::vector<std::int32_t> listStarts(const Reader& r, const std::string& path, std::size_t n, std::size_t entries,
                                     const Context& ctx)
{
  std::vector<std::int32_t> start(n + 1);
  r.int32s(path + "Start", start);
  if (start.front() != 0 || start.back() != static_cast<std::int32_t>(entries) || !std::is_sorted(start.begin(), start.end()))
    ctx.fail(path + "Start does not partition the entries of " + path + " among the shapes", false);
  return start;
}

/// The number of rows of a dataset that must be an (n, columns) array (columns 0: 1-D).
std::size_t rows(const Reader& r, const std::string& path, hsize_t columns, const Context& ctx)
{
  const std::vector<hsize_t> d = r.dims(path);
  if (columns == 0 ? d.size() != 1 : (d.size() != 2 || d[1] != columns))
    ctx.fail(path + " is not " + (columns == 0 ? std::string("one-dimensional") : "an (n, 3) array"), false);
  return d[0];
}

template <class Shape, std::size_t NS, std::size_t NL>
void readShapeColumns(const Reader& r, const std::string& group, std::vector<Shape>& shapes,
                      const std::pair<const char*, double Shape::*> (&scalars)[NS],
                      const std::pair<const char*, std::vector<Vec3> Shape::*> (&vectorLists)[NL], const Context& ctx)
{
  const std::size_t n = rows(r, group + "r", 0, ctx);
  shapes.resize(n);
  std::vector<double> column(n);
  for (const auto& [name, field] : scalars)
  {
    r.doubles(group + name, {n}, column.data());
    for (std::size_t k = 0; k < n; ++k)
      shapes[k].*field = column[k];
  }
  std::vector<std::uint8_t> boundary(n);
  r.uint8s(group + "isBoundary", boundary);
  for (std::size_t k = 0; k < n; ++k)
    shapes[k].isBoundary = boundary[k] != 0;
  for (const auto& [name, field] : vectorLists)
  {
    std::vector<Vec3> values(rows(r, group + name, 3, ctx));
    r.vec3s(group + name, values);
    const std::vector<std::int32_t> start = listStarts(r, group + name, n, values.size(), ctx);
    for (std::size_t k = 0; k < n; ++k)
      (shapes[k].*field).assign(values.begin() + start[k], values.begin() + start[k + 1]);
  }
  std::size_t planes = 0;
  for (const Shape& s : shapes)
    planes += s.normals.size();
  std::vector<double> d(planes);
  r.doubles(group + "d", {planes}, d.data());
  auto next = d.begin();
  for (Shape& s : shapes)
  {
    s.d.assign(next, next + static_cast<std::ptrdiff_t>(s.normals.size()));
    next += static_cast<std::ptrdiff_t>(s.normals.size());
  }
}

void readPlaneShapes(const Reader& r, Bodies& b, const Context& ctx)
{
  readShapeColumns(r, "/bodies/blocks/", b.blocks, blockScalars, blockVectorLists, ctx);
  std::vector<std::int32_t> facePlane(rows(r, "/bodies/blocks/facePlane", 0, ctx));
  r.int32s("/bodies/blocks/facePlane", facePlane);
  std::vector<std::int32_t> faceVertices(rows(r, "/bodies/blocks/faceVertices", 0, ctx));
  r.int32s("/bodies/blocks/faceVertices", faceVertices);
  const std::vector<std::int32_t> faceStart =
      listStarts(r, "/bodies/blocks/face", b.blocks.size(), facePlane.size(), ctx);
  const std::vector<std::int32_t> vertexStart =
      listStarts(r, "/bodies/blocks/faceVertices", facePlane.size(), faceVertices.size(), ctx);
  for (std::size_t k = 0; k < b.blocks.size(); ++k)
  {
    PotentialBlockShape& s = b.blocks[k];
    s.facePlane.assign(facePlane.begin() + faceStart[k], facePlane.begin() + faceStart[k + 1]);
    for (auto f = static_cast<std::size_t>(faceStart[k]); f < static_cast<std::size_t>(faceStart[k + 1]); ++f)
      s.faces.emplace_back(faceVertices.begin() + vertexStart[f], faceVertices.begin() + vertexStart[f + 1]);
  }
  std::size_t planes = 0;
  for (const PotentialBlockShape& s : b.blocks)
    planes += s.normals.size();
  std::vector<double> cohesion(planes), tension(planes);
  std::vector<std::uint8_t> intactRock(planes);
  std::vector<std::int32_t> jointType(planes);
  r.doubles("/bodies/blocks/cohesion", {planes}, cohesion.data());
  r.doubles("/bodies/blocks/tension", {planes}, tension.data());
  r.uint8s("/bodies/blocks/intactRock", intactRock);
  r.int32s("/bodies/blocks/jointType", jointType);
  std::size_t next = 0;
  for (PotentialBlockShape& s : b.blocks)
  {
    const auto from = static_cast<std::ptrdiff_t>(next), to = static_cast<std::ptrdiff_t>(next + s.normals.size());
    s.cohesion.assign(cohesion.begin() + from, cohesion.begin() + to);
    s.tension.assign(tension.begin() + from, tension.begin() + to);
    s.intactRock.assign(intactRock.begin() + from, intactRock.begin() + to);
    s.jointType.assign(jointType.begin() + from, jointType.begin() + to);
    next += s.normals.size();
  }

  readShapeColumns(r, "/bodies/particles/", b.particles, particleScalars, particleVectorLists, ctx);
  const std::size_t n = b.particles.size();
  std::vector<Vec3> column(n);
  for (const auto& [name, field] : particleVectors)
  {
    r.vec3s(at("/bodies/particles/", name), column);
    for (std::size_t k = 0; k < n; ++k)
      b.particles[k].*field = column[k];
  }
  std::vector<double> axes(9 * n);
  r.doubles("/bodies/particles/axes", {n, 3, 3}, axes.data());
  for (std::size_t k = 0; k < n; ++k)
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j)
        b.particles[k].axes(i, j) = axes[9 * k + static_cast<std::size_t>(3 * i + j)];
}

/// Shapes given by planes that a solver can use: enough finite planes, faces naming existing
/// vertices and planes, a valid rounding (and for particles k in (0, 1]).
void validatePlaneShapes(const Bodies& b, const Context& ctx)
{
  auto finite = [](const auto& shape) {
    bool ok = std::all_of(shape.d.begin(), shape.d.end(), [](double x) { return std::isfinite(x); });
    for (const Vec3& v : shape.normals)
      ok = ok && v.allFinite() && std::abs(v.norm() - 1) <= 1e-6;
    return ok && shape.normals.size() >= 4 && std::isfinite(shape.volume) && shape.volume > 0
           && std::isfinite(shape.boundingRadius) && std::isfinite(shape.R) && std::isfinite(shape.r);
  };
  for (std::size_t k = 0; k < b.blocks.size(); ++k)
  {
    const PotentialBlockShape& s = b.blocks[k];
    bool ok = finite(s) && s.r >= 0 && s.R > 0 && s.vertices.size() >= 4 && s.faces.size() == s.facePlane.size();
    for (std::size_t i = 0; ok && i < s.cohesion.size(); ++i)
      ok = std::isfinite(s.cohesion[i]) && s.cohesion[i] >= 0 && std::isfinite(s.tension[i]) && s.tension[i] >= 0;
    for (std::size_t f = 0; ok && f < s.faces.size(); ++f)
      ok = s.facePlane[f] >= 0 && static_cast<std::size_t>(s.facePlane[f]) < s.normals.size() && s.faces[f].size() >= 3
           && std::all_of(s.faces[f].begin(), s.faces[f].end(),
                          [&](int v) { return v >= 0 && static_cast<std::size_t>(v) < s.vertices.size(); });
    if (!ok)
      ctx.fail("Potential Block shape " + std::to_string(k)
                   + " is invalid (planes, rounding, volume, faces or face strengths out of range)",
               false);
  }
  for (std::size_t k = 0; k < b.particles.size(); ++k)
  {
    const PotentialParticleShape& s = b.particles[k];
    if (!(finite(s) && s.r > 0 && s.R > 0 && s.k > 0 && s.k <= 1 && !s.samples.empty()))
      ctx.fail("Potential Particle shape " + std::to_string(k) + " is invalid (planes, r, k, R, volume or samples)",
               false);
  }
}

/// Read and check the header; then everything else, into `in`.
void readScene(hid_t file, Loaded& in, const Context& ctx)
{
  const Reader r(file, ctx);
  {
    const Id root = ctx.checkId(H5Gopen2(file, "/", H5P_DEFAULT), H5Gclose, "cannot open the root group");
    if (ctx.check(H5Aexists(root.get(), "magic"), "cannot read the root attributes") == 0
        || r.stringAttribute("/", "magic") != checkpointMagic)
      ctx.fail("not a Talus checkpoint (HDF5 file without the '" + std::string(checkpointMagic) + "' magic attribute)",
               false);
  }
  const std::int64_t version = r.integer("/", "format_version");
  if (version != checkpointFormatVersion)
    ctx.fail("checkpoint format version " + std::to_string(version) + " (written by Talus "
                 + r.stringAttribute("/", "talus_version") + "); this Talus (" + std::string(talus::version())
                 + ") reads version " + std::to_string(checkpointFormatVersion),
             false);

  in.dt = r.real("/clock", "dt");
  in.time = r.real("/clock", "time");
  in.iter = r.integer("/clock", "iter");
  in.bodiesVersion = r.integer("/clock", "bodiesVersion");
  in.bodyPropertiesVersion = r.integer("/clock", "bodyPropertiesVersion");

  in.maxOverlapRatio = r.real("/settings", "maxOverlapRatio");
  // Files written before these existed lack them: the defaults then.
  in.maxEnergyGrowth = r.hasAttribute("/settings", "maxEnergyGrowth") ? r.real("/settings", "maxEnergyGrowth") : 0.0;
  in.energy.growthReference = r.hasAttribute("/energy", "growthReference") ? r.real("/energy", "growthReference")
                                                                            : std::numeric_limits<double>::quiet_NaN();
  in.energy.enabled = r.integer("/energy", "enabled") != 0;
  // Files written before a term existed lack it: nothing of it was accumulated.
  for (const auto& [name, field] : energyTerms)
    in.energy.*field = r.hasAttribute("/energy", name) ? r.real("/energy", name) : 0.0;
  for (const auto& [name, field] : energyHistory)
    if (r.exists(at("/energy/", name)))
    {
      const std::vector<hsize_t> d = r.dims(at("/energy/", name));
      if (d.size() != 2 || d[1] != 3)
        ctx.fail(at("/energy/", name) + " is not an (n, 3) array", false);
      (in.energy.*field).assign(d[0], Vec3::Zero());
      r.vec3s(at("/energy/", name), in.energy.*field);
    }
  if (r.exists("/energy/grownBy")) // a growth not yet seen by the contacts
  {
    const std::vector<hsize_t> d = r.dims("/energy/grownBy");
    if (d.size() != 1)
      ctx.fail("/energy/grownBy is not one-dimensional", false);
    in.energy.grownBy.resize(d[0]);
    r.doubles("/energy/grownBy", {d[0]}, in.energy.grownBy.data());
  }
  in.periodic = r.integer("/cell", "periodic") != 0;
  in.cell.homoDeform = r.integer("/cell", "homoDeform") != 0;
  in.cell.hSize = r.matrix("/cell/hSize");
  in.cell.velGrad = r.matrix("/cell/velGrad");
  in.cell.prevVelGrad = r.matrix("/cell/prevVelGrad");
  in.cell.trsf = r.matrix("/cell/trsf");

  // Materials.
  {
    const std::vector<hsize_t> d = r.dims("/materials/density");
    if (d.size() != 1)
      ctx.fail("/materials/density is not one-dimensional", false);
    const std::size_t m = d[0];
    std::vector<std::uint8_t> kind(m);
    r.uint8s("/materials/kind", kind);
    const std::vector<std::string> label = r.strings("/materials/label");
    if (label.size() != m)
      ctx.fail("/materials/label has " + std::to_string(label.size()) + " entries, expected " + std::to_string(m),
               false);
    in.materials.resize(m);
    std::vector<double> column(m);
    for (const auto& [name, field] : materialScalars)
    {
      r.doubles(at("/materials/", name), {m}, column.data());
      for (std::size_t i = 0; i < m; ++i)
        in.materials[i].*field = column[i];
    }
    std::vector<std::uint8_t> flag(m);
    for (const auto& [name, field] : materialFlags)
    {
      r.uint8s(at("/materials/", name), flag);
      for (std::size_t i = 0; i < m; ++i)
        in.materials[i].*field = flag[i] != 0;
    }
    for (std::size_t i = 0; i < m; ++i)
    {
      if (kind[i] > static_cast<std::uint8_t>(MaterialKind::CohFrict))
        ctx.fail("material " + std::to_string(i) + " has unknown kind " + std::to_string(kind[i]), false);
      in.materials[i].kind = static_cast<MaterialKind>(kind[i]);
      in.materials[i].label = label[i];
    }
  }

  // Bodies.
  {
    const std::vector<hsize_t> d = r.dims("/bodies/pos");
    if (d.size() != 2 || d[1] != 3)
      ctx.fail("/bodies/pos is not an (n, 3) array", false);
    const std::size_t n = d[0];
    Bodies& b = in.bodies;
    for (const auto& [name, field] : bodyVectors)
    {
      (b.*field).assign(n, Vec3::Zero());
      r.vec3s(at("/bodies/", name), b.*field);
    }
    for (const auto& [name, field] : bodyScalars)
    {
      (b.*field).resize(n);
      r.doubles(at("/bodies/", name), {n}, (b.*field).data());
    }
    for (const auto& [name, field] : bodyInts)
    {
      (b.*field).resize(n);
      r.int32s(at("/bodies/", name), b.*field);
    }
    for (const auto& [name, field] : bodyBytes)
    {
      (b.*field).resize(n);
      r.uint8s(at("/bodies/", name), b.*field);
    }
    std::vector<double> ori(4 * n);
    r.doubles("/bodies/ori", {n, 4}, ori.data());
    b.ori.resize(n);
    for (std::size_t i = 0; i < n; ++i)
      b.ori[i] = Quat(ori[4 * i], ori[4 * i + 1], ori[4 * i + 2], ori[4 * i + 3]);
    std::vector<std::uint8_t> shape(n);
    r.uint8s("/bodies/shape", shape);
    b.shape.resize(n);
    for (std::size_t i = 0; i < n; ++i)
    {
      if (shape[i] > static_cast<std::uint8_t>(ShapeKind::PotentialParticle))
        ctx.fail("body " + std::to_string(i) + " has unknown shape kind " + std::to_string(shape[i]), false);
      b.shape[i] = static_cast<ShapeKind>(shape[i]);
    }

    const std::vector<hsize_t> dw = r.dims("/bodies/walls/axis");
    if (dw.size() != 1)
      ctx.fail("/bodies/walls/axis is not one-dimensional", false);
    std::vector<std::int32_t> axis(dw[0]), sense(dw[0]);
    r.int32s("/bodies/walls/axis", axis);
    r.int32s("/bodies/walls/sense", sense);
    for (std::size_t k = 0; k < axis.size(); ++k)
      b.walls.push_back({axis[k], sense[k]});

    const std::vector<hsize_t> df = r.dims("/bodies/facets/normal");
    if (df.size() != 2 || df[1] != 3)
      ctx.fail("/bodies/facets/normal is not an (n, 3) array", false);
    const std::size_t nf = df[0];
    std::vector<double> vertices(9 * nf), normal(3 * nf);
    r.doubles("/bodies/facets/vertices", {nf, 3, 3}, vertices.data());
    r.doubles("/bodies/facets/normal", {nf, 3}, normal.data());
    b.facets.resize(nf);
    for (std::size_t f = 0; f < nf; ++f)
    {
      for (std::size_t k = 0; k < 3; ++k)
        b.facets[f].vertices[k] = Vec3(vertices[9 * f + 3 * k], vertices[9 * f + 3 * k + 1], vertices[9 * f + 3 * k + 2]);
      b.facets[f].normal = Vec3(normal[3 * f], normal[3 * f + 1], normal[3 * f + 2]);
    }

    const std::vector<hsize_t> db = r.dims("/bodies/boxes/extents");
    if (db.size() != 2 || db[1] != 3)
      ctx.fail("/bodies/boxes/extents is not an (n, 3) array", false);
    std::vector<Vec3> extents(db[0]);
    r.vec3s("/bodies/boxes/extents", extents);
    for (const Vec3& e : extents)
      b.boxes.push_back({e});

    const std::vector<hsize_t> ds = r.dims("/bodies/clumps/start"), dm = r.dims("/bodies/clumps/members");
    if (ds.size() != 1 || ds[0] < 1 || dm.size() != 1)
      ctx.fail("/bodies/clumps/start or /bodies/clumps/members is not a one-dimensional array", false);
    std::vector<std::int32_t> start(ds[0]), members(dm[0]);
    r.int32s("/bodies/clumps/start", start);
    r.int32s("/bodies/clumps/members", members);
    std::vector<Vec3> relPos(dm[0]);
    std::vector<double> relOri(4 * dm[0]);
    r.vec3s("/bodies/clumps/relPos", relPos);
    r.doubles("/bodies/clumps/relOri", {dm[0], 4}, relOri.data());
    if (start.front() != 0 || start.back() != static_cast<std::int32_t>(members.size())
        || !std::is_sorted(start.begin(), start.end()))
      ctx.fail("/bodies/clumps/start does not partition the members", false);
    for (std::size_t k = 0; k + 1 < start.size(); ++k)
    {
      ClumpShape clump;
      for (auto e = static_cast<std::size_t>(start[k]); e < static_cast<std::size_t>(start[k + 1]); ++e)
      {
        clump.members.push_back(members[e]);
        clump.relPos.push_back(relPos[e]);
        clump.relOri.emplace_back(relOri[4 * e], relOri[4 * e + 1], relOri[4 * e + 2], relOri[4 * e + 3]);
      }
      b.clumps.push_back(std::move(clump));
    }
    readPlaneShapes(r, b, ctx);
  }

  // Contacts.
  {
    const std::vector<hsize_t> d = r.dims("/contacts/id1");
    if (d.size() != 1)
      ctx.fail("/contacts/id1 is not one-dimensional", false);
    const std::size_t c = d[0];
    std::vector<Contact>& list = in.contacts;
    list.resize(c);
    std::vector<std::int32_t> ints(c), cellDist(3 * c);
    for (const auto& [name, field] : contactIds)
    {
      r.int32s(at("/contacts/", name), ints);
      for (std::size_t k = 0; k < c; ++k)
        list[k].*field = ints[k];
    }
    r.array("/contacts/cellDist", H5T_INTEGER, H5T_NATIVE_INT32, {c, 3}, cellDist.data());
    for (std::size_t k = 0; k < c; ++k)
      list[k].cellDist = Eigen::Vector3i(cellDist[3 * k], cellDist[3 * k + 1], cellDist[3 * k + 2]);
    std::vector<std::uint8_t> bytes(c);
    for (const auto& [name, field] : contactFlags)
    {
      r.uint8s(at("/contacts/", name), bytes);
      for (std::size_t k = 0; k < c; ++k)
        list[k].*field = bytes[k] != 0;
    }
    r.uint8s("/contacts/law", bytes);
    for (std::size_t k = 0; k < c; ++k)
      list[k].law = bytes[k];
    r.uint8s("/contacts/kind", bytes);
    for (std::size_t k = 0; k < c; ++k)
    {
      if (bytes[k] > static_cast<std::uint8_t>(ContactGeometryKind::WallParticle))
        ctx.fail("contact " + std::to_string(k) + " has unknown kind " + std::to_string(bytes[k]), false);
      list[k].kind = static_cast<ContactGeometryKind>(bytes[k]);
    }
    std::vector<Vec3> column3(c);
    for (const auto& [name, field] : contactVectors)
    {
      r.vec3s(at("/contacts/", name), column3);
      for (std::size_t k = 0; k < c; ++k)
        list[k].*field = column3[k];
    }
    std::vector<double> column(c);
    for (const auto& [name, field] : contactScalars)
    {
      r.doubles(at("/contacts/", name), {c}, column.data());
      for (std::size_t k = 0; k < c; ++k)
        list[k].*field = column[k];
    }
    const std::vector<hsize_t> de = r.dims("/contacts/extra/kno");
    if (de.size() != 1 || (de[0] != 0 && de[0] != c))
      ctx.fail("/contacts/extra has " + std::to_string(de.empty() ? 0 : de[0]) + " rows for " + std::to_string(c)
                   + " contacts (expected 0 or as many)",
               false);
    const std::size_t e = de[0];
    std::vector<ContactExtra>& extra = in.contactExtra;
    extra.resize(e);
    column.resize(e);
    for (const auto& [name, field] : extraScalars)
    {
      r.doubles(at("/contacts/extra/", name), {e}, column.data());
      for (std::size_t k = 0; k < e; ++k)
        extra[k].*field = column[k];
    }
    column3.resize(e);
    for (const auto& [name, field] : extraVectors)
    {
      r.vec3s(at("/contacts/extra/", name), column3);
      for (std::size_t k = 0; k < e; ++k)
        extra[k].*field = column3[k];
    }
    std::vector<double> quats(4 * e);
    for (const auto& [name, field] : extraQuats)
    {
      r.doubles(at("/contacts/extra/", name), {e, 4}, quats.data());
      for (std::size_t k = 0; k < e; ++k)
        extra[k].*field = Quat(quats[4 * k], quats[4 * k + 1], quats[4 * k + 2], quats[4 * k + 3]);
    }
    bytes.resize(e);
    for (const auto& [name, field] : extraBytes)
    {
      r.uint8s(at("/contacts/extra/", name), bytes);
      for (std::size_t k = 0; k < e; ++k)
        extra[k].*field = bytes[k];
    }
  }

  // Extras.
  if (r.exists("/extras"))
    for (const std::string& name : r.members("/extras"))
    {
      const std::vector<std::string> text = r.strings("/extras/" + name);
      if (text.size() != 1)
        ctx.fail("/extras/" + name + " is not a single string", false);
      in.extras[name] = text[0];
    }
}

/// The geometry kind the collider gives a pair of these shapes (body 1 first).
bool kindMatchesShapes(ContactGeometryKind kind, ShapeKind first, ShapeKind second)
{
  switch (kind)
  {
  case ContactGeometryKind::SphereSphere: return first == ShapeKind::Sphere && second == ShapeKind::Sphere;
  case ContactGeometryKind::WallSphere: return first == ShapeKind::Wall && second == ShapeKind::Sphere;
  case ContactGeometryKind::FacetSphere: return first == ShapeKind::Facet && second == ShapeKind::Sphere;
  case ContactGeometryKind::BoxSphere: return first == ShapeKind::Box && second == ShapeKind::Sphere;
  case ContactGeometryKind::BlockBlock: return first == ShapeKind::PotentialBlock && second == ShapeKind::PotentialBlock;
  case ContactGeometryKind::WallBlock: return first == ShapeKind::Wall && second == ShapeKind::PotentialBlock;
  case ContactGeometryKind::ParticleParticle:
    return first == ShapeKind::PotentialParticle && second == ShapeKind::PotentialParticle;
  case ContactGeometryKind::WallParticle: return first == ShapeKind::Wall && second == ShapeKind::PotentialParticle;
  }
  return false;
}

/// Consistency of what was read: every index in range, the contact list sorted, the
/// materials valid. Catches damage that checksums cannot (a file edited by hand).
void validate(const Loaded& in, const Context& ctx)
{
  if (!(std::isfinite(in.dt) && in.dt > 0))
    ctx.fail("the time step dt = " + std::to_string(in.dt) + " is not positive and finite", false);
  if (!std::isfinite(in.time) || in.iter < 0)
    ctx.fail("the clock (time " + std::to_string(in.time) + ", iter " + std::to_string(in.iter) + ") is invalid", false);
  if (!(std::isfinite(in.maxOverlapRatio) && in.maxOverlapRatio >= 0))
    ctx.fail("maxOverlapRatio = " + std::to_string(in.maxOverlapRatio) + " is not a finite number >= 0", false);
  if (!(std::isfinite(in.maxEnergyGrowth) && in.maxEnergyGrowth >= 0))
    ctx.fail("maxEnergyGrowth = " + std::to_string(in.maxEnergyGrowth) + " is not a finite number >= 0", false);
  for (std::size_t i = 0; i < in.materials.size(); ++i)
    try
    {
      in.materials[i].validate();
    }
    catch (const std::exception& e)
    {
      ctx.fail("material " + std::to_string(i) + ": " + e.what(), false);
    }
  const Bodies& b = in.bodies;
  const std::size_t n = b.size();
  for (std::size_t i = 0; i < n; ++i)
  {
    const std::string which = "body " + std::to_string(i);
    if (b.material[i] < 0 || static_cast<std::size_t>(b.material[i]) >= in.materials.size())
      ctx.fail(which + " has material index " + std::to_string(b.material[i]) + " but there are "
                   + std::to_string(in.materials.size()) + " materials",
               false);
    const int s = b.shapeIndex[i];
    const auto within = [s](std::size_t count) { return s >= 0 && static_cast<std::size_t>(s) < count; };
    bool ok = false;
    switch (b.shape[i])
    {
    case ShapeKind::Sphere: ok = s == -1; break;
    case ShapeKind::Wall: ok = within(b.walls.size()); break;
    case ShapeKind::Facet: ok = within(b.facets.size()); break;
    case ShapeKind::Box: ok = within(b.boxes.size()); break;
    case ShapeKind::Clump: ok = within(b.clumps.size()); break;
    case ShapeKind::PotentialBlock: ok = within(b.blocks.size()); break;
    case ShapeKind::PotentialParticle: ok = within(b.particles.size()); break;
    }
    if (!ok)
      ctx.fail(which + " has an invalid shape index " + std::to_string(s), false);
    const BodyId clump = b.clumpId[i];
    if (clump >= 0)
    {
      // A member must be listed by the clump it names.
      const bool listed = static_cast<std::size_t>(clump) < n && b.shape[static_cast<std::size_t>(clump)] == ShapeKind::Clump
                          && b.shapeIndex[static_cast<std::size_t>(clump)] >= 0
                          && static_cast<std::size_t>(b.shapeIndex[static_cast<std::size_t>(clump)]) < b.clumps.size();
      const auto& members = listed ? b.clumps[static_cast<std::size_t>(b.shapeIndex[static_cast<std::size_t>(clump)])].members
                                   : std::vector<BodyId>{};
      if (!listed || std::find(members.begin(), members.end(), static_cast<BodyId>(i)) == members.end())
        ctx.fail(which + " names clump " + std::to_string(clump) + " which does not list it as a member", false);
    }
    else if (clump != -1)
      ctx.fail(which + " has an invalid clump id " + std::to_string(clump), false);
    if (b.blockedDofs[i] > DofAll || b.dynamic[i] > 1 || b.alive[i] > 1)
      ctx.fail(which + " has invalid flags (blockedDofs, dynamic or alive)", false);
  }
  for (std::size_t k = 0; k < b.clumps.size(); ++k)
    for (BodyId m : b.clumps[k].members)
      if (m < 0 || static_cast<std::size_t>(m) >= n || b.clumpId[static_cast<std::size_t>(m)] < 0)
        ctx.fail("clump shape " + std::to_string(k) + " lists body " + std::to_string(m)
                     + " which is not one of its members",
                 false);
  validatePlaneShapes(b, ctx);
  for (std::size_t k = 0; k < b.boxes.size(); ++k)
    if (!b.boxes[k].extents.allFinite() || !(b.boxes[k].extents.minCoeff() > 0))
      ctx.fail("box shape " + std::to_string(k) + " has invalid extents", false);
  for (std::size_t k = 0; k < b.walls.size(); ++k)
    if (b.walls[k].axis < 0 || b.walls[k].axis > 2 || b.walls[k].sense < -1 || b.walls[k].sense > 1)
      ctx.fail("wall shape " + std::to_string(k) + " has an invalid axis or sense", false);
  const auto key = [](const Contact& c) {
    return (static_cast<std::uint64_t>(c.id1) << 32) | static_cast<std::uint32_t>(c.id2);
  };
  for (std::size_t k = 0; k < in.contacts.size(); ++k)
  {
    const Contact& c = in.contacts[k];
    const std::string which = "contact " + std::to_string(k) + " (" + std::to_string(c.id1) + ", "
                              + std::to_string(c.id2) + ")";
    if (c.id1 < 0 || c.id2 < 0 || static_cast<std::size_t>(c.id1) >= n || static_cast<std::size_t>(c.id2) >= n
        || c.id1 == c.id2)
      ctx.fail(which + " refers to bodies that do not exist (" + std::to_string(n) + " bodies)", false);
    if (!kindMatchesShapes(c.kind, b.shape[static_cast<std::size_t>(c.id1)], b.shape[static_cast<std::size_t>(c.id2)]))
      ctx.fail(which + " has a kind that does not match the shapes of its bodies", false);
    if (k > 0 && key(in.contacts[k - 1]) > key(c))
      ctx.fail("the contact list is not sorted by (id1, id2) at " + which, false);
  }
  if (!in.cell.hSize.allFinite() || (in.periodic && !(in.cell.hSize.determinant() > 0)))
    ctx.fail("the periodic cell hSize is degenerate or not finite", false);
}

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
} // namespace

void saveCheckpoint(const Scene& scene, const std::string& path, const CheckpointExtras& extras)
{
  namespace fs = std::filesystem;
  const Context ctx("checkpoint " + quoted(path));
  const QuietErrors quiet;
  if (path.empty())
    ctx.fail("the file name is empty", false);
  const fs::path target(path);
  const fs::path folder = target.has_parent_path() ? target.parent_path() : fs::path(".");
  std::error_code ec;
  if (!fs::is_directory(folder, ec))
    ctx.fail("cannot write: the folder " + quoted(folder.string()) + " does not exist", false);
  if (fs::is_directory(target, ec))
    ctx.fail("cannot write: it is a folder", false);
  const std::string temporary = (folder / ("." + target.filename().string() + ".tmp-" + std::to_string(::getpid())
                                           + "-" + std::to_string(uniqueCounter++)))
                                    .string();
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
    syncPath(temporary, false, ctx);
    if (std::rename(temporary.c_str(), path.c_str()) != 0)
      ctx.fail("cannot replace the file with the new checkpoint: " + errnoText(errno), false);
  }
  catch (...)
  {
    ::unlink(temporary.c_str());
    throw;
  }
  syncPath(folder.string(), true, ctx);
}

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
