"""A ready-to-run permeability study (packing -> pore flow -> permeability table), written into
a folder: ``talus case permeability --out DIR`` or :func:`permeability_study`."""

from __future__ import annotations

import json
import shutil
from pathlib import Path

__all__ = ["permeability_study"]


def permeability_study(out, *, porosities=(0.36, 0.40, 0.44), spheres: int = 400, rRelFuzz: float = 0.3,
                       axis: int = 1, viscosity: float = 1.0, seed: int = 1,
                       duplicateThreshold: float = 0.25) -> Path:
    """Write ``out/permeability.py`` (the study, talus.flow.permeability_study) and
    ``out/study.json`` (these inputs); returns the script's path. Run it with
    ``talus run out/permeability.py``: it writes ``permeability.csv`` and ``permeability.png``.

    Args:
        porosities: the packings' porosities (each between 0.34, near jamming, and 0.6).
        spheres: spheres per periodic packing; rRelFuzz: radii uniform in rMean (1 +- rRelFuzz).
        axis: the flow direction (0, 1, 2); viscosity [Pa s]; seed: the packings' random seed.
        duplicateThreshold: the periodic images kept around the cell, as a fraction of its size.
    """
    porosities = [float(n) for n in porosities]
    bad = [n for n in porosities if not 0.34 <= n <= 0.6]
    if not porosities or bad:
        raise ValueError(f"permeability_study: porosities {porosities}: give at least one, each within "
                         "[0.34, 0.6] (denser packings jam before they reach it)")
    if int(spheres) < 50:
        raise ValueError(f"permeability_study: spheres must be at least 50 (a periodic cell of a few pores "
                         f"has no meaningful permeability), got {spheres}")
    if axis not in (0, 1, 2):
        raise ValueError(f"permeability_study: axis must be 0, 1 or 2, got {axis}")
    if not 0 <= rRelFuzz < 1 or not viscosity > 0 or not duplicateThreshold > 0:
        raise ValueError("permeability_study: rRelFuzz must be in [0, 1), viscosity and duplicateThreshold positive")
    out = Path(out)
    out.mkdir(parents=True, exist_ok=True)
    study = dict(porosities=porosities, spheres=int(spheres), rRelFuzz=float(rRelFuzz), axis=int(axis),
                 viscosity=float(viscosity), seed=int(seed), duplicateThreshold=float(duplicateThreshold))
    (out / "study.json").write_text(json.dumps(study, indent=2) + "\n")
    script = out / "permeability.py"
    shutil.copyfile(Path(__file__).with_name("permeability_study.py"), script)
    return script
