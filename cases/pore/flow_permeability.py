"""Pore-scale flow case: permeability of sphere packings over porosity and size distribution,
against Kozeny-Carman and against Yade's FlowEngine on the identical packings.

Run:      build/bin/talus run cases/pore/flow_permeability.py [--quick] [--results DIR]
Set-up:   periodic clouds (Yade's makeCloud, fixed seeds) of two size distributions -- narrow
          (rRelFuzz 0.1) and wide (rRelFuzz 0.5, uniform radii from 0.5 to 1.5 rMean) --
          compressed homothetically (talus.dem.packing.pack.compressedCloud, frictionless) to cell
          porosities from 0.34 to 0.45 (quick: three), then taken out of the periodic cell
          (centres wrapped into it) and put between six walls on the cell's faces
          (boundaryUseMaxMin off; the walls cut the spheres crossing them, so that the sample has
          the cell's porosity -- the packing's bounding box would add a loose layer of a radius
          on every side, porosity 0.6 for a few hundred spheres). Pressure dp = 1 on ymin, 0 on ymax, no flux elsewhere, viscosity 1:
          K = Q mu L / (A dp) from the inlet flux getBoundaryFlux(2) and the box. The same
          packing also in its periodic cell (PeriodicFlowEngine, gradP (0, 1, 0), no walls):
          K = -mu <v_y> / gradP_y.
Checked:  - against Yade 2023.02a's FlowEngine (CHOLMOD) on the same sphere files, run by
            cases/yade/pore_flow.py in the same invocation: worst relative difference of K over
            all packings <= 1 % (record flow.permeability.yade); skipped (no record) without yade;
          - against Kozeny-Carman K_KC = d32^2 n^3 / (180 (1 - n)^2) with the Sauter diameter d32
            and the sample's porosity n (solid volume inside the walls): worst |ln(K / K_KC)| reported, bound ln 3 (the PFV model
            is known to sit within a small factor of Kozeny-Carman; a bug in the conductances or
            the flux shows up as orders of magnitude).
          - the periodic K against Yade's PeriodicFlowEngine on the same files and cells (record
            flow.permeability.periodic-yade, <= 1 %), and the box K against the periodic K of
            the same packing (record flow.permeability.periodic-vs-box: |ln ratio| <= ln 2; measured
            1.3-1.8 with 600 spheres: the looser layers the walls leave along the lateral faces).
Produces: records flow.permeability.yade and flow.permeability.kozeny-carman (per-packing
          numbers in the records' `packings`); chart flow.permeability.png (K / d32^2 against
          porosity, both distributions, Talus, Yade and Kozeny-Carman).
"""
import tempfile
import time
from pathlib import Path

import numpy as np

from talus import results
from talus import twin
from talus.dem.packing.pack import SpherePack, compressedCloud
from talus.flow import FlowEngine, PeriodicFlowEngine

DISTRIBUTIONS = {"narrow": 0.1, "wide": 0.5}
YADE_SCRIPT = Path(__file__).resolve().parents[1] / "yade" / "pore_flow.py"
YADE_PERIODIC = Path(__file__).resolve().parents[1] / "yade" / "pore_flow_periodic.py"
THRESHOLD = 0.25  # duplicateThreshold: images within 0.25 of the unit cell (2-3 diameters)


def make_packing(fuzz: float, porosity: float, num: int, seed: int):
    """A periodic packing compressed to the cell porosity: its spheres (centres wrapped into the
    cell) and the cell size."""
    try:
        periodic = compressedCloud((0, 0, 0), (1, 1, 1), rRelFuzz=fuzz, num=num, seed=seed, stress=None,
                                   porosity=porosity, maxUnbalanced=0.05, maxIter=40000)
    except RuntimeError:
        # near the jamming porosity the packing creeps for long: the flow only needs the
        # geometry, a looser equilibrium will do
        periodic = compressedCloud((0, 0, 0), (1, 1, 1), rRelFuzz=fuzz, num=num, seed=seed, stress=None,
                                   porosity=porosity, maxUnbalanced=0.5, maxIter=200000)
    return SpherePack([(c, r) for c, r in periodic]), periodic.cellSize


def solid_in_box(centers, radii, size):
    """Volume of the spheres inside the box [0, size]: each sphere minus its caps beyond the
    faces (a sphere crossing two faces at a corner counts the tiny corner overlap twice)."""
    volume = 4 / 3 * np.pi * radii ** 3
    for d in range(3):
        for depth in (radii - centers[:, d], radii - (size[d] - centers[:, d])):
            h = np.clip(depth, 0, None)
            volume -= np.pi * h ** 2 * (3 * radii - h) / 3
    return float(volume.sum())


