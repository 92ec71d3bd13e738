"""yade.bodiesHandling and utils.getSpheresVolume/getSpheresMass, written so that the same file
runs in Yade (`yade -n -x`) and in Talus: the extent of spheres given as ids and as bodies (a
facet among them is skipped) or chosen by mask, of facets, and moved, turned and scaled copies. Prints one RESULT
line (tests/yade/test_bodies_handling.py)."""
import json

try:
    O  # noqa: B018  (defined when Yade runs the script)
except NameError:
    from talus.dem import *  # noqa: F401,F403
from yade import bodiesHandling, geom, utils


def plain(d):
    return {k: (list(v) if hasattr(v, "__len__") else v) for k, v in d.items()}


O.materials.append(FrictMat(density=2000))
ids = O.bodies.append([sphere((0.3 * i, 0.1 * i * i, -0.2 * i), 0.1 + 0.02 * i, mask=1 + i % 3) for i in range(6)])
facets = O.bodies.append(geom.facetBox((1, 2, 3), (0.5, 0.7, 0.9)))
out = {"ids": plain(bodiesHandling.spheresPackDimensions(ids + facets[:1])),
       "bodies": plain(bodiesHandling.spheresPackDimensions([O.bodies[i] for i in ids[2:]])),
       "facets": plain(bodiesHandling.facetsDimensions(facets)),
       "volume": utils.getSpheresVolume(), "mass": utils.getSpheresMass()}
copies = bodiesHandling.spheresModify(ids[:4], shift=(1, 0, 0), scale=1.5, orientation=Quaternion((0, 0, 1), 0.3),
                                      copy=True)
O.bodies.append(copies)
out["masks"] = [[utils.getSpheresVolume(mask=m), utils.getSpheresMass(mask=m)] for m in (-1, 0, 1, 2, 4)]
out["by mask"] = plain(bodiesHandling.spheresPackDimensions(mask=2))
out["list and mask"] = plain(bodiesHandling.spheresPackDimensions(ids, mask=1))
out["copies"] = [list(b.state.pos) + [b.shape.radius, b.state.mass] for b in copies]
out["moved"] = bodiesHandling.spheresModify(ids[4:], shift=(0, 0, 2), orientation=Quaternion((1, 0, 0), 0.5))
out["after"] = [list(O.bodies[i].state.pos) for i in ids]
print("RESULT " + json.dumps(out))
