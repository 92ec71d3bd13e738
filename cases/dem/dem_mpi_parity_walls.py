"""DEM case: clumps, boxes and a triaxial box of walls give the serial run's positions under mpirun.

Run:      build/bin/talus run cases/dem/dem_mpi_parity_walls.py [--quick] [--results DIR]
Set-up:   two scenes, each unchanged in every run, 1000 steps, run by `talus run` in one process
          and by `mpirun --oversubscribe -np N talus run -j 1`, N = 1, 2, 3 (this machine has 2
          cores: 3 processes are oversubscribed), as cases/dem/dem_mpi_parity.py runs its scenes:
          - cases/scenes/triax_box.py: Yade's triaxial tutorial, small: spheres (makeCloud,
            rRelFuzz 0.3333) in a box of six walls (aabbWalls), grown by a
            TriaxialStressController to -10 kPa for 400 steps, then compressed by the walls to
            -20 kPa (internalCompaction off: each wall moved by the force on it, summed exactly
            over the processes), GlobalStiffnessTimeStepper, damping 0.2. Quick: 300 spheres;
            full: 2000.
          - cases/scenes/clump_deposition.py: clumps of two and three spheres and free spheres
            (every fourth) falling into a box of walls onto a fixed box (utils.box, held by every
            process); a clump and its members owned by the process of its centre of mass. Quick:
            200 clumps and spheres; full: 1500.
          - cases/scenes/periodic_clumps.py: clumps of two spheres and free spheres (every
            fourth) in a periodic cell compacted by PeriTriaxController (dynCell), the clumps
            ghosted whole through the cell's images. Quick: 300 clumps and spheres; full: 1500.
Checked:  dem.mpi.parity.triax-box, dem.mpi.parity.clumps and .clumps-periodic: the largest difference of a body's
          position from the serial run's, every 100 steps over the 1000, over the largest
          coordinate (relative; <= 1e-10), at every process count. The details hold each count's
          difference, the halo traffic per process and step, and for the triaxial box the walls'
          stresses, the porosity and the mean stress the controller read at the end.
Produces: the records and the chart dem.mpi.parity.walls.png (differences per process count).
"""
import sys
import tempfile
from pathlib import Path

from talus import results

sys.path.insert(0, str(Path(__file__).resolve().parent))
import dem_mpi_parity  # noqa: E402  (the runs, differences and halo of the parity case)

COUNTS = [1, 2, 3]


def main():
    args = results.case_arguments(__doc__).parse_args()
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    case = results.Case("dem.mpi.parity", quick=args.quick, folder=args.results)
    sizes = {"triax_box": 300 if args.quick else 2000, "clump_deposition": 200 if args.quick else 1500,
             "periodic_clumps": 300 if args.quick else 1500}
    with tempfile.TemporaryDirectory() as tmp:
        runs = {scene: dem_mpi_parity.parity(scene, n, COUNTS, Path(tmp)) for scene, n in sizes.items()}
    serial, split, differences, halos = runs["triax_box"]
    case.record("triaxial box of walls (TriaxialStressController growing the spheres, then moving the walls by the "
                "force on each): largest difference of a body's position from the serial run over 1000 steps, "
                "relative to the largest coordinate, at 1 to 3 processes", max(differences.values()),
                "the same script in one process (talus run)", 1e-10, suffix="triax-box", spheres=sizes["triax_box"],
                steps=dem_mpi_parity.STEPS, differences={str(n): d for n, d in differences.items()},
                halo={str(n): h for n, h in halos.items()},
                read_serial={k: serial[k] for k in ("stress", "porosity", "meanStress")},
                read={str(n): {k: r[k] for k in ("stress", "porosity", "meanStress")} for n, r in split.items()})
    serial, split, differences, halos = runs["clump_deposition"]
    case.record("clumps and spheres falling onto a fixed box (clumps owned with their members): largest difference "
                "of a body's position from the serial run over 1000 steps, relative to the largest coordinate, at 1 "
                "to 3 processes", max(differences.values()), "the same script in one process (talus run)", 1e-10,
                suffix="clumps", clumps_and_spheres=sizes["clump_deposition"], steps=dem_mpi_parity.STEPS,
                differences={str(n): d for n, d in differences.items()}, halo={str(n): h for n, h in halos.items()},
                box_force_serial=serial["box_force"], box_force={str(n): r["box_force"] for n, r in split.items()})
    serial, split, differences, halos = runs["periodic_clumps"]
    case.record("clumps and spheres in a periodic cell compacted by PeriTriaxController (clumps ghosted whole through "
                "the cell's images): largest difference of a body's position from the serial run over 1000 steps, "
                "relative to the largest coordinate, at 1 to 3 processes", max(differences.values()),
                "the same script in one process (talus run)", 1e-10, suffix="clumps-periodic",
                clumps_and_spheres=sizes["periodic_clumps"], steps=dem_mpi_parity.STEPS,
                differences={str(n): d for n, d in differences.items()}, halo={str(n): h for n, h in halos.items()},
                stress_serial=serial["stress"], stress={str(n): r["stress"] for n, r in split.items()})

    # Both scenes' differences side by side at each process count (1e-18 standing for 0: the same bits).
    fig, ax = plt.subplots(figsize=(6.5, 3.8))
    titles = {"triax_box": f"triaxial box, {sizes['triax_box']} spheres",
              "clump_deposition": f"clumps onto a box, {sizes['clump_deposition']} clumps and spheres",
              "periodic_clumps": f"clumps in a periodic cell, {sizes['periodic_clumps']} clumps and spheres"}
    for k, (scene, (_, _, differences, _)) in enumerate(runs.items()):
        ax.bar([c + 0.27 * k - 0.27 for c in COUNTS], [max(differences[c], 1e-18) for c in COUNTS], width=0.27,
               label=titles[scene])
    ax.axhline(1e-10, color="C3", ls="--", label="tolerance 1e-10")
    ax.set(yscale="log", xticks=COUNTS, xlabel="MPI processes", ylabel="largest relative position difference",
           title="1000 steps against one process (1e-18: the same bits)")
    ax.legend(fontsize=8)
    fig.tight_layout()
    case.save_chart(fig, suffix="walls")


if __name__ == "__main__":
    main()