def permeability(sp: SpherePack, size):
    """Talus's K along y in the box [0, size] (the periodic cell, walls cutting the spheres that
    cross it), the sample porosity and d32, and the time of triangulate + solve."""
    centers = np.array([c for c, _ in sp])
    radii = np.array([r for _, r in sp])
    flow = FlowEngine(bndCondIsPressure=[0, 0, 1, 1, 0, 0], bndCondValue=[0, 0, 1, 0, 0, 0],
                      boundaryUseMaxMin=[0] * 6, wallPosition=[0, size[0], 0, size[1], 0, size[2]])
    start = time.perf_counter()
    flow.triangulate(centers, radii)
    flow.solve()
    wall = time.perf_counter() - start
    porosity = 1 - solid_in_box(centers, radii, size) / np.prod(size)
    d32 = 2 * np.sum(radii ** 3) / np.sum(radii ** 2)
    return dict(K=flow.samplePermeability(2, 3), porosity=float(porosity), d32=float(d32),
                nCells=flow.nCells(), flux=flow.getBoundaryFlux(2), wall_s=wall)


def periodic_permeability(sp: SpherePack, size):
    """Talus's K along y of the periodic packing itself (PeriodicFlowEngine, gradP (0, 1, 0), no
    walls) and the time of triangulate + solve."""
    flow = PeriodicFlowEngine(gradP=(0, 1, 0), duplicateThreshold=THRESHOLD)
    radii = np.array([r for _, r in sp])
    start = time.perf_counter()
    flow.triangulate(np.array([c for c, _ in sp]), radii, cellSize=size)
    flow.solve()
    porosity = 1 - float(np.sum(4 / 3 * np.pi * radii ** 3)) / float(np.prod(size))
    return dict(K_periodic=flow.samplePermeability(), nCells_periodic=flow.nCells(), porosity_periodic=porosity,
                wall_periodic_s=time.perf_counter() - start)


def kozeny_carman(porosity: float, d32: float) -> float:
    return d32 ** 2 * porosity ** 3 / (180 * (1 - porosity) ** 2)


