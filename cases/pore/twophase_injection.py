"""Two-phase flow case: the dynamic injection of Yade's TwoPhaseFlowInjection.py (wetting fluid
pushed into a dry packing through the clusters of TwoPhaseFlowEngine), Talus against Yade on the
same packing, same invocation.

Run:      build/bin/talus run cases/pore/twophase_injection.py [--quick] [--results DIR]
Set-up:   the seeded 1 000-sphere cloud of cases/pore/twophase_drainage.py (makeCloud, rMean 0.035,
          rRelFuzz 0.3, unit cube); cases/yade/twophase/twophase_injection.py, run unchanged by both
          programs, puts it in the walls of its bounding box, imposes 1 000 Pa of wetting fluid
          (viscosity 0.1) on ymin, fills the pores below a third of the height through the
          reservoir cluster, then advances the menisci of the cluster's interfaces by their
          fluxes (updateCapVolList), lets a dry pore whose interfaces brought its void volume join
          the cluster (clusterOutvadePore, the excess passed on to its own interfaces) and solves
          the cluster's pressures (solvePressure), every step of 2e-5 s: 400 steps (quick), 2 000
          (full: past the complete imbibition).
Checked:  twophase.injection: the largest difference over the records (every 20 steps) of the
          imbibed fraction of the initially dry pore volume (imbibed pores + menisci over it)
          from Yade's (absolute, <= 0.01, as twophase.drainage's saturations), with the injected
          volumes (getBoundaryFlux integrated) and the wet pore counts of both. Without yade the
          record is skipped.
          twophase.injection.speed: Yade's CPU time over the injection steps over Talus's (each one
          thread, same invocation; the scenario's own Python loop, which both programs run, is in
          both), >= 3.
Produces: the record and twophase.injection.png (imbibed fraction and injected volume over time).
"""
import os
import tempfile
import time
from pathlib import Path

import numpy as np

from talus import results
from talus import twin
from twophase_drainage import cloud  # the drainage case's packing

SCENARIO = Path(__file__).resolve().parents[1] / "yade" / "twophase" / "twophase_injection.py"
DT = 2e-5
EVERY = 20


def main():
    args = results.case_arguments(__doc__).parse_args()
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    case = results.Case("twophase.injection", quick=args.quick, folder=args.results)
    if not twin.yade_available():
        print("yade not installed: no comparison, no record")
        return
    steps = 400 if args.quick else 2000
    with tempfile.TemporaryDirectory() as tmp:
        params = {"packing": str(cloud(1000, Path(tmp))), "steps": steps, "dt": DT, "every": EVERY,
                  "pressure": 1000.0, "viscosity": 0.1}
        t0 = time.perf_counter()
        ours = twin.run(SCENARIO, params, "talus")
        t1 = time.perf_counter()
        theirs = twin.run(SCENARIO, params, "yade")
        t2 = time.perf_counter()
    print(f"cells Talus {ours['nCells']}, Yade {theirs['nCells']}; dry pores {ours['dry0']}, {theirs['dry0']}; "
          f"run Talus {t1 - t0:.1f} s, Yade {t2 - t1:.1f} s")
    t = np.array([r["step"] for r in ours["records"]]) * DT
    fraction = {name: np.array([r["stored"] for r in run["records"]]) / run["dryVolume"]
                for name, run in (("talus", ours), ("yade", theirs))}
    injected = {name: np.array([r["injected"] for r in run["records"]]) for name, run in (("talus", ours),
                                                                                          ("yade", theirs))}
    wet = {name: [r["wet"] for r in run["records"]] for name, run in (("talus", ours), ("yade", theirs))}
    gap = float(np.max(np.abs(fraction["talus"] - fraction["yade"])))
    injected_gap = float(np.max(np.abs(injected["talus"] - injected["yade"]) / injected["yade"]))
    print(f"largest difference of the imbibed fraction {gap:.3g}, of the injected volume (relative) "
          f"{injected_gap:.3g}; wet pores equal at every record: {wet['talus'] == wet['yade']}; "
          f"final imbibed fraction Talus {fraction['talus'][-1]:.4f}, Yade {fraction['yade'][-1]:.4f}")
    case.record("largest difference of the imbibed fraction of the dry pore volume from Yade's over the injection",
                gap, "yade 2023.02a TwoPhaseFlowEngine clusters (TwoPhaseFlowInjection.py's scheme), same packing",
                0.01, steps=steps, dt=DT, injected_volume_relative_difference=injected_gap,
                wet_pores_equal=wet["talus"] == wet["yade"], talus_wet=wet["talus"], yade_wet=wet["yade"],
                talus_fraction=fraction["talus"].tolist(), yade_fraction=fraction["yade"].tolist(),
                talus_run_s=t1 - t0, yade_run_s=t2 - t1)
    speed = theirs["stepsCpu"] / ours["stepsCpu"]
    print(f"CPU over the injection steps: Talus {ours['stepsCpu']:.3f} s, Yade {theirs['stepsCpu']:.3f} s, "
          f"ratio {speed:.2f}")
    case.record("Yade CPU time over Talus's, injection steps (clusters' solves, scenario loop), 1 thread each", speed,
                "yade 2023.02a TwoPhaseFlowEngine clusters, same scenario and packing, same invocation", 3.0,
                suffix="speed", comparison=">=", steps=steps, talus_cpu_s=ours["stepsCpu"],
                yade_cpu_s=theirs["stepsCpu"], load_average=list(os.getloadavg()))
    fig, ax = plt.subplots(figsize=(6.5, 4.5))
    ax.plot(t, fraction["talus"], "-", label="Talus, imbibed fraction")
    ax.plot(t, fraction["yade"], "o", ms=3, mfc="none", label="Yade, imbibed fraction")
    ax.plot(t, injected["talus"] / ours["dryVolume"], "--", label="Talus, injected volume / dry volume")
    ax.plot(t, injected["yade"] / theirs["dryVolume"], "s", ms=3, mfc="none", label="Yade, injected volume / dry volume")
    ax.set_xlabel("time (s)")
    ax.set_ylabel("fraction of the initially dry pore volume")
    ax.set_title("dynamic injection through the wetting cluster (1 000 spheres)")
    ax.legend()
    fig.tight_layout()
    case.save_chart(fig)


if __name__ == "__main__":
    main()
