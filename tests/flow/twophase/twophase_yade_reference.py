# Yade side of the two-phase tests (tests/flow/twophase/test_twophase.py): run with
#   cd tests/flow/twophase && yade -n -x twophase_yade_reference.py
# On the 400-sphere cloud of data/pore_packing.txt in the walls of its bounding box, Yade's
# TwoPhaseFlowEngine (wetting reservoir ymin, non-wetting ymax at 0, surfaceTension 0.0728) for
# each entry-pressure method and with and without trapping: the saturation after invasion() at
# each capillary pressure of a drainage then (MS-P, trapped) an imbibition; the capillary forces
# (computeCapillaryForce, fluidForce) of a few spheres mid-drainage; the saturation with the
# boundary pores (getSaturation(True)) after the drainage; the pore-body radii of all pores; the
# MS-P and inscribed radii of a few sphere triplets (getMSPRcByPosRadius, getEffRcByPosRadius);
# drainages with isInvadeBoundary or recursiveInvasion off and an imbibition from a non-wetting
# start. Written as JSON to
# data/twophase_yade_reference.json.
import json
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(sys.argv[0])), "..", "..", "..", "cases", "yade", "twophase"))
from twophase_scene import invade, read_spheres, reservoir_engine  # noqa: E402

spheres, lo, hi = read_spheres("../data/pore_packing.txt")
GAMMA = 0.0728
PCS = [GAMMA / 0.1 * (0.2 + 0.1 * i) for i in range(40)]  # pc d / gamma from 0.2 to 4.1, d the mean diameter
FORCE_STEP = 20                                            # forces after this many drainage steps
FORCE_BODIES = [6, 50, 100, 200, 300, 405]


def engine(method, trapped):
    tp = reservoir_engine(spheres, lo, hi, surfaceTension=GAMMA, entryPressureMethod=method, isPhaseTrapped=trapped)
    tp.initialization()
    return tp


tp = engine(1, True)
bodyRadii = {" ".join(map(str, sorted(tp.getVertices(i)))): tp.getCellInSphereRadius(i) for i in range(tp.nCells())}
runs = {}
forces = {}
for method in (1, 2, 3):
    for trapped in (True, False):
        tp = engine(method, trapped)
        drainage, imbibition = invade(tp, PCS[:FORCE_STEP]), []
        if method == 1 and trapped:
            tp.computeCapillaryForce()
            forces = {str(b): list(tp.fluidForce(b)) for b in FORCE_BODIES}
        drainage += invade(tp, PCS[FORCE_STEP:])
        sideIncluded = tp.getSaturation(True)
        if method == 1:
            tp.isDrainageActivated = False
            tp.isImbibitionActivated = True
            imbibition = invade(tp, reversed(PCS))
        runs[f"{method}-{int(trapped)}"] = {"drainage": drainage, "imbibition": imbibition,
                                           "sideIncluded": sideIncluded, "nCells": tp.nCells()}

# option variants of the drainage (MS-P, trapped): attribute settings -> saturations; the last
# starts non-wetting and imbibes with decreasing capillary pressure
variants = {}
for name, attrs, pcs in (("isInvadeBoundary=0", {"isInvadeBoundary": False}, PCS),
                         ("recursiveInvasion=0", {"recursiveInvasion": False}, PCS),
                         ("drainageFirst=0", {"drainageFirst": False, "isDrainageActivated": False,
                                              "isImbibitionActivated": True}, PCS[::-1])):
    tp = reservoir_engine(spheres, lo, hi, surfaceTension=GAMMA, **attrs)
    tp.initialization()
    variants[name] = {"attrs": attrs, "pcs": pcs, "saturations": invade(tp, pcs)}

triplets = [((0, 0, 0), 1.0, (2, 0, 0), 1.0, (1, 3 ** 0.5, 0), 1.0),
            ((0, 0, 0), 1.0, (2.2, 0, 0), 0.9, (1.1, 1.9, 0.2), 1.1),
            ((0, 0, 0), 0.5, (1.4, 0.1, 0), 0.7, (0.6, 1.3, 0), 0.6)]
radii = [{"msp": tp.getMSPRcByPosRadius(Vector3(*a), ra, Vector3(*b), rb, Vector3(*c), rc),
          "inscribed": tp.getEffRcByPosRadius(Vector3(*a), ra, Vector3(*b), rb, Vector3(*c), rc),
          "spheres": [a, ra, b, rb, c, rc]} for a, ra, b, rb, c, rc in triplets]
json.dump({"surfaceTension": GAMMA, "pcs": PCS, "runs": runs, "forceStep": FORCE_STEP, "forces": forces,
           "triplets": radii, "bodyRadii": bodyRadii, "variants": variants}, open("../data/twophase_yade_reference.json", "w"), indent=1)
print("written", {k: v["drainage"][-1] for k, v in runs.items()})
