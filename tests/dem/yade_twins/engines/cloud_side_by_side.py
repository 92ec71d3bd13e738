"""Seeded makeCloud calls, written so that the same file runs in Yade (`yade -n -x`) and in Talus:
prints every cloud's centres and radii as JSON (one CLOUDS line)."""
import json

try:
    O  # noqa: B018  (defined when Yade runs the script)
    from yade import pack
except NameError:
    from talus.dem import *  # noqa: F401,F403

CALLS = {
    "box": dict(minCorner=(0, 0, 0), maxCorner=(1, 1, 1), rMean=.1, rRelFuzz=.3, seed=1),
    "shifted-box-num": dict(minCorner=(-1, 2, 0.5), maxCorner=(0, 3.5, 1.5), rMean=.08, rRelFuzz=.5, num=60, seed=7),
    "periodic": dict(minCorner=(0, 0, 0), maxCorner=(2, 1, 1.5), rMean=.12, rRelFuzz=.4, periodic=True, seed=3),
    "porosity": dict(minCorner=(0, 0, 0), maxCorner=(1, 1, 1), rRelFuzz=.2, num=200, porosity=.7, seed=11),
    "psd-mass": dict(minCorner=(0, 0, 0), maxCorner=(1, 1, 1), psdSizes=[.05, .1, .2], psdCumm=[0, .3, 1],
                     distributeMass=True, num=100, seed=5),
    "flat": dict(minCorner=(0, 0, 0), maxCorner=(1, 1, 0), rMean=.05, rRelFuzz=.2, seed=2),
    # a sheared cell (Yade's hSize), moderately: Yade's one-image overlap test is still exact
    "sheared": dict(minCorner=(0.1, 0, 0.2), rMean=.09, rRelFuzz=.3, periodic=True, seed=4,
                    hSize=Matrix3(1, .3, 0, 0, 1.2, -.2, 0, 0, .9)),
}
out = {}
for name, kw in CALLS.items():
    sp = pack.SpherePack()
    n = sp.makeCloud(**kw)
    out[name] = {"n": n, "spheres": [[float(c[0]), float(c[1]), float(c[2]), float(r)] for c, r in sp],
                 "scaling": float(sp.appliedPsdScaling) if hasattr(sp, "appliedPsdScaling") else 1.0}
print("RESULT " + json.dumps(out))
