// Python bindings of dem/'s I/O: checkpoints (HDF5) and the array copies that the ParaView
// export reads. Compiled into talus._dem; `talus_wrap_io(m)` is called from dem_wrappers.cpp.
// The Python API (defaults, docstrings, engine lists) is talus.dem.files.io and talus.dem.files.export.
#include "dem/checkpoint/Checkpoint.h"
#include "dem/contact/ContactGeometry.h"
#include "dem/core/Scene.h"

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <array>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

namespace py = pybind11;
using namespace talus::dem;

namespace
{
/// (n, 3) array copied from a list of per-item vectors.
template <class Get>
py::array_t<double> rows3(std::size_t n, Get get)
{
  py::array_t<double> out({static_cast<py::ssize_t>(n), py::ssize_t{3}});
  auto a = out.mutable_unchecked<2>();
  for (std::size_t k = 0; k < n; ++k)
  {
    const Vec3 v = get(k);
    for (py::ssize_t d = 0; d < 3; ++d)
      a(static_cast<py::ssize_t>(k), d) = v[static_cast<int>(d)];
  }
  return out;
}

/// 1-D array copied from per-item values.
template <class T, class Get>
py::array_t<T> column(std::size_t n, Get get)
{
  py::array_t<T> out(static_cast<py::ssize_t>(n));
  auto a = out.template mutable_unchecked<1>();
  for (std::size_t k = 0; k < n; ++k)
    a(static_cast<py::ssize_t>(k)) = get(k);
  return out;
}

/// Every contact (or only the real ones) as named arrays, in list order.
py::dict contactArrays(const Scene& scene, bool realOnly)
{
  std::vector<const Contact*> list;
  for (const Contact& c : scene.contacts.list)
    if (c.real || !realOnly)
      list.push_back(&c);
  const std::size_t n = list.size();
  py::dict d;
  d["id1"] = column<std::int32_t>(n, [&](std::size_t k) { return list[k]->id1; });
  d["id2"] = column<std::int32_t>(n, [&](std::size_t k) { return list[k]->id2; });
  d["kind"] = column<std::uint8_t>(n, [&](std::size_t k) { return static_cast<std::uint8_t>(list[k]->kind); });
  d["real"] = column<std::uint8_t>(n, [&](std::size_t k) { return static_cast<std::uint8_t>(list[k]->real); });
  // Where body 2's periodic image is, with the cell as it is now (zero without periodicity).
  d["shift2"] = rows3(n, [&](std::size_t k) { return scene.periodic ? scene.cell.shift(list[k]->cellDist) : Vec3::Zero(); });
  d["normal"] = rows3(n, [&](std::size_t k) { return list[k]->normal; });
  d["contactPoint"] = rows3(n, [&](std::size_t k) { return list[k]->contactPoint; });
  d["penetration"] = column<double>(n, [&](std::size_t k) { return list[k]->penetration; });
  d["kn"] = column<double>(n, [&](std::size_t k) { return list[k]->kn; });
  d["ks"] = column<double>(n, [&](std::size_t k) { return list[k]->ks; });
  d["normalForce"] = rows3(n, [&](std::size_t k) { return list[k]->normalForce; });
  d["shearForce"] = rows3(n, [&](std::size_t k) { return list[k]->shearForce; });
  d["force"] = rows3(n, [&](std::size_t k) { return list[k]->force; });
  return d;
}

/// Live facets: ids, world vertices (n, 3, 3), world unit normals, materials.
py::dict facetArrays(const Scene& scene)
{
  const Bodies& b = scene.bodies;
  std::vector<std::size_t> ids;
  for (std::size_t i = 0; i < b.size(); ++i)
    if (b.alive[i] && b.shape[i] == ShapeKind::Facet)
      ids.push_back(i);
  const std::size_t n = ids.size();
  py::array_t<double> vertices({static_cast<py::ssize_t>(n), py::ssize_t{3}, py::ssize_t{3}});
  auto v = vertices.mutable_unchecked<3>();
  for (std::size_t k = 0; k < n; ++k)
  {
    const std::array<Vec3, 3> world = facetVertices(b, ids[k]);
    for (py::ssize_t j = 0; j < 3; ++j)
      for (py::ssize_t d = 0; d < 3; ++d)
        v(static_cast<py::ssize_t>(k), j, d) = world[static_cast<std::size_t>(j)][static_cast<int>(d)];
  }
  py::dict d;
  d["id"] = column<std::int32_t>(n, [&](std::size_t k) { return static_cast<std::int32_t>(ids[k]); });
  d["vertices"] = vertices;
  d["normal"] = rows3(n, [&](std::size_t k) {
    return Vec3(b.ori[ids[k]] * b.facets[static_cast<std::size_t>(b.shapeIndex[ids[k]])].normal);
  });
  d["material"] = column<std::int32_t>(n, [&](std::size_t k) { return b.material[ids[k]]; });
  return d;
}

/// Live walls: ids, axis, sense, position along the axis, materials.
py::dict wallArrays(const Scene& scene)
{
  const Bodies& b = scene.bodies;
  std::vector<std::size_t> ids;
  for (std::size_t i = 0; i < b.size(); ++i)
    if (b.alive[i] && b.shape[i] == ShapeKind::Wall)
      ids.push_back(i);
  const std::size_t n = ids.size();
  auto shape = [&](std::size_t k) -> const WallShape& { return b.walls[static_cast<std::size_t>(b.shapeIndex[ids[k]])]; };
  py::dict d;
  d["id"] = column<std::int32_t>(n, [&](std::size_t k) { return static_cast<std::int32_t>(ids[k]); });
  d["axis"] = column<std::int32_t>(n, [&](std::size_t k) { return shape(k).axis; });
  d["sense"] = column<std::int32_t>(n, [&](std::size_t k) { return shape(k).sense; });
  d["position"] = column<double>(n, [&](std::size_t k) { return b.pos[ids[k]][shape(k).axis]; });
  d["material"] = column<std::int32_t>(n, [&](std::size_t k) { return b.material[ids[k]]; });
  return d;
}
} // namespace

