"""Scenario: the seed's bouncing-sphere tutorial (01-bouncing-sphere: a sphere falling on a fixed
one, FrictMat defaults, damping 0.1), written so that the same file runs in Yade (`yade -n -x`)
and in Talus (`talus run`); `steps` from $TALUS_SCENARIO (JSON, default 30001). Prints the height
of the falling sphere after 101, 201, 301, ... integrations (a PyRunner after the integrator, first
run at iteration 100) as one `RESULT {json}` line (see talus.twin)."""
import json
import os

try:
    O  # noqa: B018  (defined when Yade runs the script)
except NameError:
    from talus.dem import *  # noqa: F401,F403

P = {"steps": 30001, **json.loads(os.environ.get("TALUS_SCENARIO", "{}"))}

O.bodies.append([sphere((0, 0, 0), 0.5, fixed=True), sphere((0, 0, 2), 0.5)])
O.engines = [
    ForceResetter(),
    InsertionSortCollider([Bo1_Sphere_Aabb()]),
    InteractionLoop([Ig2_Sphere_Sphere_ScGeom()], [Ip2_FrictMat_FrictMat_FrictPhys()],
                    [Law2_ScGeom_FrictPhys_CundallStrack()]),
    NewtonIntegrator(gravity=(0, 0, -9.81), damping=0.1),
    PyRunner(command="heights.append(O.bodies[1].state.pos[2])", iterPeriod=100),
]
O.dt = 5e-5  # 0.01 PWaveTimeStep(), written out so both programs use the same bits
heights = []
O.run(P["steps"], True)
print("RESULT " + json.dumps({"dt": O.dt, "z": heights}))
