// The clusters of TwoPhaseFlow (Yade's cell labels and PhaseCluster): labelling, a non-wetting
// pore joining a wetting cluster (clusterOutvadePore), the pressure of a cluster and the fluxes
// through its interfaces. The order of pores and interfaces in a cluster is Yade's (pores in
// labelling order, interfaces appended as found and erased in place), since scripts address
// interfaces by their rank.
#include "flow/twophase/TwoPhaseFlow.h"

#include <Eigen/Dense>
#include <Eigen/SparseCholesky>
#include <Eigen/SparseCore>

#include <algorithm>
#include <stdexcept>
#include <string>
#include <utility>

namespace talus::flow::twophase
{
namespace
{
constexpr int kNonWettingLabel = 0;
constexpr int kReservoirLabel = 1;
} // namespace

/// A cluster's pressure matrix, factorised, and the pores joined since. A pore joining the
/// cluster borders the matrix with one row and column and leaves the rest as it was (a row's
/// diagonal sums all its throats, members or not), so the factor of the matrix the cluster had is
/// kept and the joined pores are solved through the Schur complement of the bordered system:
/// one solve with the kept factor per joined pore, once, instead of a new factorisation (of its
/// ordering too) after every pore. The kept block is checked to be the current matrix's, exactly;
/// after kMaxBorder joined pores, or any other change, the whole matrix is factorised again.
struct TwoPhaseFlow::ClusterSystem
{
  static constexpr Eigen::Index kMaxBorder = 64;
  Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> factor;
  Eigen::SparseMatrix<double> matrix; ///< the matrix of the last solve (factorised block first)
  std::vector<int> unknowns;          ///< its pores, in its row order
  Eigen::Index factorised = 0;        ///< rows of the factorised block
  Eigen::MatrixXd coupling;           ///< factor^-1 times the columns of the joined pores (their rows cut)

  /// Whether `a` over `pores` is this system's matrix bordered by rows and columns of further pores.
  bool borders(const Eigen::SparseMatrix<double>& a, const std::vector<int>& pores) const
  {
    const Eigen::Index kept = matrix.rows();
    if (pores.size() < unknowns.size() || a.rows() - factorised > kMaxBorder
        || !std::equal(unknowns.begin(), unknowns.end(), pores.begin()))
      return false;
    const Eigen::SparseMatrix<double> block = a.topLeftCorner(kept, kept);
    if (block.nonZeros() != matrix.nonZeros())
      return false;
    return std::equal(block.valuePtr(), block.valuePtr() + block.nonZeros(), matrix.valuePtr())
           && std::equal(block.innerIndexPtr(), block.innerIndexPtr() + block.nonZeros(), matrix.innerIndexPtr())
           && std::equal(block.outerIndexPtr(), block.outerIndexPtr() + kept + 1, matrix.outerIndexPtr());
  }

  void factorise(Eigen::SparseMatrix<double> a, std::vector<int> pores, int cluster)
  {
    factor.compute(a);
    if (factor.info() != Eigen::Success)
      throw std::runtime_error("PhaseCluster.solvePressure: the pressure matrix of cluster " + std::to_string(cluster)
                               + " could not be factorised (a cluster without any pressure condition?)");
    factorised = a.rows();
    coupling.resize(factorised, 0);
    matrix = std::move(a);
    unknowns = std::move(pores);
  }

