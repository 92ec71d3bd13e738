#pragma once
// A cluster of pores of one phase (Yade's PhaseCluster, used with isCellLabelActivated): label 0
// gathers the non-wetting pores, 1 the wetting pores of the reservoir (boundary 2, ymin) and those
// joined to it since, 2, 3... the other wetting clusters. A wetting cluster's interfaces are the
// throats from one of its pores to a non-wetting one; each carries a meniscus that a dynamic
// injection moves (its volume) and a capillary pressure jump across it. The pressures of a
// cluster's pores follow from Darcy flow inside it with the pressures of the non-wetting pores,
// plus the jumps, as conditions on its interfaces (TwoPhaseFlow::solveClusterPressure).
#include <vector>

namespace talus::flow::twophase
{
/// A throat from a pore of the cluster (inner) to a non-wetting pore (outer).
struct Interface
{
  int inner = -1;
  int outer = -1;
  double area = 0;              ///< fluid area of the throat
  int facet = 0;                ///< the facet of `inner` the throat is (0..3)
  double volume = 0;            ///< fluid volume that crossed it (Yade's capillary volume)
  double capillaryPressure = 0; ///< pressure jump from inner to outer side
};

/// One cluster: its pores, its interfaces and what Yade's PhaseCluster reports of them.
struct PhaseCluster
{
  int label = -1;
  double volume = 0;          ///< pore-body volume of its pores
  double entryRadius = 0;     ///< largest entry radius of its interfaces
  int entryPore = -1;         ///< the inner pore of that interface
  double interfacialArea = 0; ///< fluid area of every interface added (removed ones not subtracted, as Yade)
  std::vector<int> pores;
  std::vector<Interface> interfaces;
};
} // namespace talus::flow::twophase
