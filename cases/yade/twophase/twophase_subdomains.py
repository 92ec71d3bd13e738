# UnsaturatedEngine's measures of parts of a packing along a drainage, one script for both
# programs: run by talus.twin.run(script, params, "yade" or "talus") with the parameters as JSON in
# $TALUS_SCENARIO:
#   packing       sphere file (x y z r per line)
#   pcs           the capillary pressures of the drainage steps
# UnsaturatedEngine (MS-P, trapped phases) on the spheres in the walls of their bounding box
# (wetting reservoir ymin, non-wetting ymax); after invasion() at each capillary pressure: the
# saturation, the saturation and porosity of the middle half of the box (getCuboidSubdomainSaturation,
# getCuboidSubdomainPorosity, without and with the pores touching the walls), the saturation of the
# sphere of radius a quarter of the box's smallest side at its centre
# (getSphericalSubdomainSaturation) and the invasion depth (getInvadeDepth). Printed as one line
# `RESULT {json}` of these lists.
import json
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(sys.argv[0])))   # twophase_scene.py, under Yade's -x too
from twophase_scene import read_spheres, reservoir_engine  # noqa: E402
from yade import UnsaturatedEngine  # noqa: E402
from yade.minieigenHP import Vector3  # noqa: E402

params = json.loads(os.environ["TALUS_SCENARIO"])
spheres, lo, hi = read_spheres(params["packing"])
flow = reservoir_engine(spheres, lo, hi, engine=UnsaturatedEngine, surfaceTension=0.0728)
flow.initialization()
quarter = [lo[k] + (hi[k] - lo[k]) / 4 for k in range(3)]
threeQuarters = [lo[k] + 3 * (hi[k] - lo[k]) / 4 for k in range(3)]
centre = Vector3(*[(lo[k] + hi[k]) / 2 for k in range(3)])
radius = min(hi[k] - lo[k] for k in range(3)) / 4
out = {key: [] for key in ("saturation", "cuboid", "cuboidSides", "porosity", "porositySides", "sphere", "depth")}
for pc in params["pcs"]:
    flow.bndCondValue = [0, 0, -pc, 0, 0, 0]
    flow.invasion()
    out["saturation"].append(flow.getSaturation(False))
    out["cuboid"].append(flow.getCuboidSubdomainSaturation(Vector3(*quarter), Vector3(*threeQuarters), False))
    out["cuboidSides"].append(flow.getCuboidSubdomainSaturation(Vector3(*lo), Vector3(*hi), True))
    out["porosity"].append(flow.getCuboidSubdomainPorosity(Vector3(*quarter), Vector3(*threeQuarters), False))
    out["porositySides"].append(flow.getCuboidSubdomainPorosity(Vector3(*lo), Vector3(*hi), True))
    out["sphere"].append(flow.getSphericalSubdomainSaturation(centre, radius))
    out["depth"].append(flow.getInvadeDepth())
print("RESULT " + json.dumps(out))
