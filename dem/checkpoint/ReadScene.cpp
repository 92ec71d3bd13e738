// Reading a checkpoint: every part of a scene from an open HDF5 file, then the checks of what
// was read (dem/checkpoint/Layout.h).
#include "dem/checkpoint/BodyHeat.h"
#include "dem/checkpoint/Layout.h"

#include <type_traits>

namespace talus::dem::checkpoint
{
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
/// Materials, each checked as it is read.
void readMaterials(const Reader& r, Loaded& in, const Context& ctx)
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
  std::vector<std::int32_t> integer(m);
  for (const auto& [name, field] : materialInts)
  {
    r.int32s(at("/materials/", name), integer);
    for (std::size_t i = 0; i < m; ++i)
      in.materials[i].*field = integer[i];
  }
  for (std::size_t i = 0; i < m; ++i)
  {
    if (kind[i] > static_cast<std::uint8_t>(MaterialKind::CohFrict))
      ctx.fail("material " + std::to_string(i) + " has unknown kind " + std::to_string(kind[i]), false);
    in.materials[i].kind = static_cast<MaterialKind>(kind[i]);
    in.materials[i].label = label[i];
  }
}

/// Bodies: every array and shape, checked against each other.
void readBodies(const Reader& r, Loaded& in, const Context& ctx)
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
  readBodyHeat(r, b, n);
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
  if (r.exists("/bodies/facets/bounded")) // written since facets may have no bound
  {
    std::vector<std::int32_t> bounded(nf);
    r.int32s("/bodies/facets/bounded", bounded);
    for (std::size_t f = 0; f < nf; ++f)
      b.facets[f].bounded = bounded[f] != 0;
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

/// Contacts: the list and the richer models' state beside it.
void readContacts(const Reader& r, Loaded& in, const Context& ctx)
{
  const std::vector<hsize_t> d = r.dims("/contacts/id1");
  if (d.size() != 1)
    ctx.fail("/contacts/id1 is not one-dimensional", false);
  const std::size_t c = d[0];
  ContactList& list = in.contacts;
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
  ContactExtraList& extra = in.contactExtra;
  extra.resize(e);
  forEachContactStateField([&](const auto& f) {
    using T = std::remove_cvref_t<decltype(extra[0].*f.member)>;
    using Column = StateColumn<T>;
    using Stored = StoredType<typename Column::Stored>;
    if (!f.stored)
      return;
    std::vector<typename Column::Stored> rows(e * Column::width);
    r.array(at("/contacts/extra/", f.name), Stored::typeClass, Stored::memory(), stateColumnShape<T>(e), rows.data());
    for (std::size_t k = 0; k < e; ++k)
      extra[k].*f.member = Column::get(rows.data() + k * Column::width);
  });
}

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
  if (version < oldestCheckpointFormatVersion || version > checkpointFormatVersion)
    ctx.fail("checkpoint format version " + std::to_string(version) + " (written by Talus "
                 + r.stringAttribute("/", "talus_version") + "); this Talus (" + std::string(talus::version())
                 + ") reads versions " + std::to_string(oldestCheckpointFormatVersion) + " to "
                 + std::to_string(checkpointFormatVersion),
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

  readMaterials(r, in, ctx);
  readBodies(r, in, ctx);
  readContacts(r, in, ctx);

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
    if (b.blockedDofs[i] > DofAll || b.dynamic[i] > 1 || b.alive[i] > 1 || b.damped[i] > 1)
      ctx.fail(which + " has invalid flags (blockedDofs, dynamic, alive or damped)", false);
    // Fields no scene can hold (an edited file): named here, not a step later as a
    // non-finite force blamed on the time step.
    if (!b.alive[i])
      continue;
    if (!b.pos[i].allFinite())
      ctx.fail(which + ": position is not finite", false);
    if (b.shape[i] == ShapeKind::Sphere && !(std::isfinite(b.radius[i]) && b.radius[i] > 0))
      ctx.fail(which + ": radius " + std::to_string(b.radius[i]) + " is not positive and finite", false);
    if (!(std::isfinite(b.mass[i]) && b.mass[i] >= 0))
      ctx.fail(which + ": mass " + std::to_string(b.mass[i]) + " is not finite and >= 0", false);
    if (b.dynamic[i] && clump < 0 && (b.blockedDofs[i] & (DofX | DofY | DofZ)) != (DofX | DofY | DofZ)
        && !(b.mass[i] > 0))
      ctx.fail(which + ": mass is 0 but the body is dynamic (a massless body must be non-dynamic or blocked)",
               false);
  }
  for (std::size_t k = 0; k < b.clumps.size(); ++k)
    for (BodyId m : b.clumps[k].members)
      if (m < 0 || static_cast<std::size_t>(m) >= n || b.clumpId[static_cast<std::size_t>(m)] < 0)
        ctx.fail("clump shape " + std::to_string(k) + " lists body " + std::to_string(m)
                     + " which is not one of its members",
                 false);
  validatePlaneShapes(b, ctx);
  for (std::size_t k = 0; k < b.boxes.size(); ++k)
    if (!b.boxes[k].extents.allFinite() || !(b.boxes[k].extents.minCoeff() >= 0))   // a plate: one extent 0
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
} // namespace talus::dem::checkpoint
