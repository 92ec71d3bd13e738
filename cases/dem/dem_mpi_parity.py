"""DEM case: scripts written for one process give the serial run's positions under mpirun.

Run:      build/bin/talus run cases/dem/dem_mpi_parity.py [--quick] [--results DIR]
Set-up:   three scenes, each unchanged in every run, 1000 steps, run by `talus run` in one process
          and by `mpirun --oversubscribe -np N talus run -j 1` (this machine has 2 cores: above 2
          processes are oversubscribed):
          - cases/scenes/deposition.py: spheres (makeCloud, rRelFuzz 0.3) falling onto the walls
            of a box (FrictMat, linear Cundall-Strack law, damping 0.4, dt 0.7 P-wave, a PyRunner
            printing unbalancedForce), N = 1, 2, 3, 4, 8. Quick: 400 spheres; full: 3000.
          - cases/scenes/silo_discharge.py: a square silo of 16 facets (held by every process)
            discharging through its floor's orifice, Hertz-Mindlin with restitution 0.5, a
            PyRunner erasing every 50 steps the spheres two radii below the floor (every process
            erases the same ones, deciding from the gathered positions), N = 1, 2, 4, 8. Quick: 400
            spheres; full: 3000.
          - cases/scenes/periodic_cell.py triax: the periodic triaxial test (a loose periodic cloud
            compacted to -100 kPa by PeriTriaxController with dynCell, which reads the stress every
            step, then compressed along z to a log strain of -0.2 with -100 kPa kept on x and y;
            the processes' regions in the cell's reduced coordinates, ghosts across its faces),
            N = 1, 2, 3, 4, 8, run on past the 1000 steps to the end of the compression. Quick: 400
            spheres; full: 3000.
Checked:  dem.mpi.parity (deposition) and dem.mpi.parity.silo: the largest difference of a body's
          position from the serial run's, every 100 steps over the 1000, over the largest
          coordinate (relative; <= 1e-10), at every process count; for the silo, the bodies
          erased must be the same at every sample (an erased body counted as a difference of
          1) and the details hold the spheres left every 100 steps. The details hold each
          count's difference and the halo traffic per process and step (ghost-update bytes and
          messages; migration and ghost-rebuild bytes per re-detection; bodies and contacts
          migrated).
          dem.mpi.parity.peri-triax: the positions as above over the first 1000 steps (1 to 4
          and 8 processes); dem.mpi.parity.peri-triax-peak: the largest relative difference of the peak
          stress ratio (s1 - s3) / (s1 + s3) of the compression from the serial run's (<= 1 %).
Produces: the records and the chart dem.mpi.parity.png (differences and halo bytes per process
          count).
"""
import tempfile
from pathlib import Path

import numpy as np

from talus import bench, results

SCENES = Path(__file__).resolve().parents[1] / "scenes"
STEPS = 1000
#: Each scene's arguments after its spheres, steps and output file.
ARGUMENTS = {"periodic_cell": ["triax", "finish"], "periodic_clumps": ["triax"]}


def run(scene: str, processes: int | None, spheres: int, folder: Path) -> dict:
    """The scene in one process (None) or under mpirun with `processes`; its JSON output."""
    out = folder / f"{scene}-{processes or 0}.json"
    return bench.run_talus_script([SCENES / f"{scene}.py", spheres, STEPS, out, *ARGUMENTS.get(scene, [])], out,
                                  processes)


def peak_ratio(result: dict) -> float:
    """The peak stress ratio (s1 - s3) / (s1 + s3) of the periodic triaxial's compression."""
    h = {k: np.asarray(v, float) for k, v in result["history"].items()}
    shear = h["stage"] == 1
    s1, s3 = -h["szz"][shear], -(h["sxx"][shear] + h["syy"][shear]) / 2
    return float(((s1 - s3) / (s1 + s3)).max())


def difference(serial: dict, split: dict) -> float:
    """Largest difference of a body's position from the serial run's over every sample, relative
    to the largest coordinate; 1 if a body erased in one run is not erased in the other."""
    a, b = np.asarray(serial["positions"], float), np.asarray(split["positions"], float)
    if not np.array_equal(np.isnan(a), np.isnan(b)):
        return 1.0
    kept = ~np.isnan(a)
    return float(np.abs(a[kept] - b[kept]).max() / np.abs(a[kept]).max())


def halo(traffic: list[dict]) -> dict:
    """The halo traffic per process and step or re-detection."""
    return {
        "update_bytes_per_process_step": [t["update_bytes"] / max(t["updates"], 1) for t in traffic],
        "update_messages_per_process_step": [t["update_messages"] / max(t["updates"], 1) for t in traffic],
        "rebuild_bytes_per_process_redetection": [t["rebuild_bytes"] / max(t["rebuilds"], 1) for t in traffic],
        "redetections": [t["rebuilds"] for t in traffic],
        "migrated_bodies": [t["migrated_bodies"] for t in traffic],
        "migrated_contacts": [t["migrated_contacts"] for t in traffic],
    }


