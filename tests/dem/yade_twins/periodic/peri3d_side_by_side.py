"""Yade's Peri3dController on a dense periodic packing (periodic_packing.json), written so that
the same file runs in Yade (`yade -n -x`) and in Talus: an all-stress stage (first step through
the compliance estimate, then the predictor), then a mixed stage (strains and stresses, multi-
point paths in relative and absolute values, shear, rates capped by maxStrainRate) continuing
from the first one's strain and ideal stress. Prints, every step, the controller's stress,
strain, progress and the cell's trsf (one RESULT line, talus.twin). Parameter
(TALUS_SCENARIO) "case": "stress" (the two stages above) or "strain" (every component strain-
controlled, multi-point paths, shear, rates capped)."""
import json
import os
import sys

try:
    O  # noqa: B018  (defined when Yade runs the script)
except NameError:
    from talus.dem import *  # noqa: F401,F403

sys.path.insert(0, os.path.dirname(os.path.abspath(sys.argv[0])))   # packing_scene.py, under Yade's -x too
from packing_scene import load_packing  # noqa: E402

load_packing()
O.dt = 2e-5
rows, hooks = [], []


def record():
    rows.append(list(p3d.stress) + list(p3d.strain) + [p3d.progress] + [O.cell.trsf[i, j] for i in range(3) for j in range(3)])


def engines(controller):
    return [ForceResetter(), InsertionSortCollider([Bo1_Sphere_Aabb()]),
            InteractionLoop([Ig2_Sphere_Sphere_ScGeom()], [Ip2_FrictMat_FrictMat_FrictPhys()],
                            [Law2_ScGeom_FrictPhys_CundallStrack()]),
            NewtonIntegrator(damping=0.2), controller, PyRunner(command='record()', iterPeriod=1)]


case = json.loads(os.environ.get("TALUS_SCENARIO", "{}")).get("case", "stress")
if case == "strain":
    O.engines = engines(Peri3dController(goal=(-2e-3, 1e-3, -3e-3, 1e-3, 0, 4e-3), stressMask=0, nSteps=300,
                                         maxStrainRate=0.8, xxPath=[(1, -1), (2, 1), (3, 1)],
                                         yyPath=[(2, 4), (7, -2), (11, 1)], zxPath=[(1, 5e-4), (3, 0)],
                                         xyPath=[(1, 1), (2, -1), (3, 1)], label='p3d'))
    O.run(1500, True)
else:
    O.engines = engines(Peri3dController(goal=(-2e4, -2e4, -3e4, 0, 0, 0), stressMask=0b111111, nSteps=150,
                                         youngEstimation=5e6, doneHook='hooks.append(O.iter); O.pause()', label='p3d'))
    O.run(400, True)
    O.engines = engines(Peri3dController(goal=(-2e4, 4e-3, -3e-3, 0, 1e3, 6e-3), stressMask=0b010001, nSteps=200,
                                         maxStrainRate=1.2, mod=0.2, xxPath=[(0, 1), (1, 1)],
                                         yyPath=[(2, 4), (7, -2), (11, 1)], zxPath=[(1, 5e2), (3, 0)],
                                         xyPath=[(1, 1), (2, -1), (3, 1)], strain=p3d.strain,
                                         stressIdeal=p3d.stressIdeal, label='p3d'))
    O.run(400, True)
print("RESULT " + json.dumps({"rows": rows, "hooks": hooks, "dead": p3d.dead, "iter": O.iter,
                              "xyPath": [list(p) for p in p3d.xyPath]}))
