// Writing a checkpoint: every part of a scene into an open HDF5 file (dem/checkpoint/Layout.h).
#include "dem/checkpoint/BodyHeat.h"
#include "dem/checkpoint/Layout.h"

#include <type_traits>

namespace talus::dem::checkpoint
{
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

/// Materials: one entry per material, in index order.
void writeMaterials(const Writer& w, const Scene& scene)
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
  std::vector<std::int32_t> integer(mats.size());
  for (const auto& [name, field] : materialInts)
  {
    for (std::size_t i = 0; i < mats.size(); ++i)
      integer[i] = mats[i].*field;
    w.int32s(at("/materials/", name), integer.data(), integer.size());
  }
}

/// Bodies: every array, erased slots included (ids are indices); `slabs`: the bodies' rows this
/// process writes when several write the file (the shape tables are whole).
void writeBodies(const Writer& w, const Scene& scene, const Slabs* slabs)
{
  const Bodies& b = scene.bodies;
  const std::size_t n = b.size();
  const Id g = w.group("/bodies");
  const Writer rw = w.rows(slabs ? &slabs->bodies : nullptr);
  for (const auto& [name, field] : bodyVectors)
    rw.vec3s(at("/bodies/", name), b.*field);
  for (const auto& [name, field] : bodyScalars)
    rw.doubles(at("/bodies/", name), {n}, (b.*field).data());
  writeBodyHeat(rw, b, slabs ? &slabs->heat : nullptr);
  for (const auto& [name, field] : bodyInts)
    rw.int32s(at("/bodies/", name), (b.*field).data(), n);
  for (const auto& [name, field] : bodyBytes)
    rw.uint8s(at("/bodies/", name), (b.*field).data(), n);
  std::vector<double> ori(4 * n);
  for (std::size_t i = 0; i < n; ++i)
  {
    const Quat& q = b.ori[i];
    std::copy_n(std::array<double, 4>{q.w(), q.x(), q.y(), q.z()}.begin(), 4, ori.begin() + static_cast<std::ptrdiff_t>(4 * i));
  }
  rw.doubles("/bodies/ori", {n, 4}, ori.data());
  std::vector<std::uint8_t> shape(n);
  for (std::size_t i = 0; i < n; ++i)
    shape[i] = static_cast<std::uint8_t>(b.shape[i]);
  rw.uint8s("/bodies/shape", shape.data(), n);

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
  std::vector<std::int32_t> bounded(nf);
  for (std::size_t f = 0; f < nf; ++f)
    bounded[f] = b.facets[f].bounded ? 1 : 0;
  w.int32s("/bodies/facets/bounded", bounded.data(), bounded.size());

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

/// Contacts: the real ones in list order, every field of Contact. The others are candidate
/// pairs inside the collider's skin, without history (Contact::reset), which the loaded scene's
/// first re-detection finds again: a settled bed has several times more of them than contacts.
/// `slabs`: the contacts' rows this process writes when several write the file.
void writeContacts(const Writer& whole, const Scene& scene, const Slabs* slabs)
{
  const ContactList& all = scene.contacts.list;
  std::vector<std::size_t> live;
  for (std::size_t k = 0; k < all.size(); ++k)
    if (all[k].real)
      live.push_back(k);
  const std::size_t c = live.size();
  auto list = [&](std::size_t k) -> const Contact& { return all[live[k]]; };
  const Id g = whole.group("/contacts");
  const Writer w = whole.rows(slabs ? &slabs->contacts : nullptr);
  std::vector<std::int32_t> ids(c), cellDist(3 * c);
  for (const auto& [name, field] : contactIds)
  {
    for (std::size_t k = 0; k < c; ++k)
      ids[k] = list(k).*field;
    w.int32s(at("/contacts/", name), ids.data(), c);
  }
  for (std::size_t k = 0; k < c; ++k)
    for (std::size_t d = 0; d < 3; ++d)
      cellDist[3 * k + d] = list(k).cellDist[static_cast<int>(d)];
  w.array("/contacts/cellDist", H5T_STD_I32LE, H5T_NATIVE_INT32, {c, 3}, cellDist.data());
  std::vector<std::uint8_t> bytes(c);
  for (const auto& [name, field] : contactFlags)
  {
    for (std::size_t k = 0; k < c; ++k)
      bytes[k] = list(k).*field ? 1 : 0;
    w.uint8s(at("/contacts/", name), bytes.data(), c);
  }
  for (std::size_t k = 0; k < c; ++k)
    bytes[k] = static_cast<std::uint8_t>(list(k).kind);
  w.uint8s("/contacts/kind", bytes.data(), c);
  for (std::size_t k = 0; k < c; ++k)
    bytes[k] = list(k).law;
  w.uint8s("/contacts/law", bytes.data(), c);
  std::vector<Vec3> column3(c);
  for (const auto& [name, field] : contactVectors)
  {
    for (std::size_t k = 0; k < c; ++k)
      column3[k] = list(k).*field;
    w.vec3s(at("/contacts/", name), column3);
  }
  std::vector<double> column(c);
  for (const auto& [name, field] : contactScalars)
  {
    for (std::size_t k = 0; k < c; ++k)
      column[k] = list(k).*field;
    w.doubles(at("/contacts/", name), {c}, column.data());
  }
  // The richer models' state: as many rows as contacts, or none.
  const ContactExtra* state = scene.contacts.extraState();
  const std::size_t e = state ? c : 0;
  auto extra = [&](std::size_t k) -> const ContactExtra& { return state[live[k]]; };
  const Id ge = whole.group("/contacts/extra");
  const Writer we = whole.rows(slabs ? &slabs->contactExtra : nullptr);
  forEachContactStateField([&](const auto& f) {
    using T = std::remove_cvref_t<decltype(extra(0).*f.member)>;
    using Column = StateColumn<T>;
    using Stored = StoredType<typename Column::Stored>;
    if (!f.stored)
      return;
    std::vector<typename Column::Stored> rows(e * Column::width);
    for (std::size_t k = 0; k < e; ++k)
      Column::put(extra(k).*f.member, rows.data() + k * Column::width);
    we.array(at("/contacts/extra/", f.name), Stored::file(), Stored::memory(), stateColumnShape<T>(e), rows.data());
  });
}

void writeScene(hid_t file, const Scene& scene, const CheckpointExtras& extras, const Context& ctx, bool checksums)
{
  writeScene(Writer(file, ctx, checksums), file, scene, extras, ctx, nullptr);
}

void writeScene(const Writer& w, hid_t file, const Scene& scene, const CheckpointExtras& extras, const Context& ctx,
                const Slabs* slabs)
{
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
    // Per body, as the bodies' arrays (in rows when several processes write).
    const Writer rw = w.rows(slabs ? &slabs->bodies : nullptr);
    for (const auto& [name, field] : energyHistory)
      if (slabs ? slabs->energyHistory : !(scene.energy.*field).empty())
        rw.vec3s(at("/energy/", name), scene.energy.*field);
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

  writeMaterials(w, scene);
  writeBodies(w, scene, slabs);
  writeContacts(w, scene, slabs);

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
} // namespace talus::dem::checkpoint
