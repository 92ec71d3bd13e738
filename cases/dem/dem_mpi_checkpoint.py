"""DEM case: a checkpoint written under mpirun continues the run bit for bit at any process count.

Run:      build/bin/talus run cases/dem/dem_mpi_checkpoint.py [--quick] [--results DIR]
Set-up:   cases/scenes/mpi_checkpoint.py, unchanged in every run: spheres (makeCloud, rRelFuzz 0.3)
          falling onto the walls of a box (FrictMat, linear Cundall-Strack law, damping 0.4,
          dt 0.7 P-wave); STEPS steps, O.save, STEPS steps more (the uninterrupted run), by
          `talus run` in one process and by `mpirun --oversubscribe -np N talus run -j 1` for
          N = 2, 4; then O.load of the file written at 4 processes and STEPS steps at 1, 2 and 4
          processes, and of the file written in one process at 2. Quick: 400 spheres, 1000 + 1000
          steps; full: 20 000 spheres, 300 + 300 steps (this machine has 2 cores: 4 processes are
          oversubscribed).
Checked:  dem.mpi.checkpoint: the largest difference of a body's position after the continued runs
          from the uninterrupted run's, over the largest coordinate (0: the same bits). The
          details hold the seconds O.save and O.load took (the slowest process's) and the file's
          size at each process count.
Produces: the record and chart dem.mpi.checkpoint.png (save and load seconds, file size).
"""
import os
import tempfile
from pathlib import Path

import numpy as np

from talus import bench, results

SCENE = Path(__file__).resolve().parents[1] / "scenes" / "mpi_checkpoint.py"


def run(mode: str, processes: int | None, spheres: int, steps: int, checkpoint: Path, output: Path) -> dict:
    """The scene in one process (None) or under mpirun with `processes`; its JSON output."""
    return bench.run_talus_script([SCENE, mode, spheres, steps, checkpoint, output], output, processes)


def main():
    args = results.case_arguments(__doc__).parse_args()
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    case = results.Case("dem.mpi.checkpoint", quick=args.quick, folder=args.results)
    load_before = os.getloadavg()[0]    # other work on the machine slows the processes' collective calls
    spheres, steps = (400, 1000) if args.quick else (20000, 300)
    counts = [1, 2, 4]
    with tempfile.TemporaryDirectory() as tmp:
        folder = Path(tmp)
        saved = {n: run("save", n if n > 1 else None, spheres, steps, folder / f"run-{n}.h5", folder / f"save-{n}.json")
                 for n in counts}
        loaded = {n: run("load", n if n > 1 else None, spheres, steps, folder / "run-4.h5", folder / f"load-{n}.json")
                  for n in counts}
        serial_file = run("load", 2, spheres, steps, folder / "run-1.h5", folder / "load-serial-file.json")
    reference = np.asarray(saved[4]["positions"])
    scale = np.abs(reference).max()
    differences = {f"written at 4, continued at {n}": float(np.abs(np.asarray(r["positions"]) - reference).max() / scale)
                   for n, r in loaded.items()}
    differences["written in one process, continued at 2"] = float(
        np.abs(np.asarray(serial_file["positions"]) - reference).max() / scale)
    differences.update({f"uninterrupted at {n}": float(np.abs(np.asarray(r["positions"]) - reference).max() / scale)
                        for n, r in saved.items()})
    save_seconds = {str(n): r["save_seconds"] for n, r in saved.items()}
    load_seconds = {str(n): r["load_seconds"] for n, r in loaded.items()}
    sizes = {str(n): r["bytes"] for n, r in saved.items()}
    print(f"load average {load_before:.1f} before the runs, {os.getloadavg()[0]:.1f} after")
    for n in counts:
        print(f"{n} processes: O.save {saved[n]['save_seconds']:.3f} s ({saved[n]['bytes']} bytes), "
              f"O.load {loaded[n]['load_seconds']:.3f} s")
    for what, d in differences.items():
        print(f"{what}: largest relative position difference {d:.3g}")
    worst = max(differences.values())
    case.record("largest difference of a body's position, after a run continued from a checkpoint at 1, 2 and 4 "
                "processes, from the uninterrupted run at 4, relative to the largest coordinate", worst,
                "the uninterrupted run (the same bits: 0)", 0.0, spheres=spheres, steps=steps,
                differences=differences, save_seconds=save_seconds, load_seconds=load_seconds, bytes=sizes,
                load_average_before=load_before, load_average_after=os.getloadavg()[0])

    fig, axes = plt.subplots(1, 2, figsize=(10, 3.8))
    x = np.arange(len(counts))
    axes[0].bar(x - 0.2, [saved[n]["save_seconds"] for n in counts], 0.4, label="O.save")
    axes[0].bar(x + 0.2, [loaded[n]["load_seconds"] for n in counts], 0.4, label="O.load (file written at 4)")
    axes[0].set_xticks(x, [str(n) for n in counts])
    axes[0].set_xlabel("MPI processes")
    axes[0].set_ylabel("seconds (slowest process)")
    axes[0].set_title(f"{spheres} spheres")
    axes[0].legend()
    axes[1].bar([str(n) for n in counts], [saved[n]["bytes"] / 1e6 for n in counts])
    axes[1].set_xlabel("MPI processes writing")
    axes[1].set_ylabel("file size (MB)")
    axes[1].set_title("checkpoint size")
    fig.tight_layout()
    case.save_chart(fig)


if __name__ == "__main__":
    main()
