// Four contacts in the four lanes of AVX2 vectors (dem/contact/SphereGeometryLanes.h).
#include "dem/contact/SphereGeometryBatch.h"
#include "dem/contact/SphereGeometryLanes.h"

namespace talus::dem
{
bool sphereBatchAvailable()
{
  static const bool available = __builtin_cpu_supports("avx2");
  return available;
}

[[gnu::target("avx2")]] unsigned sphereGeometryBatch(Contact* const* contacts, const Bodies& b, double dt, const Cell* cell)
{
  const avx2::SphereGeometry g = avx2::sphereGeometry(contacts, b, dt, cell, nullptr);
  avx2::store(g, contacts, g.touching);
  return g.touching;
}
} // namespace talus::dem
