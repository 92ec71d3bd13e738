"""Yade's force and kinematic engines on a few free bodies, written so that the same file runs in
Yade (`yade -n -x`) and in Talus: ForceEngine, HarmonicForceEngine,
InterpolatingDirectedForceEngine (wrapped table), engine + engine (CombinedKinematicEngine),
InterpolatingHelixEngine. Prints the bodies' positions every 200 steps (one RESULT line)."""
import json

try:
    O  # noqa: B018  (defined when Yade runs the script)
except NameError:
    from talus.dem import *  # noqa: F401,F403

ids = O.bodies.append([sphere((0, 0, 0), 0.1), sphere((1, 0, 0), 0.1), sphere((2, 0, 0), 0.1),
                       sphere((3, 0, 0), 0.1), sphere((4, 0.5, 0), 0.1)])
O.engines = [
    ForceResetter(),
    ForceEngine(ids=[ids[0]], force=(1.0, -2.0, 0.5)),
    HarmonicForceEngine(ids=[ids[1]], A=(3.0, 2.0, 1.0), f=(5.0, 7.0, 11.0), fi=(0.1, 0.2, 0.3)),
    InterpolatingDirectedForceEngine(ids=[ids[2]], times=[0, 0.01, 0.03, 0.05], magnitudes=[0, 5, -2, 1],
                                     direction=(1, 1, 0), wrap=True),
    TranslationEngine(ids=[ids[3]], translationAxis=(0, 0, 1), velocity=0.3)
    + RotationEngine(rotationAxis=(0, 1, 0), angularVelocity=2.0, rotateAroundZero=True, zeroPoint=(2.5, 0, 0)),
    InterpolatingHelixEngine(ids=[ids[4]], times=[0, 0.02, 0.04], angularVelocities=[1, 4, -2], rotationAxis=(0, 0, 1),
                             zeroPoint=(4, 0, 0), wrap=True, slope=0.05),
    NewtonIntegrator(damping=0.0),
]
O.dt = 1e-5
positions = []
for k in range(20):
    O.run(500, True)
    positions.append([float(x) for i in ids for x in O.bodies[i].state.pos])
print("RESULT " + json.dumps(positions))
