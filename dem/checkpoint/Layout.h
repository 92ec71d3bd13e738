// What a checkpoint file holds, shared by its writer and reader (internal, not installed): the
// fields stored column by column, the scene as read before it is checked, and the three steps
// (write, read, check).
#pragma once

#include "dem/checkpoint/BodyHeat.h"
#include "dem/checkpoint/Hdf5.h"

namespace talus::dem::checkpoint
{
/// Row-major copy of 3x3 matrices (Eigen stores them by column).
/// @return m(0,0), m(0,1), ..., m(2,2)
inline std::array<double, 9> rowMajor(const Mat3& m)
{
  std::array<double, 9> out{};
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      out[static_cast<std::size_t>(3 * i + j)] = m(i, j);
  return out;
}

/// Whether a user's checkpoint extra may have this name (it becomes an HDF5 path component).
/// @param name the extra's name
/// @return true for a non-empty name of ASCII letters, digits, '_' and '-'
inline bool validExtraName(const std::string& name)
{
  return !name.empty() && std::all_of(name.begin(), name.end(), [](char ch) {
    return (ch >= 'a' && ch <= 'z') || (ch >= 'A' && ch <= 'Z') || (ch >= '0' && ch <= '9') || ch == '_' || ch == '-';
  });
}

/// The fields stored column by column: one dataset per field, named as the field.
inline constexpr std::pair<const char*, double Material::*> materialScalars[] = {
    {"density", &Material::density}, {"young", &Material::young}, {"poisson", &Material::poisson},
    {"frictionAngle", &Material::frictionAngle}, {"tc", &Material::tc}, {"en", &Material::en}, {"et", &Material::et},
    {"kn", &Material::kn}, {"cn", &Material::cn}, {"ks", &Material::ks}, {"cs", &Material::cs},
    {"normalCohesion", &Material::normalCohesion}, {"shearCohesion", &Material::shearCohesion},
    {"alphaKr", &Material::alphaKr}, {"alphaKtw", &Material::alphaKtw}, {"etaRoll", &Material::etaRoll},
    {"etaTwist", &Material::etaTwist}, {"mR", &Material::mR}, {"viscoDyn", &Material::viscoDyn},
    {"roughnessScale", &Material::roughnessScale}};
inline constexpr std::pair<const char*, bool Material::*> materialFlags[] = {
    {"isCohesive", &Material::isCohesive}, {"momentRotationLaw", &Material::momentRotationLaw},
    {"fragile", &Material::fragile}, {"lubrication", &Material::lubrication}};
inline constexpr std::pair<const char*, int Material::*> materialInts[] = {{"mRtype", &Material::mRtype}};
inline constexpr std::pair<const char*, Vec3 Contact::*> contactVectors[] = {
    {"normal", &Contact::normal}, {"contactPoint", &Contact::contactPoint},
    {"shearIncrement", &Contact::shearIncrement}, {"normalForce", &Contact::normalForce},
    {"shearForce", &Contact::shearForce}, {"force", &Contact::force}};
inline constexpr std::pair<const char*, double Contact::*> contactScalars[] = {
    {"penetration", &Contact::penetration}, {"refR1", &Contact::refR1}, {"refR2", &Contact::refR2},
    {"kn", &Contact::kn}, {"ks", &Contact::ks}, {"cn", &Contact::cn}, {"cs", &Contact::cs}, {"tanPhi", &Contact::tanPhi}};
// Contacts::extra (the richer models' state): one dataset per field under /contacts/extra, the
// fields the contact-law parts declare (core/ContactExtra.h) but the transient ones.
// The energy tracker's accumulated terms, attributes of /energy.
inline constexpr std::pair<const char*, double EnergyTracker::*> energyTerms[] = {
    {"gravWork", &EnergyTracker::gravWork}, {"nonviscDamp", &EnergyTracker::nonviscDamp},
    {"plastDissip", &EnergyTracker::plastDissip}, {"viscDamp", &EnergyTracker::viscDamp},
    {"velGradWork", &EnergyTracker::velGradWork}, {"kinematicWork", &EnergyTracker::kinematicWork},
    {"growthWork", &EnergyTracker::growthWork}};
// The tracker's imposed displacements of the previous step, datasets of /energy (absent until tracked).
inline constexpr std::pair<const char*, std::vector<Vec3> EnergyTracker::*> energyHistory[] = {
    {"previousDisplacement", &EnergyTracker::previousDisplacement},
    {"previousRotation", &EnergyTracker::previousRotation}};
inline constexpr std::pair<const char*, BodyId Contact::*> contactIds[] = {{"id1", &Contact::id1}, {"id2", &Contact::id2}};
inline constexpr std::pair<const char*, bool Contact::*> contactFlags[] = {{"real", &Contact::real}, {"fresh", &Contact::fresh}};
inline constexpr std::pair<const char*, std::vector<Vec3> Bodies::*> bodyVectors[] = {
    {"pos", &Bodies::pos},           {"vel", &Bodies::vel},       {"angVel", &Bodies::angVel},
    {"force", &Bodies::force},       {"torque", &Bodies::torque}, {"extForce", &Bodies::extForce},
    {"extTorque", &Bodies::extTorque}, {"inertia", &Bodies::inertia}, {"angMom", &Bodies::angMom}};
inline constexpr std::pair<const char*, std::vector<double> Bodies::*> bodyScalars[] = {{"mass", &Bodies::mass},
                                                                                  {"radius", &Bodies::radius}};
inline constexpr std::pair<const char*, std::vector<int> Bodies::*> bodyInts[] = {
    {"shapeIndex", &Bodies::shapeIndex}, {"material", &Bodies::material}, {"clumpId", &Bodies::clumpId},
    {"groupMask", &Bodies::groupMask}};
inline constexpr std::pair<const char*, std::vector<std::uint8_t> Bodies::*> bodyBytes[] = {
    {"blockedDofs", &Bodies::blockedDofs}, {"dynamic", &Bodies::dynamic}, {"alive", &Bodies::alive},
    {"damped", &Bodies::damped}};
static_assert(sizeof(int) == 4 && sizeof(BodyId) == 4, "int arrays are written as 32-bit integers");

/// @param group a group's path ending in '/' ("/bodies/")
/// @param name a dataset's name
/// @return the dataset's path
inline std::string at(const char* group, const char* name) { return std::string(group) + name; }

// Potential Blocks and Particles: every field of their shapes, derived ones included (vertices,
// faces, principal frame, surface samples), so that a restored scene computes the same bits
// as the saved one (recomputing them from the planes would round differently). Lists of
// varying length (planes, vertices, ...) are concatenated over the shapes: shape k owns entries
// [start[k], start[k + 1]) of `<name>` with `<name>Start` (n + 1 entries).
inline constexpr std::pair<const char*, double PotentialBlockShape::*> blockScalars[] = {
    {"r", &PotentialBlockShape::r}, {"R", &PotentialBlockShape::R}, {"volume", &PotentialBlockShape::volume},
    {"boundingRadius", &PotentialBlockShape::boundingRadius}};
inline constexpr std::pair<const char*, std::vector<Vec3> PotentialBlockShape::*> blockVectorLists[] = {
    {"normals", &PotentialBlockShape::normals}, {"vertices", &PotentialBlockShape::vertices},
    {"edgeDirections", &PotentialBlockShape::edgeDirections}};
inline constexpr std::pair<const char*, double PotentialParticleShape::*> particleScalars[] = {
    {"r", &PotentialParticleShape::r}, {"k", &PotentialParticleShape::k}, {"R", &PotentialParticleShape::R},
    {"volume", &PotentialParticleShape::volume}, {"boundingRadius", &PotentialParticleShape::boundingRadius}};
inline constexpr std::pair<const char*, Vec3 PotentialParticleShape::*> particleVectors[] = {
    {"centroid", &PotentialParticleShape::centroid}, {"inertiaPerDensity", &PotentialParticleShape::inertiaPerDensity}};
inline constexpr std::pair<const char*, std::vector<Vec3> PotentialParticleShape::*> particleVectorLists[] = {
    {"normals", &PotentialParticleShape::normals}, {"samples", &PotentialParticleShape::samples}};

/// How a contact state field of type T is stored, for the writer and the reader alike: `width`
/// values of type `Stored` per contact (a dataset of shape (rows) for one value, (rows, width)
/// otherwise), `put` writes a value into its row and `get` makes it back from the row.
template <class T>
struct StateColumn;
template <>
struct StateColumn<double>
{
  using Stored = double;
  static constexpr std::size_t width = 1;
  /// @param value the field's value
  /// @param row its `width` stored values, written
  static void put(double value, double* row) { row[0] = value; }
  /// @param row the `width` stored values
  /// @return the field's value
  static double get(const double* row) { return row[0]; }
};
template <>
struct StateColumn<Vec3>
{
  using Stored = double;
  static constexpr std::size_t width = 3;
  /// @param value the field's value
  /// @param row its `width` stored values, written
  static void put(const Vec3& value, double* row) { row[0] = value.x(), row[1] = value.y(), row[2] = value.z(); }
  /// @param row the `width` stored values
  /// @return the field's value
  static Vec3 get(const double* row) { return Vec3(row[0], row[1], row[2]); }
};
template <>
struct StateColumn<Quat>
{
  using Stored = double;
  static constexpr std::size_t width = 4;
  /// @param value the field's value
  /// @param row its `width` stored values, written
  static void put(const Quat& value, double* row)
  {
    row[0] = value.w(), row[1] = value.x(), row[2] = value.y(), row[3] = value.z();
  }
  /// @param row the `width` stored values (w, x, y, z)
  /// @return the field's value
  static Quat get(const double* row) { return Quat(row[0], row[1], row[2], row[3]); }
};
template <>
struct StateColumn<std::uint8_t>
{
  using Stored = std::uint8_t;
  static constexpr std::size_t width = 1;
  /// @param value the field's value
  /// @param row its `width` stored values, written
  static void put(std::uint8_t value, std::uint8_t* row) { row[0] = value; }
  /// @param row the `width` stored values
  /// @return the field's value
  static std::uint8_t get(const std::uint8_t* row) { return row[0]; }
};

/// The HDF5 types of a stored value: in the file, in memory, and the class the reader accepts.
template <class Stored>
struct StoredType;
template <>
struct StoredType<double>
{
  /// @return the type in the file (little-endian, whatever the machine)
  static hid_t file() { return H5T_IEEE_F64LE; }
  /// @return the type in memory (native)
  static hid_t memory() { return H5T_NATIVE_DOUBLE; }
  static constexpr H5T_class_t typeClass = H5T_FLOAT;
};
template <>
struct StoredType<std::uint8_t>
{
  /// @return the type in the file (little-endian, whatever the machine)
  static hid_t file() { return H5T_STD_U8LE; }
  /// @return the type in memory (native)
  static hid_t memory() { return H5T_NATIVE_UINT8; }
  static constexpr H5T_class_t typeClass = H5T_INTEGER;
};

/// The dataset shape of `rows` values of type T.
/// @param rows the number of contacts
/// @return (rows) for one value per contact, else (rows, width)
template <class T>
std::vector<hsize_t> stateColumnShape(std::size_t rows)
{
  if constexpr (StateColumn<T>::width == 1)
    return {rows};
  else
    return {rows, StateColumn<T>::width};
}

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
  ContactList contacts;
  ContactExtraList contactExtra;
  EnergyTracker energy;
  CheckpointExtras extras;
};

