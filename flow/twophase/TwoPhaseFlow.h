#pragma once
// Quasi-static two-phase flow on the pore network (Yade's TwoPhaseFlowEngine, the "2PFV" model of
// Yuan & Chareyre 2017): each pore holds one phase, wetting (saturation 1) or non-wetting (0); a
// throat lets the non-wetting phase into a wetting pore when the pressure difference across it
// exceeds the throat's and the pore body's entry pressures, surfaceTension / radius (drainage),
// and the wetting phase back when it falls below both (imbibition). The wetting reservoir is
// boundary 2 (ymin) and the non-wetting one boundary 3 (ymax), as in Yade. With isPhaseTrapped a
// phase cut from its reservoir is trapped at the capillary pressure of the moment it was cut.
#include "flow/pore/PoreNetwork.h"
#include "flow/twophase/EntryRadius.h"
#include "flow/twophase/PhaseCluster.h"

#include <array>
#include <memory>
#include <vector>

namespace talus::flow::twophase
{
using pore::kBoundaries;

/// TwoPhaseFlowEngine's options, Yade's names and defaults.
struct TwoPhaseParameters
{
  double surfaceTension = 0.0728; ///< water-air at 20 °C, N/m
  int entryPressureMethod = 1;    ///< see EntryPressureMethod
  bool isPhaseTrapped = true;     ///< false: both phases always connected to their reservoirs
  bool isInvadeBoundary = true;   ///< false (MS-P): throats between boundary pores closed
  bool drainageFirst = true;      ///< start saturated with the wetting phase (else non-wetting)
  bool isDrainageActivated = true;
  bool isImbibitionActivated = false;
  bool recursiveInvasion = true;  ///< false: one pore deep per invasion()
  bool isCellLabelActivated = false; ///< label the pores by cluster (PhaseCluster) at initialize and invasion
  /// drainage keeps the clusters by invadePoreFast on each pore it drains, in place of labelling
  /// every pore again after each invasion (drainage only)
  bool useFastInvasion = false;
};

/// The state of one pore.
struct PoreState
{
  double saturation = 1;
  double pressure = 0;
  bool imposed = false;  ///< on a pressure boundary (Yade's Pcondition): never invaded
  bool wReservoir = false;
  bool nwReservoir = false;
  bool trappedW = false;
  bool trappedNW = false;
  double trapCapillaryPressure = 0; ///< Pn - Pw when the phase was cut from its reservoir
  bool hasInterface = false; ///< inner side of a cluster interface (set when one is added, cleared when it drains)
};

/// The phases of the pores of one network and their invasion (Yade's TwoPhaseFlowEngine).
class TwoPhaseFlow
{
public:
  /// Entry radii, pore bodies and the initial phases of `net` (geometry computed; Yade's
  /// initialization). bndCondIsPressure[2] and [3] must be set: the reservoirs ([3] optional
  /// with isCellLabelActivated).
  /// @param net the network (its connectivity is copied: it may be rebuilt afterwards)
  /// @param params the options (copied)
  /// @param bndCondIsPressure which of the six boundaries impose a pressure
  /// @param bndCondValue the six boundaries' pressures (Pa)
  /// @throws std::invalid_argument naming the parameter (surfaceTension < 0 or not finite,
  ///         entryPressureMethod, the reservoirs not pressure boundaries, non-finite bndCondValue)
  ///         or for a periodic network
  void initialize(const pore::PoreNetwork& net, const TwoPhaseParameters& params,
                  const std::array<bool, kBoundaries>& bndCondIsPressure,
                  const std::array<double, kBoundaries>& bndCondValue);
  /// One invasion at the boundary values (capillary pressure bndCondValue[3] - bndCondValue[2]):
  /// drainage from the non-wetting reservoir then imbibition from the wetting one, as activated,
  /// then the reservoirs and trapped phases updated (Yade's invasion).
  /// @param bndCondValue the six boundaries' pressures (Pa)
  /// @throws std::logic_error before initialize
  /// @throws std::invalid_argument for a non-finite value, or boundaries 2 and 3 not both
  ///         pressure boundaries
  void invasion(const std::array<double, kBoundaries>& bndCondValue);
  /// Wetting saturation: wetting pore-body volume over pore-body volume, pores on pressure
  /// boundaries left out, boundary pores too unless `sideBoundaryIncluded` (Yade's getSaturation).
  /// @param sideBoundaryIncluded count the pores touching the other boundaries
  /// @return the saturation, in [0, 1]
  [[nodiscard]] double saturation(bool sideBoundaryIncluded) const;
  /// The smallest capillary pressure that drains one more pore (0 when none can; Yade's getMinDrainagePc).
  [[nodiscard]] double minDrainagePc() const;
  /// The largest capillary pressure at which one more pore imbibes (0 when none; getMaxImbibitionPc).
  [[nodiscard]] double maxImbibitionPc() const;

