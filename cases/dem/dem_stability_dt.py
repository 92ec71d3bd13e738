"""DEM case: where the explicit step becomes unstable, and that Talus stops it instead of going on.

Run:      build/bin/talus run cases/dem/dem_stability_dt.py [--quick] [--results DIR]
Set-up:   a seeded loose cloud (makeCloud, 400 spheres; quick 200) in a box of six walls, gravity,
          frictionless FrictMat (young 1e7) and no damping, so O.energy.total() is conserved: the
          spheres fall, collide and pile up for a fixed simulated time. The step is
          dt = f * PWaveTimeStep() for f from 0.05 to 8. Each run either reaches the end or stops with
          Talus' error (a contact overlapping beyond O.maxOverlapRatio, or a non-finite force).
Checked:  dem.stability-dt.stable: worst relative energy error |E - E0| / E0 over the runs with
          f <= 0.5 (the usual safety factors), E = O.energy.total() (<= 1e-2).
          dem.stability-dt.detected: number of runs that ended with an energy error above 10 % or a
          non-finite state without being stopped (must be 0: an unstable step never goes on silently).
          dem.stability-dt.limit: smallest f at which a run was stopped (>= 0.5: the P-wave estimate
          with Yade's usual factors is on the safe side).
Produces: the records and chart dem.stability-dt.png (energy error against f, the runs Talus stopped
          marked with the step at which it stopped them; energy error against wall time).
"""
import math
import time

import numpy as np

from talus import results
from talus.dem import (FrictMat, ForceResetter, InsertionSortCollider, InteractionLoop,
                       Ip2_FrictMat_FrictMat_FrictPhys, Law2_ScGeom_FrictPhys_CundallStrack, NewtonIntegrator,
                       PWaveTimeStep, Scene, aabbWalls)
from talus.dem.packing import pack

FACTORS = (0.05, 0.1, 0.2, 0.3, 0.5, 0.7, 1.0, 1.5, 2.0, 3.0, 5.0, 8.0)
DURATION = 0.25   # s of simulated time: the cloud falls and piles up on the floor


def scene(num: int, factor: float) -> Scene:
    S = Scene()
    S.materials.append(FrictMat(young=1e7, poisson=0.3, frictionAngle=0.0, density=2600))
    S.bodies.append(aabbWalls([(0, 0, 0), (1, 1, 1)]))
    sp = pack.SpherePack()
    sp.makeCloud((0, 0, 0), (1, 1, 1), -1, 0.3, num, False, 0.8, seed=1)
    sp.toSimulation(S)
    S.engines = [ForceResetter(), InsertionSortCollider(),
                 InteractionLoop([], [Ip2_FrictMat_FrictMat_FrictPhys()], [Law2_ScGeom_FrictPhys_CundallStrack()]),
                 NewtonIntegrator(gravity=(0, 0, -9.81), damping=0.0)]
    S.dt = factor * PWaveTimeStep(S)
    S.trackEnergy = True
    return S


def run(num: int, factor: float) -> dict:
    S = scene(num, factor)
    steps = int(math.ceil(DURATION / S.dt))
    S.step()                      # energies are defined from the first step on
    e0 = abs(S.energy["gravWork"]) + S.energy["kinetic"] + 1e-300
    reference = S.energy.total()
    start, stopped, message = time.perf_counter(), None, ""
    worst = 0.0
    try:
        for _ in range(0, steps, 50):
            S.run(50)
            total = S.energy.total()
            potential = max(abs(S.energy["gravWork"]), S.energy["kinetic"], e0)
            worst = max(worst, abs(total - reference) / potential if math.isfinite(total) else math.inf)
    except RuntimeError as error:
        stopped, message = S.iter, str(error).splitlines()[0]
    wall = time.perf_counter() - start
    finite = bool(np.all(np.isfinite(S.positions())))
    return {"factor": factor, "steps": int(S.iter), "stopped": stopped, "message": message, "energy_error": worst,
            "finite": finite, "steps_per_s": S.iter / wall if wall > 0 else math.nan}


def main():
    args = results.case_arguments(__doc__).parse_args()
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    case = results.Case("dem.stability-dt", quick=args.quick, folder=args.results)
    num = 200 if args.quick else 400
    runs = [run(num, f) for f in FACTORS]
    for r in runs:
        state = f"stopped at step {r['stopped']}: {r['message'][:110]}" if r["stopped"] is not None else "ran to the end"
        print(f"f = {r['factor']:5.2f}: energy error {r['energy_error']:.3e}, {r['steps_per_s']:8.0f} steps/s, {state}")
    stable = [r["energy_error"] for r in runs if r["factor"] <= 0.5 and r["stopped"] is None]
    silent = [r["factor"] for r in runs if r["stopped"] is None and (r["energy_error"] > 0.1 or not r["finite"])]
    caught = [r["factor"] for r in runs if r["stopped"] is not None]
    case.record("worst relative energy error for f <= 0.5 (O.energy.total(), frictionless, undamped)",
                max(stable) if len(stable) == sum(f <= 0.5 for f in FACTORS) else math.inf,
                "energy conservation of the leap-frog scheme", 1e-2, suffix="stable", spheres=num,
                factors=[r["factor"] for r in runs], energy_errors=[r["energy_error"] for r in runs])
    case.record("runs ending unstable (energy error > 10 % or non-finite) without being stopped", len(silent),
                "every unstable step is detected", 0, suffix="detected", silent_factors=silent,
                stopped_factors=caught, messages=[r["message"] for r in runs if r["stopped"] is not None])
    case.record("smallest f = dt / PWaveTimeStep() at which the run was stopped", min(caught) if caught else math.inf,
                "PWaveTimeStep() with safety factors up to 0.5 is stable", 0.5, comparison=">=", suffix="limit")

    fig, (ax, cost) = plt.subplots(1, 2, figsize=(11, 4.5))
    f = np.array([r["factor"] for r in runs])
    err = np.array([r["energy_error"] for r in runs])
    ok = np.array([r["stopped"] is None for r in runs])
    ax.loglog(f[ok], err[ok], "o-", label="ran to the end")
    ax.loglog(f[~ok], np.ones((~ok).sum()), "rx", markersize=10, label="stopped by Talus (placed at 1)")
    for r in runs:
        if r["stopped"] is not None:
            ax.annotate(f"step {r['stopped']}", (r["factor"], 1.0), fontsize=7, xytext=(-10, -14),
                        textcoords="offset points")
    ax.axvline(0.5, color="grey", lw=0.8, ls=":")
    ax.set_xlabel("dt / PWaveTimeStep()")
    ax.set_ylabel("relative energy error |E - E0| / E0")
    ax.set_title(f"stability: {num} spheres falling into a box, undamped")
    ax.legend(fontsize=8)
    wall = np.array([r["steps"] / r["steps_per_s"] for r in runs])
    cost.loglog(wall[ok], err[ok], "o-")
    for r, w in zip(runs, wall):
        if r["stopped"] is None:
            cost.annotate(f"f={r['factor']:g}", (w, r["energy_error"]), fontsize=7, xytext=(4, 2),
                          textcoords="offset points")
    cost.set_xlabel(f"wall time for {DURATION} s simulated [s]")
    cost.set_ylabel("relative energy error")
    cost.set_title("accuracy against cost")
    fig.tight_layout()
    case.save_chart(fig)


if __name__ == "__main__":
    main()
