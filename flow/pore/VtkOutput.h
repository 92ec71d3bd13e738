#pragma once
// ParaView output of a solved pore network (legacy VTK, ASCII; ParaView and VisIt open it):
//   <base>.pores.vtk    UNSTRUCTURED_GRID, one tetrahedron per pore; cell data: pressure,
//                       volume, voidVolume, velocity (the pore's Darcy velocity), boundary pores'
//                       wall vertices drawn at the projection of their spheres on the wall;
//                       point data: radius, fluidForce (zero on those wall points);
//   <base>.throats.vtk  POLYDATA, one line per throat between the two pore centres; cell data:
//                       flux (from pores[0] to pores[1]), conductance, fluidArea, hydraulicRadius.
#include "flow/pore/PoreFlow.h"

#include <string>

namespace talus::flow::pore
{
/// Write both files.
/// @param flow the solved pore flow
/// @param base the files' path without the ending
/// @return the two paths
/// @throws std::runtime_error if a file cannot be written
std::array<std::string, 2> saveVtk(const PoreFlow& flow, const std::string& base);
} // namespace talus::flow::pore
