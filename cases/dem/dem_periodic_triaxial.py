"""DEM case: the seed's periodic triaxial test (tutorial 06), in Talus and in Yade on identical input.

Run:      build/bin/talus run cases/dem/dem_periodic_triaxial.py [--quick] [--clumps] [--results DIR]
Set-up:   cases/yade/periodic_triaxial.py, run unchanged by both programs: a seeded periodic cloud
          (makeCloud, rMean 0.1, rRelFuzz 0.3, FrictMat E 1e7, friction 0.5) compacted to -100 kPa by
          PeriTriaxController (dynCell), then compressed along z at 0.1/s to a log strain of -0.2 with
          -100 kPa kept on x and y. A 2 m cell (~460 spheres); quick: seed 1; full: seeds 1..4. (A
          larger cell with the tutorial's maxStrainRate 10/s compacts so violently that spheres
          overlap by more than half a radius, which Talus rejects.) Yade 2023.02a runs the same file
          (skipped if not installed). --clumps: the tutorial's clump variant (makeClumpCloud of its
          three-sphere template, periodic; records under dem.periodic-triaxial-clumps): the
          tutorial's 500 clumps in a 2 m cell (quick: 200 in 0.8 m), compacted at maxStrainRate 1/s
          (at the tutorial's 10/s members overlap by more than half a radius). The clouds are not
          the same in the two programs (Yade draws with C rand()), only alike.
Checked:  dem.periodic-triaxial.compaction: worst relative gap of the three stresses to -100 kPa when
          the doneHook fires (PeriTriaxController's relStressTol, 1e-3).
          dem.periodic-triaxial.lateral: worst relative deviation of the lateral stresses from
          -100 kPa during the compression, after the first 1 % of strain (<= 10 %).
          dem.periodic-triaxial.peak: relative difference of the peak friction sin(phi) = (s1 - s3) /
          (s1 + s3) from Yade's (mean over seeds; <= 5 %: the runs diverge chaotically, so this is the
          statistical agreement of two samples of the same packing).
          dem.periodic-triaxial.porosity: porosity after compaction against Yade's (<= 1 %).
Produces: the records and chart dem.periodic-triaxial.png (stress ratio and lateral stresses
          against axial strain, Talus and Yade).
"""
from pathlib import Path

import numpy as np

from talus import results
from talus import twin

SCENARIO = Path(__file__).resolve().parents[1] / "yade" / "periodic_triaxial.py"
SIGMA = -1e5
CLUMPS, CLUMP_SIZE = 500, 2.0           # the tutorial's cloud
QUICK_CLUMPS, QUICK_CLUMP_SIZE = 200, 0.8


def analyse(result: dict) -> dict:
    h = {k: np.array(v) for k, v in result["history"].items()}
    shear = h["stage"] == 1
    s1, s3 = -h["szz"][shear], -(h["sxx"][shear] + h["syy"][shear]) / 2
    ezz = h["ezz"][shear]
    sinphi = (s1 - s3) / (s1 + s3)
    settled = ezz < -0.01
    lateral = np.concatenate([h["sxx"][shear][settled], h["syy"][shear][settled]])
    return {"ezz": ezz, "sinphi": sinphi, "s3": s3, "peak": float(sinphi.max()),
            "lateral": float(np.max(np.abs(lateral - SIGMA)) / abs(SIGMA)),
            "compaction": float(np.max(np.abs(np.array(result["compaction"]["stress"]) - SIGMA)) / abs(SIGMA)),
            "porosity": result["compaction"]["porosity"], "final_ezz": result["final_strain"][2],
            "spheres": result["spheres"]}


def main():
    parser = results.case_arguments(__doc__)
    parser.add_argument("--clumps", action="store_true", help="the tutorial's clump variant (makeClumpCloud)")
    args = parser.parse_args()
    import matplotlib
    matplotlib.use("Agg")
    name = "dem.periodic-triaxial-clumps" if args.clumps else "dem.periodic-triaxial"
    case = results.Case(name, quick=args.quick, folder=args.results)
    seeds = [1] if args.quick else [1, 2, 3, 4]
    if args.clumps:
        size, clumps = (QUICK_CLUMP_SIZE, QUICK_CLUMPS) if args.quick else (CLUMP_SIZE, CLUMPS)
        extra = {"clumps": clumps, "compactionRate": 1.0}
    else:
        size, extra = 2.0, {}
    ours, theirs = [], []
    for seed in seeds:
        params = {"size": size, "seed": seed, **extra}
        ours.append(analyse(twin.run(SCENARIO, params, "talus")))
        print(f"seed {seed}: Talus {ours[-1]['spheres']} spheres, porosity {ours[-1]['porosity']:.4f}, "
              f"peak sin(phi) {ours[-1]['peak']:.4f}, final ezz {ours[-1]['final_ezz']:.6f}")
        if twin.yade_available():
            theirs.append(analyse(twin.run(SCENARIO, params, "yade")))
            print(f"seed {seed}: Yade  porosity {theirs[-1]['porosity']:.4f}, peak sin(phi) {theirs[-1]['peak']:.4f}")
    case.record("worst relative gap of the cell stresses to the goal when the compaction doneHook fires",
                max(o["compaction"] for o in ours), "goal -100 kPa, PeriTriaxController relStressTol", 1e-3,
                suffix="compaction", seeds=seeds)
    case.record("worst relative deviation of the lateral stresses from -100 kPa during the compression",
                max(o["lateral"] for o in ours), "confinement -100 kPa (stressMask 3)", 0.10, suffix="lateral",
                final_ezz=[o["final_ezz"] for o in ours])
    if theirs:
        twin.record_mean_difference(case, "relative difference of the peak sin(phi) from Yade's (mean over seeds)",
                                    "peak", ours, theirs, 0.05, "peak", seeds=seeds)
        twin.record_mean_difference(case, "relative difference of the porosity after compaction from Yade's",
                                    "porosity", ours, theirs, 0.01, "porosity")

    fig, axes = twin.plot_seeds(seeds, ours, theirs, lambda r: -r["ezz"], "axial strain -ezz (log)", [
        (lambda r: r["sinphi"], "sin(phi) = (s1 - s3) / (s1 + s3)", "periodic triaxial: mobilised friction"),
        (lambda r: -r["s3"] / 1e3, "lateral stress (kPa, compression)", "confinement held by PeriTriaxController")])
    axes[1].axhline(100, color="gray", lw=.8)
    case.save_chart(fig)


if __name__ == "__main__":
    main()