  /// Yade's updatePressure: each pore's pressure from the boundary values and its reservoir and
  /// trapping flags (what invasion() starts with).
  /// @param bndCondValue the six boundaries' pressures (Pa)
  /// @throws std::logic_error before initialize
  /// @throws std::invalid_argument for a non-finite value
  void updatePressure(const std::array<double, kBoundaries>& bndCondValue);
  // Yade's per-pore setters, for set-ups a script makes itself: the state is changed as given
  // (no label or reservoir is recomputed; the next invasion() or updatePressure() reads it).
  /// @param pore a pore index
  /// @param saturation in [0, 1] (setCellSaturation)
  /// @throws std::out_of_range for the pore, std::invalid_argument for the saturation
  void setSaturation(int pore, double saturation);
  /// @param pore a pore index
  /// @param wetting the flag of the wetting reservoir (setCellIsWRes), else the non-wetting one's (setCellIsNWRes)
  /// @param value the flag
  /// @throws std::out_of_range for the pore
  void setReservoir(int pore, bool wetting, bool value);
  /// @param pore a pore index
  /// @param radius its pore-body entry radius, > 0 (setPoreBodyRadius)
  /// @throws std::out_of_range for the pore, std::invalid_argument for the radius
  void setBodyRadius(int pore, double radius);
  /// @param throat a throat index (the network's)
  /// @param radius its entry radius, finite; negative closes it to invasion (setPoreThroatRadius)
  /// @throws std::out_of_range for the throat, std::invalid_argument for the radius
  void setThroatRadius(int throat, double radius);
  /// Yade's setCellHasInterface.
  /// @param pore a pore index
  /// @param value the flag
  /// @throws std::out_of_range for the pore
  void setHasInterface(int pore, bool value);

  /// initialize was called (with a network of at least one pore).
  [[nodiscard]] bool initialized() const { return !pores_.empty(); }
  /// Each pore's phase, pressure and reservoir and trapping flags (index as the network's pores).
  [[nodiscard]] const std::vector<PoreState>& pores() const { return pores_; }
  /// Each throat's entry radius (m; -1: closed to invasion), index as the network's throats.
  [[nodiscard]] const std::vector<double>& throatRadii() const { return throatRadius_; }
  /// Each pore's inscribed-sphere radius (m), its pore-body entry radius.
  [[nodiscard]] const std::vector<double>& bodyRadii() const { return bodyRadius_; }
  /// Each pore's body volume (m^3), the weights of saturation().
  [[nodiscard]] const std::vector<double>& bodyVolumes() const { return bodyVolume_; }
  /// Mean of each pore's four vertices, a wall's being its fictitious sphere's far centre (Yade's
  /// cellBarycenter, which TwoPhaseFlowInjection.py compares with a height).
  [[nodiscard]] const std::vector<pore::Vec3>& barycentres() const { return barycentre_; }
  /// Pore pressures (the phase pressure of each pore).
  [[nodiscard]] std::vector<double> pressures() const;
  /// Force of the phase pressures on each vertex of the network (0..5 the walls, then the
  /// spheres; Yade's computeCapillaryForce, see CapillaryForce.h).
  [[nodiscard]] std::vector<pore::Vec3> capillaryForces() const;
  /// The current options.
  [[nodiscard]] const TwoPhaseParameters& parameters() const { return params_; }
  /// Change the options between invasions (surfaceTension scales the entry pressures; the
  /// entry-pressure method and isInvadeBoundary act at initialize only, as in Yade).
  /// @param params the new options (copied)
  /// @throws std::invalid_argument as initialize
  void setParameters(const TwoPhaseParameters& params);