/// Write every part of the scene (bodies, shapes, materials, contacts, cell, clock, energy,
/// extras) into the open file; `checksums`: numeric datasets checksummed (files, not images).
/// @param file the open file (or in-memory image), not owned
/// @param extras the user's extra datasets saved with the scene
/// @param ctx names the checkpoint in errors
/// @param checksums chunk numeric datasets with a Fletcher-32 checksum
/// @throws CheckpointError naming the path when HDF5 refuses
void writeScene(hid_t file, const Scene& scene, const CheckpointExtras& extras, const Context& ctx, bool checksums);

/// How the processes writing one file together split its rows: each writes its bodies (global
/// ids, ascending) at `bodies`, its contacts (sorted by (id1, id2), after those of the processes
/// before it) at `contacts`, their richer state at `contactExtra` (of total 0 when the list
/// keeps none, the contacts' rows otherwise); `energyHistory`: whether the energy tracker's
/// per-body memory is written (decided alike on every process), in the bodies' rows;
/// `heat`: the heat fields written (those a body of any process has a value of), as bodyHeat.
struct Slabs
{
  Rows bodies, contacts, contactExtra;
  bool energyHistory = false;
  std::array<bool, std::size(bodyHeat)> heat{};
};
/// writeScene by one of several processes writing one file (parallel HDF5): `scene` holds this
/// process's rows (`slabs`) and what every process holds alike (clock, materials, shapes, cell).
/// @param w the writer (collective transfers; the process writing the whole datasets)
/// @param file, scene, extras, ctx as writeScene's
/// @param slabs this process's rows; null: one process writes everything
/// @throws CheckpointError naming the path when HDF5 refuses
void writeScene(const Writer& w, hid_t file, const Scene& scene, const CheckpointExtras& extras, const Context& ctx,
                const Slabs* slabs);
/// Read every part into `in` (shapes and lists checked as they are read).
/// @param file the open file (or in-memory image), not owned
/// @param in filled; the scene is not touched
/// @param ctx names the checkpoint in errors
/// @throws CheckpointError for a missing or malformed part, or corrupted data
void readScene(hid_t file, Loaded& in, const Context& ctx);
/// Consistency of what was read: every index in range, the contact list sorted, the
/// materials valid. Catches damage that checksums cannot (a file edited by hand).
/// @param in what readScene read
/// @param ctx names the checkpoint in errors
/// @throws CheckpointError naming the first inconsistency
void validate(const Loaded& in, const Context& ctx);
} // namespace talus::dem::checkpoint
