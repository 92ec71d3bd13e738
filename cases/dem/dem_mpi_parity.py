"""DEM case: a script written for one process gives the serial run's positions under mpirun.

Run:      build/bin/talus run cases/dem/dem_mpi_parity.py [--quick] [--results DIR]
Set-up:   cases/scenes/deposition.py, unchanged in every run: spheres (makeCloud, rRelFuzz 0.3)
          falling onto the walls of a box (FrictMat, linear Cundall-Strack law, damping 0.4,
          dt 0.7 P-wave, a PyRunner printing unbalancedForce), 1000 steps, run by `talus run`
          in one process and by `mpirun --oversubscribe -np N talus run -j 1` for N = 1, 2, 3, 4
          (this machine has 2 cores: 3 and 4 processes are oversubscribed). Quick: 400 spheres;
          full: 3000.
Checked:  dem.mpi.parity: the largest difference of a body's position from the serial run's,
          every 100 steps over the 1000, over the largest coordinate (relative; <= 1e-10), at
          every process count. The details hold each count's difference and the halo traffic per
          process and step (ghost-update bytes and messages; migration and ghost-rebuild bytes
          per re-detection).
Produces: the record and chart dem.mpi.parity.png (difference and halo bytes per process count).
"""
import json
import os
import subprocess
import sys
import tempfile
from pathlib import Path

import numpy as np

from talus import results

SCENE = Path(__file__).resolve().parents[1] / "scenes" / "deposition.py"
STEPS = 1000


def run(processes: int | None, spheres: int, folder: Path) -> dict:
    """The scene in one process (None) or under mpirun with `processes`; its JSON output."""
    out = folder / f"run-{processes or 0}.json"
    talus = [sys.executable, "-m", "talus", "run", "-j", "1", str(SCENE), str(spheres), str(STEPS), str(out)]
    command = talus if processes is None else ["mpirun", "--allow-run-as-root", "--oversubscribe", "-np",
                                               str(processes), *talus]
    env = {**os.environ, "OMP_NUM_THREADS": "1"}
    done = subprocess.run(command, capture_output=True, text=True, timeout=1800, env=env)
    if done.returncode != 0:
        raise RuntimeError(f"{' '.join(command)} failed:\n{done.stdout}\n{done.stderr}")
    return json.loads(out.read_text())


def main():
    args = results.case_arguments(__doc__).parse_args()
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    case = results.Case("dem.mpi.parity", quick=args.quick, folder=args.results)
    spheres = 400 if args.quick else 3000
    counts = [1, 2, 3, 4]
    with tempfile.TemporaryDirectory() as tmp:
        serial = run(None, spheres, Path(tmp))
        split = {n: run(n, spheres, Path(tmp)) for n in counts}
    reference = np.asarray(serial["positions"])
    scale = np.abs(reference).max()
    differences, halo = {}, {}
    for n, r in split.items():
        differences[n] = float(np.abs(np.asarray(r["positions"]) - reference).max() / scale)
        per_process = r["traffic"]
        halo[n] = {
            "update_bytes_per_process_step": [t["update_bytes"] / max(t["updates"], 1) for t in per_process],
            "update_messages_per_process_step": [t["update_messages"] / max(t["updates"], 1) for t in per_process],
            "rebuild_bytes_per_process_redetection": [t["rebuild_bytes"] / max(t["rebuilds"], 1) for t in per_process],
            "redetections": [t["rebuilds"] for t in per_process],
        }
        print(f"{n} processes: largest relative position difference {differences[n]:.3g}, ghost updates "
              f"{np.mean(halo[n]['update_bytes_per_process_step'] or [0]):.0f} bytes and "
              f"{np.mean(halo[n]['update_messages_per_process_step'] or [0]):.2f} messages per process and step")
    worst = max(differences.values())
    case.record("largest difference of a body's position from the serial run over 1000 steps, relative to the "
                "largest coordinate, at 1 to 4 processes", worst,
                "the same script in one process (talus run)", 1e-10, spheres=spheres, steps=STEPS,
                differences={str(n): d for n, d in differences.items()}, halo={str(n): h for n, h in halo.items()},
                floor_force_serial=serial["floor_force"],
                floor_force={str(n): r["floor_force"] for n, r in split.items()})

    fig, axes = plt.subplots(1, 2, figsize=(10, 3.8))
    axes[0].bar([str(n) for n in counts], [max(differences[n], 1e-18) for n in counts])
    axes[0].axhline(1e-10, color="C3", ls="--", label="tolerance 1e-10")
    axes[0].set_yscale("log")
    axes[0].set_xlabel("MPI processes")
    axes[0].set_ylabel("largest relative position difference")
    axes[0].set_title(f"deposition of {spheres} spheres, 1000 steps (0: same bits)")
    axes[0].legend()
    axes[1].bar([str(n) for n in counts],
                [np.mean(halo[n]["update_bytes_per_process_step"] or [0]) for n in counts])
    axes[1].set_xlabel("MPI processes")
    axes[1].set_ylabel("ghost-update bytes per process and step")
    axes[1].set_title("halo traffic")
    fig.tight_layout()
    case.save_chart(fig)


if __name__ == "__main__":
    main()