  // --- clusters of pores (Yade's cell labels and PhaseCluster; PhaseClusters.cpp) ---
  /// Label every pore by cluster: 0 the non-wetting pores, 1 the wetting reservoir, new clusters
  /// for the other wetting pores, with their interfaces (Yade's updateCellLabel).
  void updateCellLabels();
  /// Each pore's cluster label (Yade's getCellLabel), from the last updateCellLabels.
  [[nodiscard]] const std::vector<int>& labels() const { return label_; }
  /// The clusters, index = label.
  [[nodiscard]] const std::vector<PhaseCluster>& clusters() const { return clusters_; }
  /// The interface `index` of cluster `cluster` (the second form writable: a script sets its
  /// volume or capillary pressure).
  /// @param cluster a label, 0 .. clusters().size() - 1
  /// @param index an index into that cluster's interfaces
  /// @return the interface, stored here (valid until the labels change)
  /// @throws std::out_of_range naming the cluster or the index
  [[nodiscard]] const Interface& interface(int cluster, int index) const;
  [[nodiscard]] Interface& interface(int cluster, int index);
  /// Wetting pore `cellId` drains, its cluster kept in place (Yade's clusterInvadePoreFast): its
  /// interfaces go, its neighbours in the cluster get interfaces onto it (added at the end, volume
  /// 0; the others keep theirs), and the cluster is split only if those neighbours are no longer
  /// joined: not if there is one, or if they meet around the edges they share with the pore (two:
  /// around theirs; three: around two of their three); otherwise the pores it no longer reaches
  /// from its first pore (from its last imposed pore for the wetting reservoir) form new
  /// clusters. The cluster's volume, interfacial area and entry radius are not updated (as Yade).
  /// A pore on a pressure boundary is left as it is.
  /// @param cellId a pore of a wetting cluster
  /// @return the cluster's label (and the new clusters' labels, in Yade's order); empty if the
  ///         pore was its cluster's last
  /// @throws std::out_of_range, std::invalid_argument as invadePore
  std::vector<int> invadePoreFast(int cellId);
  /// Pore `imbibedId` (non-wetting) joins the cluster of pore `startingId`, merging the clusters
  /// it touches; returns the labels of the cluster and of those merged into it (Yade's
  /// clusterOutvadePore).
  /// @param startingId a pore of a wetting cluster
  /// @param imbibedId a non-wetting pore
  /// @return the cluster's label first, then the labels merged into it
  /// @throws std::out_of_range for a pore index outside the network
  /// @throws std::invalid_argument if startingId is not in a wetting cluster (isCellLabelActivated
  ///         not set) or imbibedId is not non-wetting
  std::vector<int> outvadePore(int startingId, int imbibedId);
  /// Wetting pore `cellId` drains: it joins the non-wetting pores (label 0) and its cluster is
  /// labelled again from its neighbours, in their order: the first keeps the cluster's label,
  /// each other neighbour it no longer reaches starts a new cluster (Yade's clusterInvadePore).
  /// The clusters rebuilt get their interfaces anew (volume and capillary pressure 0).
  /// @param cellId a pore of a wetting cluster
  /// @return the cluster's label then the new clusters' labels; empty if the pore was its
  ///         cluster's last (the cluster stays, empty)
  /// @throws std::out_of_range for a pore index outside the network
  /// @throws std::invalid_argument if cellId is not in a wetting cluster
  std::vector<int> invadePore(int cellId);
  /// Pressures of the pores of cluster `cluster` (those not on a pressure boundary): Darcy flow
  /// in the cluster, the non-wetting and imposed pores' pressures plus the interfaces' capillary
  /// pressures as conditions (PhaseCluster.solvePressure).
  /// @param cluster a label
  /// @throws std::out_of_range for an unknown label
  /// @throws std::invalid_argument for a cluster without pores
  /// @throws std::runtime_error if the cluster's pressure matrix cannot be factorised
  void solveClusterPressure(int cluster);
  /// Conductance of the throat of an interface, and the flux through it from the cluster,
  /// conductance (p_inner + capillaryPressure - p_outer).
  /// @param cluster, index as interface()'s
  /// @return the conductance (m^3/(Pa s))
  /// @throws std::out_of_range as interface()
  [[nodiscard]] double interfaceConductance(int cluster, int index) const;
  /// @param cluster, index as interface()'s
  /// @return the flux (m^3/s), positive out of the cluster
  /// @throws std::out_of_range as interface()
  [[nodiscard]] double interfaceFlux(int cluster, int index) const;
  /// Every interface of the cluster: volume += dt * flux (PhaseCluster.updateCapVolList).
  /// @param cluster a label
  /// @param dt the time step (s)
  /// @throws std::out_of_range for an unknown label
  void updateInterfaceVolumes(int cluster, double dt);
  /// Yade's getBoundaryFlux on the phase pressures: the flux the pores of boundary k receive
  /// from their neighbours, negative where fluid enters.
  /// @param k the boundary, 0..5
  /// @return the flux (m^3/s)
  /// @throws std::out_of_range for k outside 0..5
  [[nodiscard]] double boundaryFlux(int k) const;
  /// Yade's getCellFluxFromId on the phase pressures: the flux pore `pore` sends to its
  /// neighbours, sum of conductance (p_pore - p_neighbour); negative where fluid enters it.
  /// @param pore a pore index
  /// @return the flux (m^3/s)
  /// @throws std::out_of_range for the pore
  [[nodiscard]] double poreFlux(int pore) const;

private:
  /// The state of pore `pore`, its index checked (`function` names the caller in the message).
  PoreState& checkedPore(int pore, const char* function);
  /// Spread the phase of pore `start` to its neighbours as the entry pressures allow.
  void invadeFrom(int start);
  /// Reservoir flags from connectivity to boundaries 2 and 3 (isPhaseTrapped) or from the
  /// pressures (not trapped), then the newly trapped phases at capillary pressure pc.
  void updateReservoirs(double pc);
  /// Pressures from the reservoir and trapped flags.
  void applyPressures();
  /// The pores a reservoir's phase reaches from the pores of boundary k through pores of
  /// saturation `phase` (not imposed), flagged as that reservoir.
  void floodReservoir(int k, double phase);

