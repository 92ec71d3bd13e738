"""DEM case: the seed's gravity deposition tutorial, in Talus and in Yade on identical input.

Run:      build/bin/talus run cases/dem/dem_gravity_deposition.py [--quick] [--results DIR]
Set-up:   cases/yade/gravity_deposition.py, run unchanged by both programs: a seeded cloud
          (makeCloud in the unit cube, rRelFuzz 0.5; the same spheres in both programs) falls into an
          open facet box (FrictMat defaults, damping 0.4, dt 0.5 P-wave) for a fixed simulated time (the
          same number of steps in both programs; the deposit has settled by then). Quick: rMean 0.05
          (the tutorial's, ~330 spheres), 3 s; full: rMean 0.03 (~1500 spheres), 4 s; seeds 1..4, two
          runs at a time. (Stopping at an unbalanced-force threshold instead makes the stop time, and
          with it the creep compaction, differ between two chaotic runs.) Yade 2023.02a runs the same file (skipped if not installed).
Checked:  dem.gravity-deposition.porosity: relative difference of the final porosity (slab
          0.05 < z < 0.2, away from floor and surface; mean over seeds) from Yade's (<= 1 %).
          dem.gravity-deposition.coordination: the same for the sphere-sphere coordination number
          2 C / N (<= 1 %). Single deposits scatter by 2-3 % (chaotic divergence), hence the mean.
          dem.gravity-deposition.settled: largest final unbalanced force (<= 0.1; the tutorial stops
          at 0.05; Talus).
Produces: the records and chart dem.gravity-deposition.png (porosity and coordination per seed).
"""
from pathlib import Path

import numpy as np

from talus import results
from talus import twin

SCENARIO = Path(__file__).resolve().parents[1] / "yade" / "gravity_deposition.py"


def main():
    args = results.case_arguments(__doc__).parse_args()
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    case = results.Case("dem.gravity-deposition", quick=args.quick, folder=args.results)
    r_mean, duration = (.05, 3.0) if args.quick else (.03, 4.0)
    seeds = [1, 2, 3, 4]
    ours, theirs = twin.run_seeds(SCENARIO, lambda seed: {"rMean": r_mean, "seed": seed, "time": duration}, seeds)
    twin.print_seeds(seeds, ours, theirs, lambda r: f"{r['spheres']} spheres, {r['iter']} steps, porosity "
                     f"{r['porosity']:.4f}, coordination {r['coordination']:.3f}")
    case.record("largest unbalanced force at the end of the deposition", max(o["unbalanced"] for o in ours),
                "a settled deposit (the tutorial stops at unbalancedForce() < 0.05)", 0.1, suffix="settled")
    if theirs:
        for key, what in (("porosity", "porosity of the slab 0.05 < z < 0.2"),
                          ("coordination", "sphere-sphere coordination number 2C/N")):
            twin.record_mean_difference(case, f"relative difference of the mean {what} from Yade's", key, ours, theirs,
                                        0.01, key, "yade 2023.02a on the same scenario file (same seeded clouds)",
                                        ours_each=[r[key] for r in ours], theirs_each=[r[key] for r in theirs],
                                        seeds=seeds, spheres=[r["spheres"] for r in ours])

    fig, axes = plt.subplots(1, 2, figsize=(10, 3.8))
    for ax, key in zip(axes, ("porosity", "coordination")):
        ax.plot(seeds, [r[key] for r in ours], "o", label="Talus")
        if theirs:
            ax.plot(seeds, [r[key] for r in theirs], "s", mfc="none", label="Yade")
        ax.axhline(np.mean([r[key] for r in ours]), color="C0", lw=.8)
        if theirs:
            ax.axhline(np.mean([r[key] for r in theirs]), color="C1", lw=.8, ls="--")
        ax.set_xlabel("seed of makeCloud")
        ax.set_ylabel(key)
        ax.set_xticks(seeds)
    axes[0].set_title("gravity deposition: slab porosity")
    axes[1].set_title("sphere-sphere coordination")
    axes[0].legend()
    fig.tight_layout()
    case.save_chart(fig)


if __name__ == "__main__":
    main()
