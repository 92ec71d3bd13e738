#include "dem/distributed/script/Snapshot.h"

#include "dem/core/Scene.h"
#include "dem/distributed/script/Channel.h"

#include <algorithm>

namespace talus::dem::distributed
{
void snapshotOf(const MpiDomain& domain, const Scene& scene, std::size_t row, double* out)
{
  const Bodies& b = scene.bodies;
  *out++ = static_cast<double>(domain.globalIdOf(row));
  for (const Vec3* v : {&b.pos[row], &b.vel[row], &b.angVel[row]})
    out = std::copy(v->data(), v->data() + 3, out);
  const Quat& q = b.ori[row];
  for (const double x : {q.w(), q.x(), q.y(), q.z(), b.mass[row]})
    *out++ = x;
  out = std::copy(b.inertia[row].data(), b.inertia[row].data() + 3, out);
  const BodyId clump = b.clumpId[row];
  for (const double x : {b.radius[row], static_cast<double>(b.dynamic[row]), static_cast<double>(b.material[row]),
                         static_cast<double>(b.groupMask[row]),
                         clump >= 0 ? static_cast<double>(domain.globalIdOf(static_cast<std::size_t>(clump))) : -1.0,
                         b.shape[row] == ShapeKind::Clump ? 1.0 : 0.0, static_cast<double>(b.blockedDofs[row]),
                         static_cast<double>(domain.rank()), static_cast<double>(b.damped[row])})
    *out++ = x;
}

ScriptRead readById(const MpiDomain& domain, const Scene& scene, GlobalId id, double patience, const std::string& rule)
{
  ScriptRead read;
  const std::int64_t found = domain.rowOf(id);
  const auto row = static_cast<std::size_t>(found);
  const bool here = found >= 0 && domain.owns(row) && scene.bodies.alive[row];
  if (found >= 0 && domain.owns(row) && domain.replicated(row))
  {
    read.local = true;
    read.row = here ? found : -1;
    return read;
  }
  std::vector<double> mine(placeDoubles + snapshotDoubles, 0.0);
  mine[0] = readPlace;
  mine[1] = static_cast<double>(id);
  if (here)
  {
    mine[2] = 1;
    snapshotOf(domain, scene, row, mine.data() + placeDoubles);
    read.row = found;
  }
  read.rows = gatherOnScriptChannel(mine, patience,
                                    "talus run: process " + std::to_string(domain.rank()) + " read O.bodies["
                                        + std::to_string(id) + "] and the other processes did not come to it: " + rule);
  for (std::size_t at = 0; at < read.rows.size(); at += mine.size())
    read.agreed = read.agreed && read.rows[at] == mine[0] && read.rows[at + 1] == mine[1];
  return read;
}
} // namespace talus::dem::distributed
