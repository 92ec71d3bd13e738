#include "dem/distributed/collect/Gather.h"

#include "dem/core/Scene.h"
#include "dem/distributed/Collective.h"

#include <array>
#include <numeric>
#include <string>

namespace talus::dem::distributed
{
std::vector<double> gatherBodies(const MpiDomain& domain, const Scene& scene, std::span<const GlobalId> ids)
{
  // The ranks must ask for the same bodies: the table's length (and its sum) would differ.
  const auto count = static_cast<double>(ids.size());
  const auto idSum = static_cast<double>(std::accumulate(ids.begin(), ids.end(), GlobalId{0}));
  std::array<double, 4> agree{count, -count, idSum, -idSum};
  domain.min(agree);
  if (agree[0] != -agree[1] || agree[2] != -agree[3])
    throw CollectiveError("O.bodies.gather: the processes asked for different bodies (" + std::to_string(ids.size())
                          + " ids on process " + std::to_string(domain.rank())
                          + "): it is collective, every process calls it with the same ids");
  for (const GlobalId id : ids)
    if (id < 0 || id >= domain.globalCount())
      throw CollectiveError("O.bodies.gather: no body with id " + std::to_string(id) + " (ids run from 0 to "
                            + std::to_string(domain.globalCount() - 1) + ")");

  // One more entry per body: 1 from the rank that filled it, so that an erased body shows.
  constexpr std::size_t width = gatheredDoubles + 1;
  std::vector<double> table(ids.size() * width, 0.0);
  const Bodies& b = scene.bodies;
  for (std::size_t k = 0; k < ids.size(); ++k)
  {
    const std::int64_t found = domain.rowOf(ids[k]);
    if (found < 0)
      continue;
    const auto row = static_cast<std::size_t>(found);
    if (!domain.countsBody(row) || !b.alive[row])
      continue;
    double* out = table.data() + k * width;
    for (const Vec3* v : {&b.pos[row], &b.vel[row], &b.angVel[row]})
      out = std::copy(v->data(), v->data() + 3, out);
    const Quat& q = b.ori[row];
    for (const double x : {q.w(), q.x(), q.y(), q.z(), b.mass[row]})
      *out++ = x;
    out = std::copy(b.inertia[row].data(), b.inertia[row].data() + 3, out);
    *out++ = b.radius[row];
    *out++ = b.dynamic[row] ? 1.0 : 0.0;
    *out = 1.0;
  }
  domain.sum(table);
  std::vector<double> state(ids.size() * gatheredDoubles);
  for (std::size_t k = 0; k < ids.size(); ++k)
  {
    const double* in = table.data() + k * width;
    if (in[gatheredDoubles] != 1.0)
      throw CollectiveError("O.bodies.gather: body " + std::to_string(ids[k]) + " was erased");
    std::copy(in, in + gatheredDoubles, state.begin() + static_cast<std::ptrdiff_t>(k * gatheredDoubles));
  }
  return state;
}
} // namespace talus::dem::distributed
