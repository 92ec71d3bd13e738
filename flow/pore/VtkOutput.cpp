#include "flow/pore/VtkOutput.h"

#include <algorithm>
#include <fstream>
#include <iomanip>
#include <stdexcept>

namespace talus::flow::pore
{
namespace
{
std::ofstream open(const std::string& path)
{
  std::ofstream out(path);
  if (!out)
    throw std::runtime_error("saveVtk: cannot write " + path);
  out << std::setprecision(12);
  return out;
}

void vector(std::ostream& out, const Vec3& v) { out << v[0] << ' ' << v[1] << ' ' << v[2] << '\n'; }
} // namespace

std::array<std::string, 2> saveVtk(const PoreFlow& flow, const std::string& base, const std::vector<PoreField>& poreFields,
                                   bool withBoundaries)
{
  const PoreNetwork& net = flow.network();
  const std::vector<double>& p = flow.pressures();
  const std::array<std::string, 2> paths{base + ".pores.vtk", base + ".throats.vtk"};
  for (const auto& [name, values] : poreFields)
    if (values.size() != net.pores.size())
      throw std::invalid_argument("saveVtk: the pore field " + name + " has " + std::to_string(values.size()) +
                                  " values for " + std::to_string(net.pores.size()) + " pores");

  // Points: the spheres (vertex 6+i is point i), then one point per wall vertex of a boundary
  // pore, at the projection of the pore's spheres' centroid on the wall.
  std::vector<Vec3> points;
  for (std::size_t v = kBoundaries; v < net.vertices.size(); ++v)
    points.push_back(net.vertices[v].pos);
  // the pores drawn: all, or those with four spheres
  std::vector<std::size_t> drawn;
  for (std::size_t c = 0; c < net.pores.size(); ++c)
    if (withBoundaries || std::none_of(net.pores[c].vertices.begin(), net.pores[c].vertices.end(), [&](int v) {
          return net.vertices[static_cast<std::size_t>(v)].fictitious;
        }))
      drawn.push_back(c);
  std::vector<std::array<std::size_t, 4>> cells(drawn.size());
  for (std::size_t d = 0; d < drawn.size(); ++d)
  {
    const Pore& pore = net.pores[drawn[d]];
    Vec3 centroid = Vec3::Zero();
    int real = 0;
    for (int v : pore.vertices)
      if (!net.vertices[static_cast<std::size_t>(v)].fictitious)
      {
        centroid += net.vertices[static_cast<std::size_t>(v)].pos;
        ++real;
      }
    if (real > 0) // a pore of four walls (none in practice) is drawn at the box corner
      centroid /= real;
    for (int k = 0; k < 4; ++k)
    {
      const Vertex& vx = net.vertices[static_cast<std::size_t>(pore.vertices[k])];
      if (!vx.fictitious)
      {
        cells[d][k] = static_cast<std::size_t>(pore.vertices[k]) - kBoundaries;
        continue;
      }
      const Boundary& b = net.boundaries[static_cast<std::size_t>(vx.id)];
      Vec3 q = centroid;
      q[b.coordinate] = b.position;
      cells[d][k] = points.size();
      points.push_back(q);
    }
  }
  const std::vector<Vec3> forces = flow.vertexForces();
  const std::vector<Vec3> velocity = flow.poreVelocities();
  {
    std::ofstream out = open(paths[0]);
    out << "# vtk DataFile Version 3.0\nTalus pore network: pores\nASCII\nDATASET UNSTRUCTURED_GRID\n";
    out << "POINTS " << points.size() << " double\n";
    for (const Vec3& x : points)
      vector(out, x);
    out << "CELLS " << cells.size() << ' ' << 5 * cells.size() << '\n';
    for (const auto& c : cells)
      out << "4 " << c[0] << ' ' << c[1] << ' ' << c[2] << ' ' << c[3] << '\n';
    out << "CELL_TYPES " << cells.size() << '\n';
    for (std::size_t c = 0; c < cells.size(); ++c)
      out << "10\n"; // VTK_TETRA
    out << "CELL_DATA " << cells.size() << '\n';
    const auto column = [&](const std::string& name, auto value) {
      out << "SCALARS " << name << " double 1\nLOOKUP_TABLE default\n";
      for (std::size_t c : drawn)
        out << value(c) << '\n';
    };
    column("pressure", [&](std::size_t c) { return p[c]; });
    column("volume", [&](std::size_t c) { return std::abs(net.pores[c].volume); });
    column("voidVolume", [&](std::size_t c) { return net.pores[c].voidVolume; });
    out << "VECTORS velocity double\n";
    for (std::size_t c : drawn)
      vector(out, velocity[c]);
    for (const auto& [name, values] : poreFields)
      column(name, [&](std::size_t c) { return values[c]; });
    out << "POINT_DATA " << points.size() << "\nSCALARS radius double 1\nLOOKUP_TABLE default\n";
    for (std::size_t i = 0; i < points.size(); ++i)
      out << (i < net.sphereCount() ? net.vertices[kBoundaries + i].radius : 0.0) << '\n';
    out << "VECTORS fluidForce double\n";
    for (std::size_t i = 0; i < points.size(); ++i)
      vector(out, i < net.sphereCount() ? forces[kBoundaries + i] : Vec3::Zero());
    if (!out)
      throw std::runtime_error("saveVtk: writing " + paths[0] + " failed");
  }
  {
    std::ofstream out = open(paths[1]);
    out << "# vtk DataFile Version 3.0\nTalus pore network: throats\nASCII\nDATASET POLYDATA\n";
    out << "POINTS " << net.pores.size() << " double\n";
    for (const Pore& pore : net.pores)
      vector(out, pore.centre);
    out << "LINES " << net.throats.size() << ' ' << 3 * net.throats.size() << '\n';
    for (const Throat& t : net.throats)
      out << "2 " << t.pores[0] << ' ' << t.pores[1] << '\n';
    out << "CELL_DATA " << net.throats.size() << "\nSCALARS flux double 1\nLOOKUP_TABLE default\n";
    for (const Throat& t : net.throats)
      out << t.conductance * (p[static_cast<std::size_t>(t.pores[0])] - p[static_cast<std::size_t>(t.pores[1])]) << '\n';
    const auto column = [&](const char* name, auto f) {
      out << "SCALARS " << name << " double 1\nLOOKUP_TABLE default\n";
      for (const Throat& t : net.throats)
        out << f(t) << '\n';
    };
    column("conductance", [](const Throat& t) { return t.conductance; });
    column("fluidArea", [](const Throat& t) { return t.fluidArea; });
    column("hydraulicRadius", [](const Throat& t) { return t.hydraulicRadius; });
    if (!out)
      throw std::runtime_error("saveVtk: writing " + paths[1] + " failed");
  }
  return paths;
}
} // namespace talus::flow::pore
