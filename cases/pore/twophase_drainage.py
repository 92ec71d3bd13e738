"""Two-phase flow case: quasi-static primary drainage, Talus's TwoPhaseFlowEngine against Yade's
on the same packing, same invocation.

Run:      build/bin/talus run cases/pore/twophase_drainage.py [--quick] [--results DIR]
Set-up:   a seeded loose cloud (makeCloud, rMean 0.035, rRelFuzz 0.3) of 1 000 spheres (full mode:
          also 5 000), written to a file; cases/yade/twophase/twophase_drainage.py, run unchanged by both
          programs, puts the spheres in the walls of their bounding box, the wetting reservoir on
          ymin and the non-wetting one on ymax (pressure 0), surfaceTension 0.0728, MS-P entry
          pressures (entryPressureMethod 1), trapped wetting phase (isPhaseTrapped), and drains by
          raising the capillary pressure pc = -bndCondValue[2] in 60 steps from 0.2 to 4
          surfaceTension / mean diameter (the whole drainage of this loose packing, down to its
          residual saturation), invasion() and getSaturation() at each step, then back down the
          same steps with imbibition on (the main imbibition). Each program times initialization()
          + the drainage steps (process CPU time, single-threaded, median of 3 fresh scenes).
Checked:  twophase.drainage: the largest difference of the saturation from Yade's over the steps
          (absolute, saturation being a fraction; <= 0.01); twophase.drainage.imbibition: the same
          over the imbibition steps; twophase.drainage.speed-<n>: Yade's time over Talus's for the
          drainage (>= 3); twophase.drainage.clusters: on the 1 000-sphere cloud, an invasion() at
          pc = 2 surfaceTension / d with isCellLabelActivated then 400 pores drained one at a time
          by clusterInvadePore (cases/yade/twophase/twophase_cluster_invasion.py): the share of the steps
          (pore drained, labels returned), final pore labels and cluster pore/interface lists that
          differ from Yade's (= 0). Without yade the records are skipped.
Produces: the records and twophase.drainage.png (the capillary pressure-saturation curves of both).
"""
import tempfile
import time
from pathlib import Path

import numpy as np

from talus import results
from talus import twin
from talus.dem.packing.pack import SpherePack

SCENARIO = Path(__file__).resolve().parents[1] / "yade" / "twophase" / "twophase_drainage.py"
CLUSTERS = Path(__file__).resolve().parents[1] / "yade" / "twophase" / "twophase_cluster_invasion.py"
GAMMA = 0.0728
R_MEAN = 0.035
STEPS = 60


def cloud(num: int, folder: Path) -> Path:
    side = (num / 1000) ** (1 / 3)
    sp = SpherePack()
    sp.makeCloud((0, 0, 0), (side, side, side), rMean=R_MEAN, rRelFuzz=0.3, num=num, seed=1)
    if len(sp) != num:
        raise SystemExit(f"twophase_drainage: makeCloud placed {len(sp)} of {num} spheres")
    path = folder / f"cloud{num}.txt"
    sp.save(str(path))
    return path


def record_cluster_invasion(case, packing: str, pc: float, invasions: int = 400):
    """Pores drained one at a time through the clusters (clusterInvadePore, with the splits)
    after an invasion() at `pc`, in both programs: the share of the steps and of the final pore
    labels and cluster lists that differ from Yade's."""
    params = {"packing": packing, "pc": pc, "invasions": invasions}
    ours, theirs = twin.run(CLUSTERS, params, "talus"), twin.run(CLUSTERS, params, "yade")
    steps = [a != b for a, b in zip(ours["steps"], theirs["steps"])] + [len(ours["steps"]) != len(theirs["steps"])]
    labels = [ours["labels"].get(k) != v for k, v in theirs["labels"].items()]
    clusters = [(a["pores"], a["interfaces"]) != (b["pores"], b["interfaces"])
                for a, b in zip(ours["clusters"], theirs["clusters"])] + [len(ours["clusters"]) != len(theirs["clusters"])]
    splits = sum(len(s["returned"]) > 1 for s in theirs["steps"])
    differing = (sum(steps) + sum(labels) + sum(clusters)) / (len(steps) + len(labels) + len(clusters))
    print(f"  clusterInvadePore: {len(theirs['steps'])} pores drained ({splits} splits), {len(theirs['clusters'])} "
          f"clusters; differing steps {sum(steps)}, labels {sum(labels)}, clusters {sum(clusters)}")
    case.record(f"share of clusterInvadePore steps, pore labels and cluster pore/interface lists differing from Yade's "
                f"({invasions} pores drained after invasion at pc = 2 surfaceTension / d)", differing,
                "yade 2023.02a TwoPhaseFlowEngine clusters, same scenario and packing", 0.0, suffix="clusters",
                invasions=len(theirs["steps"]), splits=splits, clusters=len(theirs["clusters"]), pores=len(labels))


