# A drainage from a state a script sets pore by pore, one script for both programs: run by
# talus.twin.run(script, params, "yade" or "talus") with the parameters as JSON in $TALUS_SCENARIO:
#   packing       sphere file (x y z r per line)
#   pcs           the capillary pressures of the drainage steps
#   every         [b, t, n]: the strides of the pores changed below (0: none)
# TwoPhaseFlowEngine (MS-P, trapped phases) on the spheres in the walls of their bounding box
# (wetting reservoir ymin, non-wetting ymax). Pores are taken in the order of their names (their
# sorted vertex ids; the network's pore numbering is each program's own), those between four
# spheres only: every b-th gets half its pore-body radius (setPoreBodyRadius), every t-th doubles
# the entry radius of its throat to its first neighbour (by name) between spheres (setPoreThroatRadius),
# every n-th is made non-wetting and part of the non-wetting reservoir (setCellSaturation,
# setCellIsNWRes, setCellIsWRes), then updatePressure() and invasion() at each capillary pressure.
# Printed as one line `RESULT {json}`: the saturation after each step, the pores' pressures after
# updatePressure() and every pore's saturation at the end, by name.
import json
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(sys.argv[0])))   # twophase_scene.py, under Yade's -x too
from twophase_scene import invade, read_spheres, reservoir_engine  # noqa: E402

params = json.loads(os.environ["TALUS_SCENARIO"])
spheres, lo, hi = read_spheres(params["packing"])
flow = reservoir_engine(spheres, lo, hi, surfaceTension=0.0728)
flow.initialization()
name = {i: " ".join(map(str, sorted(flow.getVertices(i)))) for i in range(flow.nCells())}
inner = sorted((i for i in name if min(flow.getVertices(i)) >= 6), key=name.get)
body, throat, nonWetting = params["every"]
for k, pore in enumerate(inner):
    if body and k % body == 0:
        flow.setPoreBodyRadius(pore, 0.5 * flow.getCellInSphereRadius(pore))
    if throat and k % throat == 0:
        others = sorted((n for n in flow.getNeighbors(pore) if n in name and min(flow.getVertices(n)) >= 6), key=name.get)
        if others:
            flow.setPoreThroatRadius(pore, others[0], 2 * flow.getPoreThroatRadius(pore, others[0]))
    if nonWetting and k % nonWetting == 0:
        flow.setCellSaturation(pore, 0.0)
        flow.setCellIsNWRes(pore, True)
        flow.setCellIsWRes(pore, False)
flow.bndCondValue = [0, 0, -params["pcs"][0], 0, 0, 0]
flow.updatePressure()
pressures = {name[i]: flow.getCellPressure(i) for i in inner[::5]}
saturations = invade(flow, params["pcs"])
print("RESULT " + json.dumps({"saturations": saturations, "pressures": pressures,
                              "cells": {name[i]: flow.getCellSaturation(i) for i in name}}))
