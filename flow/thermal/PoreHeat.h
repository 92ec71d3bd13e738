#pragma once
// Heat in the pore fluid of a FlowEngine network, coupled to the particles' conduction (the fluid
// part of Yade's ThermalEngine; Caulk, Scholtès, Krzaczek & Chareyre 2020, CMAME): one
// temperature per pore, advected by the pore fluxes, exchanged with the spheres that bound the
// pore and conducted through the fluid between neighbouring pores.
#include "flow/pore/PoreFlow.h"
#include "flow/thermal/ParticleConduction.h"

#include <array>
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace talus::flow::thermal
{
/// Fluid properties and options (Yade's names in ThermalEngine and FlowEngine).
struct FluidHeatParameters
{
  double fluidK = 0.58;         ///< conductivity, W/(m K) (ThermalEngine.fluidK)
  double fluidCp = 4181.3;      ///< specific heat, J/(kg K) (FlowEngine.fluidCp)
  double fluidRho = 1000;       ///< density, kg/m^3 (FlowEngine.fluidRho)
  /// Nusselt number times fluidK: h = nusseltK / (2 r) on the sphere surface in each pore
  double nusseltK = 0;
  /// Instead of nusseltK, one per pore from the pore's Reynolds number (Yade's uniformReynolds
  /// = -1), computed at the first step and on each new network (see PoreHeat::poreNusseltK).
  bool poreReynolds = false;
  double porosity = 0.4; ///< porosity of the packing, which selects and enters the correlation
  bool advection = true;        ///< transport by the pore fluxes (ThermalEngine.advection)
  bool fluidConduction = true;  ///< conduction between neighbouring pores (ThermalEngine.fluidConduction)
  bool ignoreFictitious = false; ///< no sphere-fluid exchange in boundary pores (ignoreFictiousConduction)
  double areaFactor = 1;        ///< fluidConductionAreaFactor
  double minimumDistance = 0;   ///< minimumFluidCondDist
  double thermalPorosity = 0;   ///< > 0: heat capacity of thermalPorosity x the void volume (FlowEngine's)
};

/// Explicit heat model of the spheres and the pore fluid. Each step (as Yade's ThermalEngine with
/// advection and fluidConduction):
///
/// 1. the rates of the current temperatures: conduction between spheres (ParticleConduction),
///    upwind advection  rho Cp |Q| (T_up - T)  into the pore downstream of each throat (Q =
///    k (p_i - p_j) from the solved pressures; the conservative  -rho Cp T_up Q  for a
///    divergence-free flux), and the sphere-fluid exchange  h A (T_pore - T_sphere)  over the spherical
///    triangle A = r^2 x solid angle of each sphere in each pore, h = nusseltK / (2 r);
/// 2. spheres and pores advance with them; then fluid conduction between neighbouring inner
///    pores, G = fluidK x fluid area of the throat / distance between the pores' vertex centroids,
///    with those new pore temperatures (Yade's split).
///
/// Pores touching a boundary (fictitious) keep their temperature; those of a temperature boundary
/// hold its value and exchange heat with their spheres. The heat capacity of a pore is
/// rho Cp V_void. The pore temperatures follow the network through remeshes (each new pore takes
/// the temperature of the old pore containing its centroid, else `initialTemperature`).
class PoreHeat : public HeatModel
{
public:
  /// @param particles the spheres' conduction, whose rates the fluid exchange adds to; it must
  ///        outlive this model
  /// @param flow the pore flow whose network and pressures carry the heat (shared ownership)
  PoreHeat(ParticleConduction& particles, std::shared_ptr<const pore::PoreFlow> flow)
      : particles_(particles), flow_(std::move(flow))
  {
  }

  FluidHeatParameters params;
  /// Temperature of pores created without an old pore to take it from (FlowEngine.tZero).
  double initialTemperature = 0;

  /// Hold the pores of boundary k (0..5) at `value` (FlowEngine.bndCondIsTemperature); the held
  /// pores are found again after each remesh.
  /// @param k the boundary, 0..5 (xmin, xmax, ymin, ymax, zmin, zmax)
  /// @param held hold it (false: its pores follow the heat balance again)
  /// @param value its temperature (the user's unit)
  /// @throws std::invalid_argument for k outside 0..5
  void setBoundary(int k, bool held, double value);

  void computeRates() override;
  void applyRates(double dt) override;
  [[nodiscard]] double stableTimeStep() const override;
  [[nodiscard]] std::string limitingPart() const override;

  /// Per pore of the current network (after `sync`).
  [[nodiscard]] const std::vector<double>& temperatures() const { return temperature_; }
  /// Set one pore's temperature (after a sync with the flow's current network).
  /// @param pore the pore's index in the current network
  /// @param value the temperature (the user's unit)
  /// @throws std::out_of_range for an index outside the network; as sync()
  void setTemperature(int pore, double value);
  /// Temperature of the pore containing x (Yade's getPoreTemperature); NaN outside the network.
  /// @param x a point (m)
  /// @return the temperature, or NaN
  /// @throws std::invalid_argument as sync()
  [[nodiscard]] double temperatureAt(const pore::Vec3& x);
  /// Follow the flow's network (the pore list after a remesh) and re-apply the boundaries.
  /// @throws std::invalid_argument if the flow has no network yet, or a periodic one
  void sync();
  /// With params.poreReynolds, Nusselt number times fluidK of each pore (Yade's
  /// setReynoldsNumbers): Re = fluidRho |v| L / viscosity, v the pore's Darcy velocity, L the
  /// distance from its centre to that of its last neighbour touching no boundary (1e-6 m if
  /// none); Nu = 2 + 0.6 Re^0.5 Pr^0.33333 (Ranz-Marshall) if Re > 1000 or the porosity is below
  /// 0.35, else Tavassoli et al.'s (2015) correlation for fixed random arrays,
  /// (7 - 10 phi + 5 phi^2)(1 + 0.1 Re^0.2 Pr^0.333) + (1.33 - 2.19 phi + 1.15 phi^2) Re^0.7 Pr^0.333.
  /// Empty before the first step and without params.poreReynolds.
  [[nodiscard]] const std::vector<double>& poreNusseltK() const { return poreNusseltK_; }
  /// Compute poreNusseltK again at the next step (Yade's setReynoldsNumbers).
  void resetPoreNusselt() { poreNusseltK_.clear(); }
  /// The triangulation the temperatures belong to (null before the first sync).
  [[nodiscard]] const void* mesh() const { return mesh_ ? mesh_->triangulation.get() : nullptr; }

private:
  [[nodiscard]] bool free(std::size_t pore) const;
  [[nodiscard]] double heatCapacity(std::size_t pore) const;
  void computeGeometry();
  void computePoreNusselt();

  ParticleConduction& particles_;
  std::shared_ptr<const pore::PoreFlow> flow_;
  std::optional<pore::PoreNetwork> mesh_; ///< the network the arrays below belong to
  std::vector<double> temperature_, rate_, conductance_;
  std::vector<char> held_;
  std::array<bool, pore::kBoundaries> boundaryHeld_{};
  std::array<double, pore::kBoundaries> boundaryValue_{};
  std::vector<std::array<double, 4>> sphereArea_; ///< spherical triangle of each pore vertex (0: boundary)
  std::vector<double> fluidConductance_;          ///< per throat: fluidK A / L (0 with a boundary pore)
  std::vector<double> poreNusseltK_;              ///< per pore, with params.poreReynolds (empty: due)
  double stableStep_ = 0;
  int limitingPore_ = -1;
};
} // namespace talus::flow::thermal