def main():
    args = results.case_arguments(__doc__).parse_args()
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    case = results.Case("twophase.drainage", quick=args.quick, folder=args.results)
    if not twin.yade_available():
        print("yade not installed: no comparison, no record")
        return
    sizes = [1000] if args.quick else [1000, 5000]
    scale = GAMMA / (2 * R_MEAN)  # pc unit: surfaceTension / mean diameter
    pcs = list(np.linspace(0.2, 4, STEPS) * scale)
    fig, ax = plt.subplots(figsize=(6.5, 4.5))
    worst = worst_imbibition = None
    with tempfile.TemporaryDirectory() as tmp:
        for n in sizes:
            params = {"packing": str(cloud(n, Path(tmp))), "pcs": pcs, "imbibition_pcs": pcs[::-1],
                      "surfaceTension": GAMMA,
                      "entryPressureMethod": 1, "isPhaseTrapped": True, "repeats": 3}
            t0 = time.perf_counter()
            ours = twin.run(SCENARIO, params, "talus")
            theirs = twin.run(SCENARIO, params, "yade")
            print(f"{n} spheres: both runs {time.perf_counter() - t0:.1f} s; cells Talus {ours['nCells']}, "
                  f"Yade {theirs['nCells']}")
            sw, sy = np.array(ours["saturations"]), np.array(theirs["saturations"])
            gap = float(np.max(np.abs(sw - sy)))
            step = int(np.argmax(np.abs(sw - sy)))
            print(f"  largest saturation difference {gap:.3g} at pc* = {pcs[step] / scale:.2f}; "
                  f"final Sw Talus {sw[-1]:.4f}, Yade {sy[-1]:.4f}")
            iw, iy = np.array(ours["imbibition"]), np.array(theirs["imbibition"])
            imbibition_gap = float(np.max(np.abs(iw - iy)))
            print(f"  imbibition: largest saturation difference {imbibition_gap:.3g}; final Sw {iw[-1]:.4f}")
            if worst is None or gap > worst[0]:
                worst = (gap, n, sw.tolist(), sy.tolist())
            if worst_imbibition is None or imbibition_gap > worst_imbibition[0]:
                worst_imbibition = (imbibition_gap, n)
            ratio = theirs["cpu_s"] / ours["cpu_s"]
            print(f"  drainage CPU time: Talus {ours['cpu_s']:.3f} s, Yade {theirs['cpu_s']:.3f} s, ratio {ratio:.1f}")
            case.record(f"speed ratio Yade / Talus, initialization + {STEPS} drainage steps ({n} spheres, 1 thread, "
                        "CPU time)", ratio, "yade 2023.02a TwoPhaseFlowEngine, same scenario file", 3.0,
                        comparison=">=", suffix=f"speed-{n}", talus_cpu_s=ours["cpu_s"], yade_cpu_s=theirs["cpu_s"],
                        talus_wall_s=ours["wall_s"], yade_wall_s=theirs["wall_s"])
            if n == sizes[0]:
                record_cluster_invasion(case, params["packing"], 2 * scale)
            ax.plot(sw, np.array(pcs) / scale, "-", label=f"Talus drainage, {n} spheres")
            ax.plot(sy, np.array(pcs) / scale, "o", ms=3, mfc="none", label=f"Yade drainage, {n} spheres")
            ax.plot(iw, np.array(pcs[::-1]) / scale, "-", label=f"Talus imbibition, {n} spheres")
            ax.plot(iy, np.array(pcs[::-1]) / scale, "s", ms=3, mfc="none", label=f"Yade imbibition, {n} spheres")
    gap, n, sw, sy = worst
    case.record("largest difference of the wetting saturation from Yade's over the drainage steps",
                gap, "yade 2023.02a TwoPhaseFlowEngine (MS-P, trapped phase), same packing and boundaries", 0.01,
                spheres=n, steps=STEPS, pc_over_gamma_d=[p / scale for p in pcs], talus=sw, yade=sy)
    case.record("largest difference of the wetting saturation from Yade's over the imbibition steps that follow",
                worst_imbibition[0], "yade 2023.02a TwoPhaseFlowEngine (isImbibitionActivated), same packing", 0.01,
                suffix="imbibition", spheres=worst_imbibition[1])
    ax.set_xlabel("wetting saturation $S_w$")
    ax.set_ylabel("capillary pressure $p_c d / \\gamma$")
    ax.set_title("primary drainage and main imbibition (MS-P entry pressures)")
    ax.legend()
    fig.tight_layout()
    case.save_chart(fig)


if __name__ == "__main__":
    main()