  /// The solution of `a` x = rhs, `a` being the factorised block bordered (borders() true).
  Eigen::VectorXd solve(const Eigen::SparseMatrix<double>& a, const Eigen::VectorXd& rhs)
  {
    const Eigen::Index n = factorised;
    const Eigen::Index border = a.rows() - n;
    const Eigen::Index known = coupling.cols();
    const Eigen::SparseMatrix<double> b = a.block(0, n, n, border); // the joined pores' columns, block rows
    coupling.conservativeResize(n, border);
    for (Eigen::Index j = known; j < border; ++j)
      coupling.col(j) = factor.solve(Eigen::VectorXd(b.col(j)));
    const Eigen::MatrixXd schur =
        Eigen::MatrixXd(Eigen::SparseMatrix<double>(a.bottomRightCorner(border, border))) - b.transpose() * coupling;
    const Eigen::VectorXd y = factor.solve(rhs.head(n));
    const Eigen::VectorXd tail = schur.ldlt().solve(rhs.tail(border) - b.transpose() * y);
    Eigen::VectorXd x(a.rows());
    x.head(n) = y - coupling * tail;
    x.tail(border) = tail;
    return x;
  }
};

const PhaseCluster& TwoPhaseFlow::checkedCluster(int cluster) const
{
  if (cluster < 0 || static_cast<std::size_t>(cluster) >= clusters_.size())
    throw std::out_of_range("TwoPhaseFlowEngine: cluster index " + std::to_string(cluster) + " out of range (0.."
                            + std::to_string(static_cast<int>(clusters_.size()) - 1) + ")");
  return clusters_[static_cast<std::size_t>(cluster)];
}

const Interface& TwoPhaseFlow::interface(int cluster, int index) const
{
  const std::vector<Interface>& list = checkedCluster(cluster).interfaces;
  if (index < 0 || static_cast<std::size_t>(index) >= list.size())
    throw std::out_of_range("PhaseCluster: interface index " + std::to_string(index) + " out of range (cluster "
                            + std::to_string(cluster) + " has " + std::to_string(list.size()) + " interfaces)");
  return list[static_cast<std::size_t>(index)];
}

Interface& TwoPhaseFlow::interface(int cluster, int index)
{
  return const_cast<Interface&>(std::as_const(*this).interface(cluster, index));
}

double TwoPhaseFlow::conductanceOf(const Interface& i) const
{
  return conductance_[static_cast<std::size_t>(throats_[static_cast<std::size_t>(i.inner)][static_cast<std::size_t>(i.facet)])];
}

void TwoPhaseFlow::addPore(int cluster, int pore)
{
  PhaseCluster& k = clusters_[static_cast<std::size_t>(cluster)];
  PoreState& s = pores_[static_cast<std::size_t>(pore)];
  label_[static_cast<std::size_t>(pore)] = k.label;
  // every cluster but the non-wetting one is wetting, as Yade flags it
  s.saturation = k.label == kNonWettingLabel ? 0 : 1;
  s.nwReservoir = k.label == kNonWettingLabel;
  s.wReservoir = k.label != kNonWettingLabel;
  k.volume += bodyVolume_[static_cast<std::size_t>(pore)];
  k.pores.push_back(pore);
}

void TwoPhaseFlow::addInterface(int cluster, int pore, int facet)
{
  PhaseCluster& k = clusters_[static_cast<std::size_t>(cluster)];
  const auto c = static_cast<std::size_t>(pore);
  const auto f = static_cast<std::size_t>(facet);
  const auto t = static_cast<std::size_t>(throats_[c][f]);
  k.interfaces.push_back({pore, neighbours_[c][f], fluidArea_[t], facet, 0, 0});
  pores_[c].hasInterface = true;
  k.interfacialArea += fluidArea_[t];
  if (k.entryRadius < throatRadius_[t])
  {
    k.entryRadius = throatRadius_[t];
    k.entryPore = pore;
  }
}

void TwoPhaseFlow::labelFrom(int cluster, int pore)
{
  // depth first as Yade's recursion (the order of the pores and interfaces is its): each frame
  // is a pore and the next facet to look across
  std::vector<std::pair<int, int>> stack{{pore, 0}};
  addPore(cluster, pore);
  while (!stack.empty())
  {
    auto& [c, f] = stack.back();
    if (f == 4)
    {
      stack.pop_back();
      continue;
    }
    const auto cu = static_cast<std::size_t>(c);
    const int facet = f++;
    const int j = neighbours_[cu][static_cast<std::size_t>(facet)];
    if (j < 0)
      continue;
    const auto ju = static_cast<std::size_t>(j);
    if (pores_[ju].saturation == pores_[cu].saturation && label_[ju] != label_[cu])
    {
      addPore(cluster, j);
      stack.emplace_back(j, 0);
    }
    else if (pores_[ju].nwReservoir)
      addInterface(cluster, c, facet);
  }
}

void TwoPhaseFlow::updateCellLabels()
{
  if (clusters_.size() < 2)
  {
    clusters_.resize(2);
    systems_.resize(2);
  }
  for (int k : {kNonWettingLabel, kReservoirLabel})
  {
    clusters_[static_cast<std::size_t>(k)] = PhaseCluster{};
    clusters_[static_cast<std::size_t>(k)].label = k;
  }
  for (auto& system : systems_)
    system.reset(); // the phases of the pores around the clusters may have changed
  const int n = static_cast<int>(pores_.size());
  for (int c = 0; c < n; ++c)
  {
    const PoreState& s = pores_[static_cast<std::size_t>(c)];
    if (s.nwReservoir)
      addPore(kNonWettingLabel, c);
    else if (s.wReservoir)
    {
      addPore(kReservoirLabel, c);
      for (int f = 0; f < 4; ++f)
      {
        const int j = neighbours_[static_cast<std::size_t>(c)][static_cast<std::size_t>(f)];
        if (j >= 0 && !pores_[static_cast<std::size_t>(j)].wReservoir)
          addInterface(kReservoirLabel, c, f);
      }
    }
    else if (label_[static_cast<std::size_t>(c)] <= kReservoirLabel)
      label_[static_cast<std::size_t>(c)] = -1; // a trapped pore not yet in a cluster of its own
  }
  for (int c = 0; c < n; ++c)
    if (label_[static_cast<std::size_t>(c)] == -1)
    {
      PhaseCluster k;
      k.label = static_cast<int>(clusters_.size());
      clusters_.push_back(std::move(k));
      systems_.emplace_back();
      labelFrom(clusters_.back().label, c);
    }
}

std::vector<int> TwoPhaseFlow::outvadePore(int startingId, int imbibedId)
{
  const int n = static_cast<int>(pores_.size());
  if (startingId < 0 || startingId >= n)
    throw std::out_of_range("clusterOutvadePore: startingId " + std::to_string(startingId) + " out of range (0.."
                            + std::to_string(n - 1) + ")");
  if (imbibedId < 0 || imbibedId >= n)
    throw std::out_of_range("clusterOutvadePore: imbibedId " + std::to_string(imbibedId) + " out of range (0.."
                            + std::to_string(n - 1) + ")");
  const int label = label_[static_cast<std::size_t>(startingId)];
  if (label <= kNonWettingLabel)
    throw std::invalid_argument("clusterOutvadePore: startingId " + std::to_string(startingId)
                                + " is not in a wetting cluster (label " + std::to_string(label)
                                + "; isCellLabelActivated must be set before initialization())");
  if (label_[static_cast<std::size_t>(imbibedId)] != kNonWettingLabel)
    throw std::invalid_argument("clusterOutvadePore: imbibedId " + std::to_string(imbibedId)
                                + " is not a non-wetting pore (label "
                                + std::to_string(label_[static_cast<std::size_t>(imbibedId)]) + ")");
  addPore(label, imbibedId); // the cluster's system is kept: solveClusterPressure borders it
  std::vector<int> merged{label};
  const auto im = static_cast<std::size_t>(imbibedId);
  for (int f = 0; f < 4; ++f)
  {
    const int j = neighbours_[im][static_cast<std::size_t>(f)];
    if (j < 0 || j == startingId)
      continue;
    const int other = label_[static_cast<std::size_t>(j)];
    if (other == kNonWettingLabel)
      addInterface(label, imbibedId, f);
    else if (other != label && other > kNonWettingLabel)
    {
      // the wetting cluster met: its pores and interfaces (but those onto the imbibed pore) join
      merged.push_back(other);
      PhaseCluster& absorbed = clusters_[static_cast<std::size_t>(other)];
      PhaseCluster& into = clusters_[static_cast<std::size_t>(label)];
      for (int p : absorbed.pores)
        label_[static_cast<std::size_t>(p)] = label;
      into.pores.insert(into.pores.end(), absorbed.pores.begin(), absorbed.pores.end());
      for (const Interface& i : absorbed.interfaces)
        if (i.outer != imbibedId)
          into.interfaces.push_back(i);
      absorbed = PhaseCluster{};
      systems_[static_cast<std::size_t>(other)].reset();
    }
  }
  std::vector<int>& nonWetting = clusters_[kNonWettingLabel].pores;
  nonWetting.erase(std::find(nonWetting.begin(), nonWetting.end(), imbibedId));
  // the interfaces now inside the cluster go (erased in place: the others keep their order)
  std::vector<Interface>& list = clusters_[static_cast<std::size_t>(label)].interfaces;
  list.erase(std::remove_if(list.begin(), list.end(),
                            [&](const Interface& i) { return label_[static_cast<std::size_t>(i.outer)] == label; }),
             list.end());
  return merged;
}

int TwoPhaseFlow::wettingLabel(int cellId, const char* function) const
{
  const int n = static_cast<int>(pores_.size());
  if (cellId < 0 || cellId >= n)
    throw std::out_of_range(std::string(function) + ": cellId " + std::to_string(cellId) + " out of range (0.."
                            + std::to_string(n - 1) + ")");
  const int label = label_[static_cast<std::size_t>(cellId)];
  if (label <= kNonWettingLabel)
    throw std::invalid_argument(std::string(function) + ": cellId " + std::to_string(cellId)
                                + " is not in a wetting cluster (label " + std::to_string(label)
                                + "; isCellLabelActivated must be set before initialization())");
  return label;
}

std::vector<int> TwoPhaseFlow::invadePore(int cellId)
{
  const int label = wettingLabel(cellId, "clusterInvadePore");
  const auto cell = static_cast<std::size_t>(cellId);
  PhaseCluster& cluster = clusters_[static_cast<std::size_t>(label)];
  const std::vector<int> members = std::move(cluster.pores);
  cluster = PhaseCluster{};
  cluster.label = label;
  systems_[static_cast<std::size_t>(label)].reset();
  addPore(kNonWettingLabel, cellId);
  if (members.size() == 1)
    return {};
  // the cluster's other pores unlabelled, then found again from the drained pore's neighbours
  for (int p : members)
    if (p != cellId)
      label_[static_cast<std::size_t>(p)] = -1;
  std::vector<int> result;
  for (int j : neighbours_[cell])
  {
    if (j < 0 || label_[static_cast<std::size_t>(j)] != -1)
      continue; // not of the cluster, or reached from an earlier neighbour
    int into = label;
    if (!result.empty())
    {
      into = static_cast<int>(clusters_.size());
      clusters_.emplace_back().label = into;
      systems_.emplace_back();
    }
    labelFrom(into, j);
    result.push_back(into);
  }
  return result;
}

std::vector<int> TwoPhaseFlow::invadePoreFast(int cellId)
{
  const int label = wettingLabel(cellId, "clusterInvadePoreFast");
  const auto cell = static_cast<std::size_t>(cellId);
  if (pores_[cell].imposed)
    return {label};
  systems_[static_cast<std::size_t>(label)].reset();
  addPore(kNonWettingLabel, cellId);
  PhaseCluster& cluster = clusters_[static_cast<std::size_t>(label)];
  if (cluster.pores.size() == 1)
  {
    cluster = PhaseCluster{};
    cluster.label = label;
    return {};
  }
  std::vector<int> facets; // of the pore, towards its neighbours in the cluster
  for (int f = 0; f < 4; ++f)
  {
    const int j = neighbours_[cell][static_cast<std::size_t>(f)];
    if (j >= 0 && label_[static_cast<std::size_t>(j)] == label)
      facets.push_back(f);
  }
  // its own interfaces go (from the end, at most one per facet not towards the cluster)
  std::vector<Interface>& list = cluster.interfaces;
  std::size_t faces = 4 - facets.size();
  for (auto k = static_cast<std::ptrdiff_t>(list.size()) - 1; k >= 0 && faces > 0; --k)
    if (list[static_cast<std::size_t>(k)].inner == cellId)
    {
      cluster.interfacialArea -= list[static_cast<std::size_t>(k)].area;
      list.erase(list.begin() + k);
      --faces;
    }
  for (int f : facets)
  {
    const int j = neighbours_[cell][static_cast<std::size_t>(f)];
    const std::array<int, 4>& across = neighbours_[static_cast<std::size_t>(j)];
    addInterface(label, j, static_cast<int>(std::find(across.begin(), across.end(), cellId) - across.begin()));
  }
  cluster.pores.erase(std::find(cluster.pores.begin(), cluster.pores.end(), cellId));
  // the cases where the neighbours are still joined next to the pore: no split
  const std::size_t n = facets.size();
  if (n == 1 || (n == 2 && connectedAroundEdge(cellId, facets[0], facets[1], label)))
    return {label};
  if (n == 3
      && int(connectedAroundEdge(cellId, facets[0], facets[1], label)) + int(connectedAroundEdge(cellId, facets[1], facets[2], label))
                 + int(connectedAroundEdge(cellId, facets[2], facets[0], label))
             >= 2)
    return {label};
  // the wetting reservoir is rebuilt from its last imposed pore, so that it keeps label 1
  int start = cluster.pores.front();
  if (label == kReservoirLabel)
  {
    const auto imposed = std::find_if(cluster.pores.rbegin(), cluster.pores.rend(),
                                      [&](int p) { return pores_[static_cast<std::size_t>(p)].imposed; });
    if (imposed != cluster.pores.rend())
      start = *imposed;
  }
  return splitCluster(label, start);
}

bool TwoPhaseFlow::connectedAroundEdge(int cell, int f1, int f2, int label) const
{
  // the edge's vertices: the cell's two vertices other than those opposite f1 and f2
  std::array<int, 2> edge{};
  for (int k = 0, e = 0; k < 4; ++k)
    if (k != f1 && k != f2)
      edge[static_cast<std::size_t>(e++)] = poreVertices_[static_cast<std::size_t>(cell)][static_cast<std::size_t>(k)];
  int previous = cell;
  int current = neighbours_[static_cast<std::size_t>(cell)][static_cast<std::size_t>(f1)];
  while (current != cell)
  {
    if (current < 0 || label_[static_cast<std::size_t>(current)] != label)
      return false;
    // on to the cell across the other facet of `current` that holds the edge
    const auto c = static_cast<std::size_t>(current);
    int next = -1;
    for (std::size_t k = 0; k < 4; ++k)
    {
      const int v = poreVertices_[c][k];
      if (v != edge[0] && v != edge[1] && neighbours_[c][k] != previous)
        next = neighbours_[c][k];
    }
    previous = current;
    current = next;
  }
  return true;
}

std::vector<int> TwoPhaseFlow::splitCluster(int label, int start)
{
  const auto l = static_cast<std::size_t>(label);
  const std::size_t size = clusters_[l].pores.size();
  const int next = static_cast<int>(clusters_.size());
  for (int p : clusters_[l].pores)
    label_[static_cast<std::size_t>(p)] = next;
  // what `start` reaches through the cluster takes the label back
  std::size_t reached = 1;
  label_[static_cast<std::size_t>(start)] = label;
  std::vector<int> stack{start};
  while (!stack.empty())
  {
    const auto c = static_cast<std::size_t>(stack.back());
    stack.pop_back();
    for (int j : neighbours_[c])
      if (j >= 0 && label_[static_cast<std::size_t>(j)] == next)
      {
        label_[static_cast<std::size_t>(j)] = label;
        ++reached;
        stack.push_back(j);
      }
  }
  if (reached == size)
    return {label};
  clusters_.emplace_back().label = next;
  systems_.emplace_back();
  systems_[l].reset();
  // the rest moves, taken from the end of the lists (Yade's order)
  std::vector<int> kept;
  std::size_t moved = 0;
  const std::vector<int> pores = std::move(clusters_[l].pores);
  for (auto p = pores.rbegin(); p != pores.rend(); ++p)
    if (label_[static_cast<std::size_t>(*p)] == next)
    {
      clusters_[l].volume -= bodyVolume_[static_cast<std::size_t>(*p)];
      addPore(next, *p);
      ++moved;
    }
    else
      kept.push_back(*p);
  clusters_[l].pores.assign(kept.rbegin(), kept.rend());
  std::vector<Interface>& from = clusters_[l].interfaces;
  std::vector<Interface>& to = clusters_[static_cast<std::size_t>(next)].interfaces;
  for (auto k = static_cast<std::ptrdiff_t>(from.size()) - 1; k >= 0; --k)
    if (label_[static_cast<std::size_t>(from[static_cast<std::size_t>(k)].inner)] == next)
    {
      to.push_back(from[static_cast<std::size_t>(k)]);
      from.erase(from.begin() + k);
    }
  if (moved == 1)
    return {label, next};
  std::vector<int> labels = splitCluster(next, clusters_[static_cast<std::size_t>(next)].pores.front());
  labels.push_back(label);
  return labels;
}

void TwoPhaseFlow::solveClusterPressure(int cluster)
{
  const PhaseCluster& k = checkedCluster(cluster);
  if (k.pores.empty())
    throw std::invalid_argument("PhaseCluster.solvePressure: cluster " + std::to_string(cluster) + " has no pores");
  std::shared_ptr<ClusterSystem>& system = systems_[static_cast<std::size_t>(cluster)];
  std::vector<int> index(pores_.size(), -1); // matrix row of each unknown pore
  std::vector<int> unknowns;
  for (int p : k.pores)
    if (!pores_[static_cast<std::size_t>(p)].imposed)
    {
      index[static_cast<std::size_t>(p)] = static_cast<int>(unknowns.size());
      unknowns.push_back(p);
    }
  const auto m = static_cast<Eigen::Index>(unknowns.size());
  Eigen::VectorXd rhs = Eigen::VectorXd::Zero(m);
  std::vector<Eigen::Triplet<double>> entries;
  for (Eigen::Index row = 0; row < m; ++row)
  {
    const auto c = static_cast<std::size_t>(unknowns[static_cast<std::size_t>(row)]);
    double diagonal = 0;
    for (std::size_t f = 0; f < 4; ++f)
    {
      const int j = neighbours_[c][f];
      if (j < 0)
        continue;
      const auto ju = static_cast<std::size_t>(j);
      const double kf = conductance_[static_cast<std::size_t>(throats_[c][f])];
      diagonal += kf;
      if (pores_[ju].imposed || pores_[ju].nwReservoir)
        rhs[row] += kf * pores_[ju].pressure; // a condition: imposed or non-wetting pressure
      else if (label_[ju] == cluster)
        entries.emplace_back(row, index[ju], -kf);
      // a pore of another wetting cluster: as a zero pressure, as Yade (which warns)
    }
    entries.emplace_back(row, row, diagonal);
  }
  for (const Interface& i : k.interfaces)
    if (!pores_[static_cast<std::size_t>(i.inner)].imposed)
      rhs[index[static_cast<std::size_t>(i.inner)]] -= conductanceOf(i) * i.capillaryPressure;
  if (m == 0)
    return; // only imposed pores: nothing to solve
  Eigen::SparseMatrix<double> a(m, m);
  a.setFromTriplets(entries.begin(), entries.end());
  Eigen::VectorXd p;
  if (system && system->borders(a, unknowns))
  {
    p = system->solve(a, rhs);
    system->matrix = std::move(a);
    system->unknowns = unknowns;
  }
  else
  {
    if (!system)
      system = std::make_shared<ClusterSystem>();
    system->factorise(std::move(a), unknowns, cluster);
    p = system->factor.solve(rhs);
  }
  for (Eigen::Index row = 0; row < m; ++row)
    pores_[static_cast<std::size_t>(unknowns[static_cast<std::size_t>(row)])].pressure = p[row];
}

double TwoPhaseFlow::interfaceConductance(int cluster, int index) const
{
  return conductanceOf(interface(cluster, index));
}

double TwoPhaseFlow::interfaceFlux(int cluster, int index) const
{
  const Interface& i = interface(cluster, index);
  return conductanceOf(i) * (pores_[static_cast<std::size_t>(i.inner)].pressure + i.capillaryPressure -
                             pores_[static_cast<std::size_t>(i.outer)].pressure);
}

void TwoPhaseFlow::updateInterfaceVolumes(int cluster, double dt)
{
  const int n = static_cast<int>(checkedCluster(cluster).interfaces.size());
  for (int i = 0; i < n; ++i)
    interface(cluster, i).volume += dt * interfaceFlux(cluster, i);
}

double TwoPhaseFlow::boundaryFlux(int k) const
{
  if (k < 0 || k >= static_cast<int>(kBoundaries))
    throw std::out_of_range("getBoundaryFlux: boundary index must be 0..5, got " + std::to_string(k));
  double q = 0;
  for (int c : boundaryPores_[static_cast<std::size_t>(k)])
    for (std::size_t f = 0; f < 4; ++f)
    {
      const int j = neighbours_[static_cast<std::size_t>(c)][f];
      if (j >= 0)
        q += conductance_[static_cast<std::size_t>(throats_[static_cast<std::size_t>(c)][f])] *
             (pores_[static_cast<std::size_t>(j)].pressure - pores_[static_cast<std::size_t>(c)].pressure);
    }
  return q;
}

double TwoPhaseFlow::poreFlux(int pore) const
{
  if (pore < 0 || static_cast<std::size_t>(pore) >= pores_.size())
    throw std::out_of_range("getCellFluxFromId: cell id " + std::to_string(pore) + " out of range (0.."
                            + std::to_string(static_cast<int>(pores_.size()) - 1) + ")");
  const auto c = static_cast<std::size_t>(pore);
  double q = 0;
  for (std::size_t f = 0; f < 4; ++f)
  {
    const int j = neighbours_[c][f];
    if (j >= 0)
      q += conductance_[static_cast<std::size_t>(throats_[c][f])]
           * (pores_[c].pressure - pores_[static_cast<std::size_t>(j)].pressure);
  }
  return q;
}
} // namespace talus::flow::twophase
