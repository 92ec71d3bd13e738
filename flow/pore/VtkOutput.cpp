#include "flow/pore/VtkOutput.h"

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

std::array<std::string, 2> saveVtk(const PoreFlow& flow, const std::string& base, const std::vector<PoreField>& poreFields)
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
  std::vector<std::array<std::size_t, 4>> cells(net.pores.size());
  for (std::size_t c = 0; c < net.pores.size(); ++c)
  {
    const Pore& pore = net.pores[c];
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
        cells[c][k] = static_cast<std::size_t>(pore.vertices[k]) - kBoundaries;
        continue;
      }
      const Boundary& b = net.boundaries[static_cast<std::size_t>(vx.id)];
      Vec3 q = centroid;
      q[b.coordinate] = b.position;
      cells[c][k] = points.size();
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
    out << "CELL_DATA " << cells.size() << "\nSCALARS pressure double 1\nLOOKUP_TABLE default\n";
    for (double x : p)
      out << x << '\n';
    out << "SCALARS volume double 1\nLOOKUP_TABLE default\n";
    for (const Pore& pore : net.pores)
      out << std::abs(pore.volume) << '\n';
    out << "SCALARS voidVolume double 1\nLOOKUP_TABLE default\n";
    for (const Pore& pore : net.pores)
      out << pore.voidVolume << '\n';
    out << "VECTORS velocity double\n";
    for (const Vec3& v : velocity)
      vector(out, v);
    for (const auto& [name, values] : poreFields)
    {
      out << "SCALARS " << name << " double 1\nLOOKUP_TABLE default\n";
      for (double x : values)
        out << x << '\n';
    }
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
