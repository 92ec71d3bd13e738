"""A permeability study, written into a folder with its inputs (study.json beside it) by
``talus case permeability`` (talus.flow.case_builder.permeability_study): edit either freely.

Run:      build/bin/talus run permeability.py   (in the folder it was written to)
What:     for each porosity of study.json, a periodic cloud of `spheres` spheres (radii uniform
          within rMean (1 +- rRelFuzz)) compressed homothetically to that porosity
          (talus.dem.packing.pack.compressedCloud, frictionless), then PeriodicFlowEngine on the periodic
          packing with a unit macroscopic pressure gradient along `axis`: K = -mu <v> / gradP.
Produces: permeability.csv (porosity, K, K / d32^2, Kozeny-Carman's K, their ratio) and
          permeability.png (K / d32^2 against the porosity, with Kozeny-Carman
          d32^2 n^3 / (180 (1 - n)^2)) beside this script.
"""
import json
from pathlib import Path

import numpy as np

from talus.dem.packing.pack import compressedCloud
from talus.flow import PeriodicFlowEngine

HERE = Path(__file__).resolve().parent


def packing_permeability(porosity: float, study: dict) -> dict:
    """One packing at ``porosity`` and its permeability along the study's axis."""
    packing = compressedCloud((0, 0, 0), (1, 1, 1), rRelFuzz=study["rRelFuzz"], num=study["spheres"],
                              seed=study["seed"], stress=None, porosity=porosity, maxUnbalanced=0.5)
    centres = np.array([c for c, _ in packing])
    radii = np.array([r for _, r in packing])
    gradient = [0.0, 0.0, 0.0]
    gradient[study["axis"]] = 1.0
    flow = PeriodicFlowEngine(gradP=gradient, viscosity=study["viscosity"],
                              duplicateThreshold=study["duplicateThreshold"] * float(np.max(packing.cellSize)))
    flow.triangulate(centres, radii, cellSize=packing.cellSize)
    flow.solve()
    n = 1 - float(np.sum(4 / 3 * np.pi * radii ** 3) / np.prod(packing.cellSize))
    d32 = float(2 * np.sum(radii ** 3) / np.sum(radii ** 2))
    k = flow.samplePermeability()
    k_kc = d32 ** 2 * n ** 3 / (180 * (1 - n) ** 2)
    return dict(porosity=n, K=k, K_over_d32sq=k / d32 ** 2, K_kozeny_carman=k_kc, K_over_KC=k / k_kc,
                pores=flow.nCells())


def main():
    study = json.loads((HERE / "study.json").read_text())
    rows = []
    for target in study["porosities"]:
        row = packing_permeability(target, study)
        rows.append(row)
        print(f"porosity {row['porosity']:.3f}: K = {row['K']:.4e} (K/d32^2 {row['K_over_d32sq']:.3e}), "
              f"{row['K_over_KC']:.3f} x Kozeny-Carman, {row['pores']} pores", flush=True)
    columns = list(rows[0])
    lines = [",".join(columns)] + [",".join(f"{row[c]:.8g}" for c in columns) for row in rows]
    (HERE / "permeability.csv").write_text("\n".join(lines) + "\n")

    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, ax = plt.subplots(figsize=(5.5, 4))
    n = np.linspace(min(r["porosity"] for r in rows) - 0.02, max(r["porosity"] for r in rows) + 0.02, 100)
    ax.semilogy(n, n ** 3 / (180 * (1 - n) ** 2), "k-", label="Kozeny-Carman")
    ax.semilogy([r["porosity"] for r in rows], [r["K_over_d32sq"] for r in rows], "o", label="Talus pore flow")
    ax.set_xlabel("porosity n")
    ax.set_ylabel("K / d32$^2$")
    ax.set_title(f"Permeability of {study['spheres']} spheres (rRelFuzz {study['rRelFuzz']})")
    ax.legend()
    fig.tight_layout()
    fig.savefig(HERE / "permeability.png", dpi=110)
    print(f"wrote {HERE / 'permeability.csv'} and {HERE / 'permeability.png'}")


if __name__ == "__main__":
    main()