  // the network's connectivity, copied: the network may be rebuilt after initialize
  std::vector<std::array<int, 4>> neighbours_; ///< pore across each facet, -1: none
  std::vector<std::array<int, 4>> throats_;    ///< throat across each facet, -1: none
  std::vector<char> boundaryPore_;             ///< has a boundary vertex (Yade's isFictious)
  std::array<std::vector<int>, kBoundaries> boundaryPores_;
  std::vector<std::array<int, 4>> poreVertices_;
  std::size_t nVertices_ = 0;
  std::vector<std::array<pore::Vec3, 4>> unitForces_; ///< force on each pore vertex per unit pressure
  TwoPhaseParameters params_;
  std::array<double, kBoundaries> bnd_{};
  std::array<bool, kBoundaries> isPressure_{};
  std::vector<PoreState> pores_;
  std::vector<double> throatRadius_;
  std::vector<double> bodyRadius_;
  std::vector<double> bodyVolume_;
  std::vector<pore::Vec3> barycentre_;
  std::vector<double> conductance_; ///< per throat, as the network had it at initialize (Yade's kNorm)
  std::vector<double> fluidArea_;   ///< per throat
  std::vector<int> label_;          ///< cluster of each pore, -1: none
  std::vector<PhaseCluster> clusters_;
  struct ClusterSystem;             ///< the factorised pressure system of a cluster (PhaseClusters.cpp)
  std::vector<std::shared_ptr<ClusterSystem>> systems_; ///< per cluster; null: to factorise again

  /// Yade's clusterGetPore / clusterGetFacet / updateSingleCellLabelRecursion.
  void addPore(int cluster, int pore);
  void addInterface(int cluster, int pore, int facet);
  void labelFrom(int cluster, int pore);
  /// The label of wetting pore `cellId`, its index and cluster checked (`function` names the caller).
  [[nodiscard]] int wettingLabel(int cellId, const char* function) const;
  /// Whether the cells around the edge pore `cell` shares with its facets `f1` and `f2` (its two
  /// vertices other than f1 and f2) are all pores of cluster `label` (Yade's connectedAroundEdge;
  /// Yade's looks around another edge for the facet pairs (3, 0) and (3, 1), and can then keep
  /// whole a cluster the pore has cut).
  [[nodiscard]] bool connectedAroundEdge(int cell, int f1, int f2, int label) const;
  /// Yade's splitCluster: the pores of cluster `label` no longer reached from pore `start` move
  /// to a new cluster, split again the same way; returns the labels.
  std::vector<int> splitCluster(int label, int start);
  [[nodiscard]] const PhaseCluster& checkedCluster(int cluster) const;
  [[nodiscard]] double conductanceOf(const Interface& i) const;
};
} // namespace talus::flow::twophase
