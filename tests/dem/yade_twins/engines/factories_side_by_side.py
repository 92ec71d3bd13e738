"""Yade's particle factories and DomainLimiter, written so that the same file runs in Yade
(`yade -n -x`) and in Talus. Prints one RESULT line with, per factory, its counters and the
radii, speeds and places of what it made (for statistics: Yade's generator is seeded by the
clock), and the DomainLimiter's tallies and the ids left (deterministic)."""
import json
import math

try:
    O  # noqa: B018  (defined when Yade runs the script)
except NameError:
    from talus.dem import *  # noqa: F401,F403

out = {}
mat = O.materials.append(FrictMat(young=1e7, poisson=0.3, density=2000, frictionAngle=0.5))
O.engines = [
    ForceResetter(),
    InsertionSortCollider([Bo1_Sphere_Aabb()], verletDist=0.001),
    InteractionLoop([Ig2_Sphere_Sphere_ScGeom()], [Ip2_FrictMat_FrictMat_FrictPhys()], [Law2_ScGeom_FrictPhys_CundallStrack()]),
    NewtonIntegrator(damping=0),
    # sizes from a distribution, by mass: exact diameters (the radii made are the same in Yade)
    BoxFactory(center=(0, 0, 0), extents=(1, 1, 0.2), normal=(0, 0, 1), massFlowRate=3000, PSDsizes=[0.02, 0.03, 0.05],
               PSDcum=[0.2, 0.5, 1.0], vMin=1, vMax=2, maxParticles=-1, materialId=mat, label='exact'),
    # by number, diameters within the bins
    BoxFactory(center=(5, 0, 0), extents=(1, 1, 0.2), normal=(1, 1, 0), massFlowRate=3000, PSDsizes=[0.02, 0.03, 0.05],
               PSDcum=[0.5, 1.0], PSDcalculateMass=False, exactDiam=False, vMin=1, vMax=2, maxParticles=-1,
               materialId=mat, label='binned'),
    # uniform radii in a cylinder along normal, at most 150 spheres
    CircularFactory(center=(0, 5, 0), radius=1, length=0.5, normal=(0, 1, 1), massFlowRate=3000, rMin=0.01, rMax=0.03,
                    vMin=2, vMax=3, normalVel=(1, 0, 0), maxParticles=150, materialId=mat, label='disc'),
]
O.dt = 1e-4
O.run(30, True)
for f in O.engines[4:]:
    made = [b for b in O.bodies if b.id in f.ids]
    out[f.label] = {
        "counts": [f.numParticles, f.totalMass, f.goalMass, f.totalVolume, len(f.ids)],
        "radii": sorted(b.shape.radius for b in made),
        "speeds": [b.state.vel.norm() for b in made],
        "directions": [list(b.state.vel / b.state.vel.norm()) for b in made],
        "positions": [list(b.state.pos) for b in made],
    }

# DomainLimiter: spheres and a clump leaving a box, every 20 steps.
O.reset()
O.bodies.append([sphere((0.1 * i, 0, 0), 0.04) for i in range(10)])
clump, members = O.bodies.appendClumped([sphere((0, 1, 0), 0.05), sphere((0.07, 1, 0), 0.05)])
for i in range(10):
    O.bodies[i].state.vel = (0, 0, (i - 4.5) * 2)
O.bodies[clump].state.vel = (0, 3, 0)
O.engines = [ForceResetter(), NewtonIntegrator(damping=0),
             DomainLimiter(lo=(-1, -1, -2), hi=(2, 1.5, 3), iterPeriod=20, label='limiter')]
O.dt = 1e-2
tallies = []
for k in range(6):
    O.run(10, True)
    tallies.append([limiter.nDeleted, limiter.mDeleted, limiter.vDeleted, sorted(b.id for b in O.bodies)])
out["limiter"] = tallies
print("RESULT " + json.dumps(out))