def main():
    args = results.case_arguments(__doc__).parse_args()
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    case = results.Case("flow.permeability", quick=args.quick, folder=args.results)
    targets = [0.33, 0.37, 0.41] if args.quick else [0.33, 0.35, 0.37, 0.39, 0.41, 0.43]
    num = 600 if args.quick else 2500
    rows = []
    with tempfile.TemporaryDirectory() as tmp:
        for name, fuzz in DISTRIBUTIONS.items():
            for n, target in enumerate(targets):
                start = time.perf_counter()
                sp, size = make_packing(fuzz, target, num, seed=10 + n)
                path = Path(tmp) / f"{name}-{target:.3f}.txt"
                sp.save(str(path))
                sp = SpherePack()
                sp.load(str(path))  # Yade reads the same text: both start from identical spheres
                row = dict(distribution=name, rRelFuzz=fuzz, cell_porosity=target, spheres=len(sp),
                           packing_s=time.perf_counter() - start, file=str(path), box=[[0, 0, 0], list(size)],
                           **permeability(sp, size), **periodic_permeability(sp, size))
                row["box_over_periodic"] = row["K"] / row["K_periodic"]
                row["K_periodic_over_KC"] = row["K_periodic"] / kozeny_carman(row["porosity_periodic"], row["d32"])
                row["K_KC"] = kozeny_carman(row["porosity"], row["d32"])
                rows.append(row)
                print(f"{name:6s} cell n {target:.3f}: sample n {row['porosity']:.3f}, {row['nCells']} pores, "
                      f"K/d32^2 = {row['K'] / row['d32'] ** 2:.3e}, K/K_KC = {row['K'] / row['K_KC']:.3f} "
                      f"K_box/K_periodic = {row['box_over_periodic']:.3f} (periodic: n {row['porosity_periodic']:.3f}, "
                      f"K/K_KC {row['K_periodic_over_KC']:.3f}) "
                      f"(packing {row['packing_s']:.1f} s, flow {row['wall_s']:.2f} s)")
        yade = None
        if twin.yade_available():
            yade = twin.run(YADE_SCRIPT, {"packings": [r["file"] for r in rows], "boxes": [r["box"] for r in rows],
                                                "axis": 1, "dp": 1.0}, "yade")
            yade_periodic = twin.run(YADE_PERIODIC, {"packings": [r["file"] for r in rows],
                                                     "cells": [r["box"][1] for r in rows], "gradP": [0, 1, 0],
                                                     "threshold": THRESHOLD}, "yade")
    for row in rows:
        row.pop("file")

    ratios = [r["box_over_periodic"] for r in rows]
    case.record("worst |ln(K_box / K_periodic)| over the packings", float(max(abs(np.log(ratios)))),
                "the same packing in its periodic cell (PeriodicFlowEngine) and between walls on the cell faces "
                "(FlowEngine): the walls cutting the spheres leave a looser layer along the lateral faces, a "
                "boundary layer of a few radii: within a factor 2 for a few hundred spheres", float(np.log(2.0)),
                suffix="periodic-vs-box", ratios=ratios)
    print(f"K_box / K_periodic from {min(ratios):.3f} to {max(ratios):.3f}")
    log_kc = max(abs(np.log(r["K"] / r["K_KC"])) for r in rows)
    case.record("worst |ln(K / K_KC)| over the packings", log_kc,
                "Kozeny-Carman d32^2 n^3 / (180 (1 - n)^2) at the sample porosity", float(np.log(3.0)),
                suffix="kozeny-carman", packings=rows)
    print(f"Kozeny-Carman: K / K_KC from {min(r['K'] / r['K_KC'] for r in rows):.3f} "
          f"to {max(r['K'] / r['K_KC'] for r in rows):.3f}")
    if yade is not None:
        for row, y in zip(rows, yade):
            lo, hi = np.array(y["box"][0]), np.array(y["box"][1])
            length, area = hi[1] - lo[1], (hi[0] - lo[0]) * (hi[2] - lo[2])
            row["K_yade"] = -y["boundaryFlux"][2] * length / area
            row["nCells_yade"] = y["nCells"]
            row["rel_diff_yade"] = abs(row["K"] - row["K_yade"]) / abs(row["K_yade"])
        worst = max(r["rel_diff_yade"] for r in rows)
        case.record("worst relative difference of the permeability from Yade's over the packings", worst,
                    "Yade 2023.02a FlowEngine (useSolver=3) on the same sphere files", 0.01,
                    suffix="yade", packings=rows)
        print(f"Yade: worst relative difference of K {worst:.2e}")
        for row, y in zip(rows, yade_periodic):
            row["K_periodic_yade"] = -y["averageVelocity"][1]
            row["nCells_periodic_yade"] = y["nCells"]
            row["rel_diff_periodic_yade"] = abs(row["K_periodic"] / row["K_periodic_yade"] - 1)
        worst = max(r["rel_diff_periodic_yade"] for r in rows)
        case.record("worst relative difference of the periodic permeability from Yade's over the packings", worst,
                    "Yade 2023.02a PeriodicFlowEngine (useSolver=3, gradP (0, 1, 0)) on the same sphere files and cells",
                    0.01, suffix="periodic-yade", packings=rows)
        print(f"Yade, periodic: worst relative difference of K {worst:.2e}")
    else:
        print("yade is not installed: no side-by-side record")

    fig, ax = plt.subplots(figsize=(6, 4.5))
    grid = np.linspace(0.3, 0.5, 100)
    ax.plot(grid, grid ** 3 / (180 * (1 - grid) ** 2), "k-", label="Kozeny-Carman")
    for name, marker in zip(DISTRIBUTIONS, ("o", "s")):
        sel = [r for r in rows if r["distribution"] == name]
        n = [r["porosity"] for r in sel]
        ax.plot(n, [r["K"] / r["d32"] ** 2 for r in sel], marker, mfc="none", ms=8,
                label=f"Talus, {name} (rRelFuzz {DISTRIBUTIONS[name]})")
        ax.plot([r["porosity_periodic"] for r in sel], [r["K_periodic"] / r["d32"] ** 2 for r in sel], marker, ms=4,
                label=f"Talus periodic (cell porosity), {name}")
        if yade is not None:
            ax.plot(n, [r["K_yade"] / r["d32"] ** 2 for r in sel], "x", ms=6, label=f"Yade, {name}")
    ax.set_yscale("log")
    ax.set_xlabel("sample porosity n")
    ax.set_ylabel("K / d32$^2$")
    ax.set_title(f"Permeability of sphere packings ({num} spheres)")
    ax.legend(fontsize=8)
    case.save_chart(fig)


if __name__ == "__main__":
    main()