/// Add the I/O functions to the compiled module talus._dem.
void talus_wrap_io(py::module_& m);

void talus_wrap_io(py::module_& m)
{
  m.def("checkpoints_available", [] { return haveCheckpoints; });
  m.def("checkpoint_format_version", [] { return checkpointFormatVersion; });
  m.def("shape_codes", [](const Scene& s) {
    return column<std::uint8_t>(s.bodies.size(), [&](std::size_t i) { return static_cast<std::uint8_t>(s.bodies.shape[i]); });
  });
  // The ids of the live bodies of one shape (Yade's class name), ascending: the one place the
  // Python layer picks bodies by shape (couplings take the spheres, the exporters each shape).
  m.def("live_ids", [](const Scene& s, const std::string& shape) {
    const std::optional<ShapeKind> kind = shapeKindNamed(shape);
    if (!kind)
      throw py::value_error("live_ids: unknown shape '" + shape + "'");
    std::vector<std::int64_t> ids;
    for (std::size_t i = 0; i < s.bodies.size(); ++i)
      if (s.bodies.shape[i] == *kind && s.bodies.alive[i])
        ids.push_back(static_cast<std::int64_t>(i));
    return py::array_t<std::int64_t>(static_cast<py::ssize_t>(ids.size()), ids.data());
  });
  m.def("contact_arrays", &contactArrays);
  m.def("facet_arrays", &facetArrays);
  m.def("wall_arrays", &wallArrays);
  // Sizes of the structures every field of which a checkpoint stores: a test compares them with
  // the sizes Checkpoint.cpp was written for, so a new field cannot be left out silently.
  m.def("layout_sizes", [] {
    py::dict d;
    d["Contact"] = sizeof(Contact);
    d["Material"] = sizeof(Material);
    d["Bodies"] = sizeof(Bodies);
    d["WallShape"] = sizeof(WallShape);
    d["FacetShape"] = sizeof(FacetShape);
    d["Cell"] = sizeof(Cell);
    d["Scene"] = sizeof(Scene);
    d["ContactExtra"] = sizeof(ContactExtra);
    d["EnergyTracker"] = sizeof(EnergyTracker);
    return d;
  });

#ifdef TALUS_HAVE_HDF5
  py::register_exception<CheckpointError>(m, "CheckpointError", PyExc_RuntimeError);
  m.def("save_checkpoint", &saveCheckpoint, py::call_guard<py::gil_scoped_release>());
  m.def("load_checkpoint", &loadCheckpoint, py::call_guard<py::gil_scoped_release>());
  m.def("save_checkpoint_image", [](const Scene& s, const CheckpointExtras& extras) {
    std::vector<std::uint8_t> image;
    {
      py::gil_scoped_release release;
      image = saveCheckpointImage(s, extras);
    }
    return py::bytes(reinterpret_cast<const char*>(image.data()), image.size());
  });
  m.def("load_checkpoint_image", [](Scene& s, const py::bytes& image, const std::string& name) {
    const std::string_view view = image;
    const std::vector<std::uint8_t> bytes(view.begin(), view.end());
    py::gil_scoped_release release;
    return loadCheckpointImage(s, bytes, name);
  });
#endif
}
