"""A ready-to-run FEM x DEM biaxial test (mesh -> RVEs -> driver), written into a folder:
``talus case femxdem --out DIR`` or :func:`biaxial_study`."""

from __future__ import annotations

import json
import shutil
from pathlib import Path

__all__ = ["biaxial_study"]


def biaxial_study(out, *, cells=(2, 4), size=(1.0, 2.0), confinement: float = 1e5, axialStrain: float = 0.015,
                  steps: int = 6, demSteps: int = 40, rveSize: float = 1.2, rMean: float = 0.1,
                  friction: float = 0.5, young: float = 1e8, seed: int = 1) -> Path:
    """Write ``out/femxdem.py`` (the study, talus.fem.biaxial_study) and ``out/study.json``
    (these inputs); returns the script's path. Run it with ``talus run out/femxdem.py``.

    Args:
        cells: quadrilaterals across and along the sample; size: its width and height [m].
        confinement: the lateral stress and the RVE's consolidation stress [Pa], positive.
        axialStrain: the final axial strain (compression positive), reached in ``steps`` load
            steps; demSteps: DEM steps per Gauss-point call.
        rveSize, rMean, friction, young, seed: the RVE packing (talus.fem.prepareRVE).
    """
    cells = [int(n) for n in cells]
    size = [float(s) for s in size]
    if len(cells) != 2 or min(cells) < 1 or len(size) != 2 or min(size) <= 0:
        raise ValueError(f"biaxial_study: cells {cells} and size {size}: two positive numbers each")
    for name, value in (("confinement", confinement), ("axialStrain", axialStrain), ("rveSize", rveSize),
                        ("rMean", rMean), ("young", young)):
        if not value > 0:
            raise ValueError(f"biaxial_study: {name} must be positive, got {value}")
    if int(steps) < 1 or int(demSteps) < 1:
        raise ValueError(f"biaxial_study: steps ({steps}) and demSteps ({demSteps}) must be at least 1")
    if rveSize < 6 * rMean:
        raise ValueError(f"biaxial_study: rveSize {rveSize} holds too few spheres of rMean {rMean} (at least 6 rMean)")
    out = Path(out)
    out.mkdir(parents=True, exist_ok=True)
    study = dict(cells=cells, size=size, confinement=float(confinement), axialStrain=float(axialStrain),
                 steps=int(steps), demSteps=int(demSteps), rveSize=float(rveSize), rMean=float(rMean),
                 friction=float(friction), young=float(young), seed=int(seed))
    (out / "study.json").write_text(json.dumps(study, indent=2) + "\n")
    script = out / "femxdem.py"
    shutil.copyfile(Path(__file__).with_name("biaxial_study.py"), script)
    return script
