#include "dem/core/Scene.h"

#include "dem/core/Clump.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

namespace talus::dem
{
namespace
{
std::string str(const Vec3& v)
{
  return "(" + std::to_string(v[0]) + ", " + std::to_string(v[1]) + ", " + std::to_string(v[2]) + ")";
}

/// @throws std::invalid_argument naming the body `which` unless `material` indexes one of `count` materials
void checkMaterial(const std::string& which, int material, std::size_t count)
{
  if (material < 0 || material >= static_cast<int>(count))
    throw std::invalid_argument(which + ": unknown material index " + std::to_string(material));
}

/// Yade's fixed=True: body i is not dynamic and has every degree of freedom blocked.
void fix(Bodies& bodies, std::size_t i)
{
  bodies.dynamic[i] = 0;
  bodies.blockedDofs[i] = DofAll;
}
} // namespace

int Scene::addMaterial(const Material& material)
{
  material.validate();
  materials.push_back(material);
  return static_cast<int>(materials.size()) - 1;
}

BodyId Scene::addSphere(const Vec3& center, double radius, int material)
{
  const std::string which = "sphere #" + std::to_string(bodies.size());
  if (!(std::isfinite(radius) && radius > 0))
    throw std::invalid_argument(which + ": radius must be positive and finite, got " + std::to_string(radius));
  if (!center.allFinite())
    throw std::invalid_argument(which + ": centre is not finite " + str(center));
  if (material < 0 || material >= static_cast<int>(materials.size()))
    throw std::invalid_argument(which + ": unknown material index " + std::to_string(material) + " (the scene has "
                                + std::to_string(materials.size()) + " materials)");
  const BodyId id = bodies.append(ShapeKind::Sphere, -1, material);
  const auto i = static_cast<std::size_t>(id);
  bodies.pos[i] = center;
  bodies.radius[i] = radius;
  // Yade's order of operations (utils.sphere), so that masses are Yade's to the last bit.
  const double volume = (4.0 / 3.0) * M_PI * std::pow(radius, 3), density = materials[static_cast<std::size_t>(material)].density;
  bodies.mass[i] = volume * density;
  bodies.inertia[i] = Vec3::Constant((2.0 / 5.0) * volume * std::pow(radius, 2) * density);
  ++bodiesVersion;
  return id;
}

BodyId Scene::addWall(double position, int axis, int sense, int material)
{
  const std::string which = "wall #" + std::to_string(bodies.size());
  if (axis < 0 || axis > 2)
    throw std::invalid_argument(which + ": axis must be 0, 1 or 2, got " + std::to_string(axis));
  if (sense < -1 || sense > 1)
    throw std::invalid_argument(which + ": sense must be -1, 0 or 1, got " + std::to_string(sense));
  if (!std::isfinite(position))
    throw std::invalid_argument(which + ": position is not finite");
  checkMaterial(which, material, materials.size());
  bodies.walls.push_back({axis, sense});
  const BodyId id = bodies.append(ShapeKind::Wall, static_cast<int>(bodies.walls.size()) - 1, material);
  const auto i = static_cast<std::size_t>(id);
  bodies.pos[i][axis] = position;
  fix(bodies, i);
  ++bodiesVersion;
  return id;
}

BodyId Scene::addFacet(const Vec3& a, const Vec3& b, const Vec3& c, int material, bool bounded)
{
  const std::string which = "facet #" + std::to_string(bodies.size());
  if (!a.allFinite() || !b.allFinite() || !c.allFinite())
    throw std::invalid_argument(which + ": vertices must be finite");
  const Vec3 n = (b - a).cross(c - a);
  const double la = (c - b).norm(), lb = (a - c).norm(), lc = (b - a).norm();
  if (!(n.norm() > 1e-12 * (la + lb + lc) * (la + lb + lc)))
    throw std::invalid_argument(which + ": the three vertices are (nearly) collinear " + str(a) + " " + str(b) + " " + str(c));
  checkMaterial(which, material, materials.size());
  // Incentre: vertices weighted by the lengths of the opposite sides.
  const Vec3 centre = (la * a + lb * b + lc * c) / (la + lb + lc);
  bodies.facets.push_back({{a - centre, b - centre, c - centre}, n.normalized(), bounded});
  const BodyId id = bodies.append(ShapeKind::Facet, static_cast<int>(bodies.facets.size()) - 1, material);
  const auto i = static_cast<std::size_t>(id);
  bodies.pos[i] = centre;
  fix(bodies, i);
  ++bodiesVersion;
  return id;
}

BodyId Scene::addBox(const Vec3& center, const Vec3& extents, const Quat& orientation, int material, bool fixed)
{
  const std::string which = "box #" + std::to_string(bodies.size());
  if (!center.allFinite())
    throw std::invalid_argument(which + ": centre is not finite " + str(center));
  // A zero half-size is a flat box, as Yade allows (a plane bounded in the other directions;
  // massless, so fixed).
  if (!extents.allFinite() || !(extents.minCoeff() >= 0))
    throw std::invalid_argument(which + ": extents (half-sizes) must be finite and >= 0, got " + str(extents));
  if (!orientation.coeffs().allFinite() || !(orientation.norm() > 0))
    throw std::invalid_argument(which + ": orientation is not a finite non-zero quaternion");
  checkMaterial(which, material, materials.size());
  bodies.boxes.push_back({extents});
  const BodyId id = bodies.append(ShapeKind::Box, static_cast<int>(bodies.boxes.size()) - 1, material);
  const auto i = static_cast<std::size_t>(id);
  bodies.pos[i] = center;
  bodies.ori[i] = orientation.normalized();
  const Vec3 e2 = extents.cwiseProduct(extents);
  bodies.mass[i] = materials[static_cast<std::size_t>(material)].density * 8 * extents.prod();
  bodies.inertia[i] = bodies.mass[i] / 3 * Vec3(e2[1] + e2[2], e2[0] + e2[2], e2[0] + e2[1]);
  if (fixed)
    fix(bodies, i);
  ++bodiesVersion;
  return id;
}

BodyId Scene::addPotentialBlock(const std::vector<double>& a, const std::vector<double>& b, const std::vector<double>& c,
                                const std::vector<double>& d, double r, double R, bool isBoundary, const Vec3* center,
                                const Quat& orientation, int material, bool fixed)
{
  const std::string which = "PotentialBlock #" + std::to_string(bodies.size());
#ifndef TALUS_HAVE_CLP
  (void)a, (void)b, (void)c, (void)d, (void)r, (void)R, (void)isBoundary, (void)center, (void)orientation, (void)material,
      (void)fixed;
  throw std::runtime_error(which + ": Potential Blocks need CLP, and this build has none "
                           "(apt-get install coinor-libclp-dev, then configure again)");
#else
  if (periodic)
    throw std::invalid_argument(which + ": Potential Blocks are not supported in a periodic scene");
  if (center && !center->allFinite())
    throw std::invalid_argument(which + ": centre is not finite " + str(*center));
  if (!orientation.coeffs().allFinite() || !(orientation.norm() > 0))
    throw std::invalid_argument(which + ": orientation is not a finite non-zero quaternion");
  checkMaterial(which, material, materials.size());
  PotentialBlockPlacement placement;
  bodies.blocks.push_back(makePotentialBlock(a, b, c, d, r, R, isBoundary, which, &placement));
  const BodyId id = bodies.append(ShapeKind::PotentialBlock, static_cast<int>(bodies.blocks.size()) - 1, material);
  const auto i = static_cast<std::size_t>(id);
  bodies.pos[i] = center ? *center : placement.centroid;
  bodies.ori[i] = (orientation.normalized() * placement.principalAxes).normalized();
  const double density = materials[static_cast<std::size_t>(material)].density;
  bodies.mass[i] = density * bodies.blocks.back().volume;
  bodies.inertia[i] = density * placement.inertiaPerDensity;
  if (fixed)
    fix(bodies, i);
  ++bodiesVersion;
  return id;
#endif
}

BodyId Scene::addPotentialParticle(const std::vector<double>& a, const std::vector<double>& b,
                                   const std::vector<double>& c, const std::vector<double>& d, double r, double k,
                                   double R, bool isBoundary, const Vec3& position, const Quat& orientation,
                                   int material, bool fixed)
{
  const std::string which = "PotentialParticle #" + std::to_string(bodies.size());
  if (periodic)
    throw std::invalid_argument(which + ": Potential Particles are not supported in a periodic scene");
  if (!position.allFinite())
    throw std::invalid_argument(which + ": position is not finite " + str(position));
  if (!orientation.coeffs().allFinite() || !(orientation.norm() > 0))
    throw std::invalid_argument(which + ": orientation is not a finite non-zero quaternion");
  checkMaterial(which, material, materials.size());
  bodies.particles.push_back(makePotentialParticle(a, b, c, d, r, k, R, isBoundary, which));
  const PotentialParticleShape& s = bodies.particles.back();
  const BodyId id = bodies.append(ShapeKind::PotentialParticle, static_cast<int>(bodies.particles.size()) - 1, material);
  const auto i = static_cast<std::size_t>(id);
  const Quat q = orientation.normalized();
  bodies.pos[i] = position + q * s.centroid;
  bodies.ori[i] = (q * Quat(s.axes)).normalized();
  const double density = materials[static_cast<std::size_t>(material)].density;
  bodies.mass[i] = density * s.volume;
  bodies.inertia[i] = density * s.inertiaPerDensity;
  if (fixed)
    fix(bodies, i);
  ++bodiesVersion;
  return id;
}

void Scene::checkBody(BodyId id) const
{
  if (id < 0 || static_cast<std::size_t>(id) >= bodies.size() || !bodies.alive[static_cast<std::size_t>(id)])
    throw std::out_of_range("no body with id " + std::to_string(id));
}

std::vector<BodyId> Scene::rowsActedOn(const std::vector<BodyId>& ids, const std::string& engine) const
{
  std::vector<BodyId> rows;
  rows.reserve(ids.size());
  for (const BodyId id : ids)
  {
    const std::int64_t row = domain ? domain->rowOf(id) : id;
    if (row == Domain::elsewhere)
      continue;
    if (row < 0 || static_cast<std::size_t>(row) >= bodies.size() || !bodies.alive[static_cast<std::size_t>(row)])
      throw std::out_of_range(engine + ": no body with id " + std::to_string(id));
    if (!domain || domain->owns(static_cast<std::size_t>(row))) // a ghost moves with its owner
      rows.push_back(static_cast<BodyId>(row));
  }
  return rows;
}

void Scene::setPeriodic(bool on)
{
  // Positions are not wrapped, as in Yade: bodies may lie anywhere, the collider finds the
  // periodic images that touch.
  if (on)
    for (std::size_t i = 0; i < bodies.size(); ++i)
      if (bodies.alive[i] && (bodies.shape[i] == ShapeKind::PotentialBlock || bodies.shape[i] == ShapeKind::PotentialParticle))
        throw std::invalid_argument("body " + std::to_string(i) + ": Potential Blocks and Particles are not supported "
                                    "in a periodic scene");
  periodic = on;
  ++bodiesVersion;
}

void Scene::setCellSize(const Mat3& h)
{
  if (!h.allFinite() || !(h.determinant() > 0))
    throw std::invalid_argument("cell: hSize must be finite with a positive volume (right-handed edges), got det "
                                + std::to_string(h.determinant()));
  cell.hSize = h;
  ++bodiesVersion;
}

void Scene::setBlockedDofs(BodyId id, std::uint8_t mask)
{
  checkBody(id);
  if (mask > DofAll)
    throw std::invalid_argument("body " + std::to_string(id) + ": blocked DOF mask " + std::to_string(mask) + " is not in 0..63");
  bodies.blockedDofs[static_cast<std::size_t>(id)] = mask;
  ++bodyPropertiesVersion;
}

void Scene::setMass(BodyId id, double mass)
{
  checkBody(id);
  if (!(std::isfinite(mass) && mass >= 0))
    throw std::invalid_argument("body " + std::to_string(id) + ": mass must be finite and >= 0, got " + std::to_string(mass));
  bodies.mass[static_cast<std::size_t>(id)] = mass;
  ++bodyPropertiesVersion;
}

void Scene::setInertia(BodyId id, const Vec3& inertia)
{
  checkBody(id);
  if (!(inertia.allFinite() && inertia.minCoeff() >= 0))
    throw std::invalid_argument("body " + std::to_string(id) + ": inertia must be 3 finite numbers >= 0");
  bodies.inertia[static_cast<std::size_t>(id)] = inertia;
  ++bodyPropertiesVersion;
}

void Scene::setDynamic(BodyId id, bool dynamic)
{
  checkBody(id);
  bodies.dynamic[static_cast<std::size_t>(id)] = dynamic ? 1 : 0;
  ++bodyPropertiesVersion;
}

void Scene::erase(BodyId id, bool eraseClumpMembers)
{
  checkBody(id);
  const auto i = static_cast<std::size_t>(id);
  if (bodies.shape[i] == ShapeKind::Clump)
  {
    std::vector<BodyId>& members = bodies.clumps[static_cast<std::size_t>(bodies.shapeIndex[i])].members;
    for (BodyId m : members)
    {
      bodies.clumpId[static_cast<std::size_t>(m)] = -1;
      if (eraseClumpMembers)
        erase(m);
    }
    members.clear();
  }
  else if (bodies.clumpId[i] >= 0)
    eraseClumpMember(id);
  // Its contacts go now, not at the next collider run: an engine between the collider and
  // the interaction loop would otherwise still see them.
  contacts.removeIf([id](const Contact& c) { return c.id1 == id || c.id2 == id; }, bodies.size());
  bodies.alive[i] = 0;
  ++bodiesVersion;
  ++bodyPropertiesVersion;
}

void Scene::clearBodies()
{
  Bodies empty;
  empty.blockContact = bodies.blockContact;
  empty.particleContact = bodies.particleContact;
  bodies = std::move(empty);
  contacts.list.clear();
  contacts.extra.clear();
  contacts.index(0);
  ++bodiesVersion;
  ++bodyPropertiesVersion;
}

bool Scene::eraseContact(BodyId id1, BodyId id2)
{
  const std::size_t before = contacts.list.size();
  contacts.removeIf([id1, id2](const Contact& c) { return (c.id1 == id1 && c.id2 == id2) || (c.id1 == id2 && c.id2 == id1); },
                    bodies.size());
  return contacts.list.size() != before;
}

void Scene::runEngine(std::size_t k)
{
  Engine& engine = *engines[k];
  if (engine.dead)
    return;
  try
  {
    engine.run(*this);
  }
  catch (const std::exception& e)
  {
    if (engine.resumableAfterError())
      subStep = static_cast<int>(k) + 1; // the next step() runs the engines after it, then ends the step
    else
      failedStep_ = e.what();
    throw;
  }
}

void Scene::endStep()
{
  try
  {
    stepLoop().endStep(*this);
  }
  catch (const std::exception& e)
  {
    failedStep_ = e.what();
    throw;
  }
  time += dt;
  ++iter;
}

void Scene::setEngines(std::vector<std::shared_ptr<Engine>> list)
{
  if (subStep < 0)
  {
    engines = std::move(list);
    nextEngines.reset(); // engines set during the last step are replaced too
  }
  else
    nextEngines = std::move(list);
}

void Scene::step()
{
  stepLoop().forgetAhead(); // the caller may have moved bodies since the last step
  advance();
}

void Scene::advance()
{
  if (!failedStep_.empty())
    throw std::runtime_error("cannot continue: step " + std::to_string(iter) + " failed and left the scene half updated ("
                             + failedStep_ + "); load a checkpoint (O.load, O.loadTmp) to go on from a saved state");
  if (stepping_) // an engine (a PyRunner's command) asked for a step inside this one
    throw std::runtime_error("Called O.step() while simulation is running.");
  struct Stepping
  {
    bool& flag;
    explicit Stepping(bool& f) : flag(f) { flag = true; }
    ~Stepping() { flag = false; }
    Stepping(const Stepping&) = delete;
    Stepping& operator=(const Stepping&) = delete;
  } stepping(stepping_);
  // As Yade: engines set during a step take over when the next one starts.
  if (nextEngines && (subStep < 0 || (subStep <= 0 && !subStepping)))
  {
    engines = std::move(*nextEngines);
    nextEngines.reset();
    subStep = -1;
  }
  const int n = static_cast<int>(engines.size());
  const StepLoop::EngineRunner runner = [this](std::size_t k) { runEngine(k); };
  if (!subStepping && subStep < 0)
  {
    subStep = 0;
    try
    {
      stepLoop().runStep(*this, runner);
    }
    catch (const std::exception& e)
    {
      if (subStep <= 0 && failedStep_.empty()) // not already marked by runEngine
        failedStep_ = e.what();
      throw;
    }
    endStep();
    subStep = -1;
    return;
  }
  // Sub-steps: the one due, or with subStepping off all the rest of the step.
  if (subStep < -1 || subStep > n)
    subStep = -1;
  const int last = subStepping ? subStep : n;
  for (int k = subStep; k <= last; ++k)
  {
    if (k >= 0 && k < n)
      stepLoop().runSubStep(*this, static_cast<std::size_t>(k), runner);
    else if (k == n)
    {
      endStep();
      subStep = -2; // -1 with the increment below: between steps
    }
  }
  ++subStep;
}

void Scene::run(std::int64_t steps, const std::function<void()>& poll)
{
  pauseRequested_ = false;
  stepLoop().forgetAhead(); // the caller may have moved bodies since the last step
  for (std::int64_t k = 0; steps < 0 || k < steps; ++k)
  {
    advance();
    if (pauseRequested_)
      break;
    if (poll && k % 64 == 63)
    {
      poll();
      stepLoop().forgetAhead(); // a signal handler may have run Python
    }
  }
  pauseRequested_ = false;
}

double Scene::contactTimeStep() const
{
  double best = std::numeric_limits<double>::infinity();
  for (const Contact& c : contacts.list)
  {
    if (!c.real || !(c.kn > 0))
      continue;
    const auto i1 = static_cast<std::size_t>(c.id1), i2 = static_cast<std::size_t>(c.id2);
    const double m1 = rigidDynamic(bodies, i1) ? rigidMass(bodies, i1) : 0;
    const double m2 = rigidDynamic(bodies, i2) ? rigidMass(bodies, i2) : 0;
    const double m = m1 > 0 && m2 > 0 ? m1 * m2 / (m1 + m2) : std::max(m1, m2);
    if (m > 0)
      best = std::min(best, 2 * std::sqrt(m / c.kn));
  }
  return best;
}

double Scene::pWaveTimeStep() const
{
  double best = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < bodies.size(); ++i)
    if (bodies.alive[i] && bodies.shape[i] == ShapeKind::Sphere)
    {
      // As Yade's Shop::PWaveTimeStep: the density from the body's mass (a script may change
      // a body's mass: a lighter one needs a smaller step), Yade's order of operations.
      const Material& m = materials[static_cast<std::size_t>(bodies.material[i])];
      const double r = bodies.radius[i], density = bodies.mass[i] / ((4.0 / 3.0) * M_PI * std::pow(r, 3));
      best = std::min(best, r / std::sqrt(m.young / density));
    }
  return best;
}

Scene::StiffestSphere Scene::stiffestSphere() const
{
  StiffestSphere best;
  for (std::size_t i = 0; i < bodies.size(); ++i)
  {
    if (!bodies.alive[i] || bodies.shape[i] != ShapeKind::Sphere || bodies.clumpId[i] >= 0 || !bodies.dynamic[i]
        || !(bodies.mass[i] > 0))
      continue;
    const Material& m = materials[static_cast<std::size_t>(bodies.material[i])];
    if (!(m.young > 0) || (m.kind == MaterialKind::ViscEl && (std::isfinite(m.tc) || std::isfinite(m.kn))))
      continue;
    const double r = bodies.radius[i], density = bodies.mass[i] / ((4.0 / 3.0) * M_PI * std::pow(r, 3));
    const double step = r / std::sqrt(m.young / density);
    if (step < best.step)
      best = {step, static_cast<BodyId>(i)};
  }
  return best;
}
} // namespace talus::dem
