#pragma once
// ParaView output of a solved pore network (legacy VTK, ASCII; ParaView and VisIt open it):
//   <base>.pores.vtk    UNSTRUCTURED_GRID, one tetrahedron per pore; cell data: pressure,
//                       volume, voidVolume, velocity (the pore's Darcy velocity), and the
//                       caller's per-pore fields (the pore temperatures of a ThermalEngine);
//                       boundary pores' wall vertices drawn at the projection of their spheres
//                       on the wall;
//                       point data: radius, fluidForce (zero on those wall points);
//   <base>.throats.vtk  POLYDATA, one line per throat between the two pore centres; cell data:
//                       flux (from pores[0] to pores[1]), conductance, fluidArea, hydraulicRadius.
#include "flow/pore/PoreFlow.h"

#include <string>
#include <utility>
#include <vector>

namespace talus::flow::pore
{
/// A per-pore field written with the pores: its name and one value per pore.
using PoreField = std::pair<std::string, std::vector<double>>;

/// Write both files.
/// @param flow the solved pore flow
/// @param base the files' path without the ending
/// @param poreFields more cell data of the pores' file
/// @param withBoundaries false: the pores' file leaves out the pores with a wall vertex (Yade's
/// saveVtk withBoundaries; the throats' file keeps all pores)
/// @return the two paths
/// @throws std::runtime_error if a file cannot be written
/// @throws std::invalid_argument if a field has not one value per pore
std::array<std::string, 2> saveVtk(const PoreFlow& flow, const std::string& base,
                                   const std::vector<PoreField>& poreFields = {}, bool withBoundaries = true);
} // namespace talus::flow::pore