def parity(scene: str, spheres: int, counts: list[int], folder: Path) -> tuple[dict, dict, dict, dict]:
    """The serial run, and per process count its run, its difference and its halo."""
    serial = run(scene, None, spheres, folder)
    split = {n: run(scene, n, spheres, folder) for n in counts}
    differences = {n: difference(serial, r) for n, r in split.items()}
    halos = {n: halo(r["traffic"]) for n, r in split.items()}
    for n in counts:
        print(f"{scene}, {n} processes: largest relative position difference {differences[n]:.3g}, ghost updates "
              f"{np.mean(halos[n]['update_bytes_per_process_step'] or [0]):.0f} bytes and "
              f"{np.mean(halos[n]['update_messages_per_process_step'] or [0]):.2f} messages per process and step, "
              f"{sum(halos[n]['migrated_bodies'])} bodies migrated with {sum(halos[n]['migrated_contacts'])} contacts")
    return serial, split, differences, halos


def main():
    args = results.case_arguments(__doc__).parse_args()
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    case = results.Case("dem.mpi.parity", quick=args.quick, folder=args.results)
    spheres = 400 if args.quick else 3000
    counts = {"deposition": [1, 2, 3, 4, 8], "silo_discharge": [1, 2, 4, 8], "periodic_cell": [1, 2, 3, 4, 8]}
    with tempfile.TemporaryDirectory() as tmp:
        runs = {scene: parity(scene, spheres, n, Path(tmp)) for scene, n in counts.items()}
    serial, split, differences, halos = runs["deposition"]
    case.record("largest difference of a body's position from the serial run over 1000 steps, relative to the "
                "largest coordinate, at 1 to 4 and 8 processes", max(differences.values()),
                "the same script in one process (talus run)", 1e-10, spheres=spheres, steps=STEPS,
                differences={str(n): d for n, d in differences.items()}, halo={str(n): h for n, h in halos.items()},
                floor_force_serial=serial["floor_force"],
                floor_force={str(n): r["floor_force"] for n, r in split.items()})
    serial, split, differences, halos = runs["silo_discharge"]
    case.record("silo of facets discharging (Hertz-Mindlin, spheres erased as they leave): largest difference of a "
                "body's position from the serial run over 1000 steps, relative to the largest coordinate (1 if other "
                "bodies were erased), at 1, 2, 4 and 8 processes", max(differences.values()),
                "the same script in one process (talus run)", 1e-10, suffix="silo", spheres=spheres, steps=STEPS,
                differences={str(n): d for n, d in differences.items()}, halo={str(n): h for n, h in halos.items()},
                spheres_left_serial=serial["left"], spheres_left={str(n): r["left"] for n, r in split.items()},
                floor_force_serial=serial["floor_force"],
                floor_force={str(n): r["floor_force"] for n, r in split.items()})
    serial, split, differences, halos = runs["periodic_cell"]
    case.record("periodic triaxial (PeriTriaxController, deforming cell): largest difference of a body's position "
                "from the serial run over 1000 steps, relative to the largest coordinate, at 1 to 4 and 8 processes",
                max(differences.values()), "the same script in one process (talus run)", 1e-10, suffix="peri-triax",
                spheres=spheres, steps=STEPS, differences={str(n): d for n, d in differences.items()},
                halo={str(n): h for n, h in halos.items()}, cells_serial=serial["cells"][-1],
                cells={str(n): r["cells"][-1] for n, r in split.items()})
    peaks = {n: peak_ratio(r) for n, r in split.items()}
    print(f"periodic triaxial: peak stress ratio {peak_ratio(serial):.6f} serial, "
          + ", ".join(f"{p:.6f} at {n}" for n, p in peaks.items()))
    case.record("periodic triaxial: largest relative difference of the peak stress ratio (s1 - s3) / (s1 + s3) of "
                "the compression from the serial run's, at 1 to 4 and 8 processes",
                max(abs(p - peak_ratio(serial)) / peak_ratio(serial) for p in peaks.values()),
                "the same script in one process (talus run)", 0.01, suffix="peri-triax-peak", spheres=spheres,
                peak_serial=peak_ratio(serial), peaks={str(n): p for n, p in peaks.items()},
                steps_serial=serial["iter"], steps={str(n): r["iter"] for n, r in split.items()},
                compacted_serial=serial["compacted"], compacted={str(n): r["compacted"] for n, r in split.items()})

    fig, axes = plt.subplots(1, 4, figsize=(18, 3.8))
    titles = {"deposition": f"deposition of {spheres} spheres", "silo_discharge": f"silo of {spheres} spheres",
              "periodic_cell": f"periodic triaxial of {spheres} spheres"}
    for ax, (scene, (_, _, differences, _)) in zip(axes, runs.items()):
        ax.bar([str(n) for n in counts[scene]], [max(differences[n], 1e-18) for n in counts[scene]])
        ax.axhline(1e-10, color="C3", ls="--", label="tolerance 1e-10")
        ax.set_yscale("log")
        ax.set_xlabel("MPI processes")
        ax.set_ylabel("largest relative position difference")
        ax.set_title(f"{titles[scene]}, 1000 steps (1e-18: same bits)", fontsize=9)
        ax.legend()
    for scene, (_, _, _, halos) in runs.items():
        axes[3].plot(counts[scene], [np.mean(halos[c]["update_bytes_per_process_step"] or [0]) for c in counts[scene]],
                     marker="o", label=titles[scene])
    axes[3].set_xlabel("MPI processes")
    axes[3].set_ylabel("ghost-update bytes per process and step")
    axes[3].set_title("halo traffic")
    axes[3].legend()
    fig.tight_layout()
    case.save_chart(fig)


if __name__ == "__main__":
    main()
