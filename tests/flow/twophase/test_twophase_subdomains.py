"""UnsaturatedEngine's measures of parts of the packing (getCuboidSubdomainSaturation,
getCuboidSubdomainPorosity, getSphericalSubdomainSaturation, getInvadeDepth) along the drainage of
cases/yade/twophase/twophase_subdomains.py on the 400-sphere cloud of data/pore_packing.txt, against Yade
2023.02a's run of it (data/twophase_subdomains_yade_reference.json, written by
twophase_subdomains_yade_reference.py), and bad input."""
import json
from pathlib import Path

import numpy as np
import pytest

from talus import twin
from talus.flow import UnsaturatedEngine

HERE = Path(__file__).resolve().parent
PACKING = HERE.parent / "data" / "pore_packing.txt"
REF = json.loads((HERE.parent / "data" / "twophase_subdomains_yade_reference.json").read_text())
SCENARIO = HERE.parents[2] / "cases" / "yade" / "twophase" / "twophase_subdomains.py"
SPHERES = np.loadtxt(PACKING)


def test_measures_as_yade():
    """Each measure after each drainage step as Yade's: the saturations and porosities to
    round-off (1e-12 with the wall pores, whose volumes differ by that), the invasion depth to
    1e-4 (the centres of the pores on the ymax wall, where the two differ by 5e-5)."""
    ours = twin.run(SCENARIO, {**REF["params"], "packing": str(PACKING)}, "talus")
    for key in ("saturation", "cuboid", "cuboidSides", "porosity", "porositySides", "sphere"):
        np.testing.assert_allclose(ours[key], REF[key], rtol=0, atol=1e-12, err_msg=key)
    np.testing.assert_allclose(ours["depth"], REF["depth"], rtol=0, atol=1e-4)
    for key in ("cuboid", "sphere", "depth"):   # the measures follow the invasion
        assert max(REF[key]) - min(REF[key]) > 0.5, key


def test_bad_input():
    tp = UnsaturatedEngine(bndCondIsPressure=[0, 0, 1, 1, 0, 0])
    tp.triangulate(SPHERES[:, :3], SPHERES[:, 3], ids=np.arange(6, 6 + len(SPHERES)))
    tp.initialization()
    lo, hi = SPHERES[:, :3].min(axis=0), SPHERES[:, :3].max(axis=0)
    with pytest.raises(ValueError, match="no pore has its centre in the cuboid"):
        tp.getCuboidSubdomainSaturation(lo - 1, lo - 0.5)
    with pytest.raises(ValueError, match="getSphericalSubdomainSaturation: the sphere of radius .* reaches pores touching a wall"):
        tp.getSphericalSubdomainSaturation((lo + hi) / 2, float(np.max(hi - lo)))
    with pytest.raises(ValueError, match="no pore has its centre within radius"):
        tp.getSphericalSubdomainSaturation((lo + hi) / 2, 1e-9)
