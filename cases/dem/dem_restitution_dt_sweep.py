"""DEM case: restitution error against cost over the time-step safety factor.

Run:      build/bin/talus run cases/dem/dem_restitution_dt_sweep.py [--quick] [--results DIR]
Set-up:   N head-on collisions at once (pairs of spheres, radius 1 cm, density 2600, 1 m/s
          closing speed, far apart from each other; N = 400, quick 100), no gravity, no damping:
          1. visco-elastic contacts (ViscElMat tc = 1 ms, en = et = 0.5): reference en itself;
          2. Hertz-Mindlin (FrictMat young 1e8, poisson 0.3, Ip2_FrictMat_FrictMat_MindlinPhys
             en = 0.5): reference the same contact model integrated to 1e-12
             (talus.dem.analysis.analytic.hertz_restitution);
          3. elastic Hertz (no damping): the kinetic energy after the collision, reference 1.
          dt = tc / n for n = 5 ... 2000 (quick ... 500), tc the contact duration.
Checked:  dem.restitution-dt-sweep.viscoelastic: observed order of the restitution error in dt
          over the finest steps >= 0.9 (the dashpot sees the half-step velocity: first order);
          dem.restitution-dt-sweep.hertz: restitution error at the finest step <= 1e-3 (its
          error changes sign near tc/200, where a first-order dashpot lag and the error of the
          contact's discrete start cancel, so no order is fitted); dem.restitution-dt-sweep.elastic:
          worst relative energy error of the elastic collision at n >= 50 <= 1e-4.
Produces: the three records and chart dem.restitution-dt-sweep.png (error against dt / tc and
          against the wall time per collision, with the steps per second of each run).
"""
import math
import time

import numpy as np

from talus import results
from talus.dem import (FrictMat, ForceResetter, InsertionSortCollider, InteractionLoop,
                       Ip2_FrictMat_FrictMat_MindlinPhys, Ip2_ViscElMat_ViscElMat_ViscElPhys,
                       Law2_ScGeom_MindlinPhys_Mindlin, Law2_ScGeom_ViscElPhys_Basic, NewtonIntegrator, Scene,
                       ViscElMat, sphere)
from talus.dem.analysis.analytic import hertz_contact_time, hertz_restitution, thornton_damping_ratio

R, RHO, V0 = 0.01, 2600.0, 1.0
YOUNG, POISSON, EN = 1e8, 0.3, 0.5
MASS = RHO * 4 / 3 * math.pi * R ** 3
KNO = 4 / 3 * YOUNG / (2 * (1 - POISSON ** 2)) * math.sqrt(R / 2)   # two equal spheres: R* = R/2
TC_HERTZ = hertz_contact_time(MASS / 2, KNO, V0)                       # reduced mass of a free pair
TC_VISCO = 1e-3


def collisions(model: str, pairs: int, divisions: int) -> tuple[float, float, float, float]:
    """Run `pairs` head-on collisions at dt = tc / divisions; returns (restitution, kinetic energy
    after / before, wall time per collision, steps per second)."""
    S = Scene()
    if model == "viscoelastic":
        m = S.materials.append(ViscElMat(tc=TC_VISCO, en=EN, et=EN, density=RHO, frictionAngle=0.5))
        laws = ([Ip2_ViscElMat_ViscElMat_ViscElPhys()], [Law2_ScGeom_ViscElPhys_Basic()])
        tc = TC_VISCO
    else:
        m = S.materials.append(FrictMat(young=YOUNG, poisson=POISSON, density=RHO, frictionAngle=0.5))
        params = {"en": EN} if model == "hertz" else {}
        laws = ([Ip2_FrictMat_FrictMat_MindlinPhys(**params)], [Law2_ScGeom_MindlinPhys_Mindlin()])
        tc = TC_HERTZ
    side = math.ceil(math.sqrt(pairs))
    for k in range(pairs):
        x, y = 4 * R * (k % side), 4 * R * (k // side)
        S.bodies.append([sphere((x, y, 0), R, material=m), sphere((x, y, 2 * R + 1e-7), R, material=m)])
    v = S.velocities()
    v[0::2, 2], v[1::2, 2] = 0.5 * V0, -0.5 * V0
    S.engines = [ForceResetter(), InsertionSortCollider(), InteractionLoop([], *laws), NewtonIntegrator(damping=0.0)]
    S.dt = tc / divisions
    before = 0.5 * MASS * float((S.velocities() ** 2).sum())
    steps = 0
    start = time.perf_counter()
    touched = False
    while True:
        chunk = max(divisions // 10, 1)
        S.run(chunk)
        steps += chunk
        contacts = S._cpp.realContactCount()
        touched = touched or contacts > 0
        if touched and contacts == 0:
            break
    wall = time.perf_counter() - start
    v = S.velocities()
    restitution = float(np.mean(v[1::2, 2] - v[0::2, 2])) / V0
    after = 0.5 * MASS * float((v ** 2).sum())
    return restitution, after / before, wall / pairs, steps / wall


def order(dts, errors) -> float:
    return float(np.polyfit(np.log(dts[-4:]), np.log(errors[-4:]), 1)[0])


def main():
    args = results.case_arguments(__doc__).parse_args()
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    case = results.Case("dem.restitution-dt-sweep", quick=args.quick, folder=args.results)
    pairs = 100 if args.quick else 400
    divisions = [5, 10, 20, 50, 100, 200, 500] + ([] if args.quick else [1000, 2000])
    reference = {"viscoelastic": EN,
                 "hertz": hertz_restitution(MASS / 2, KNO, thornton_damping_ratio(EN), V0),
                 "elastic": 1.0}
    runs = {}
    for model in ("viscoelastic", "hertz", "elastic"):
        rows = []
        for n in divisions:
            e, energy, cost, rate = collisions(model, pairs, n)
            error = abs((energy if model == "elastic" else e) - reference[model]) / reference[model]
            rows.append((n, error, cost, rate))
            print(f"{model:12s} dt = tc/{n:<5d} error {error:.3e}  {cost * 1e3:8.3f} ms/collision  {rate:9.0f} steps/s")
        runs[model] = rows

    n, err, cost, rate = map(list, zip(*runs["viscoelastic"]))
    case.record("observed order in dt of the visco-elastic restitution error (first order expected)",
                order([1 / k for k in n], err), "en itself", 0.9, comparison=">=", suffix="viscoelastic",
                dt_over_tc=[1 / k for k in n], errors=err, wall_s_per_collision=cost, steps_per_s=rate, pairs=pairs)
    n, err, cost, rate = map(list, zip(*runs["hertz"]))
    case.record(f"relative restitution error of Hertz-Mindlin (en = {EN}) at dt = tc/{n[-1]}", err[-1],
                "the damped Hertz contact integrated to 1e-12 (talus.dem.analysis.analytic.hertz_restitution)", 1e-3,
                suffix="hertz", dt_over_tc=[1 / k for k in n], errors=err, wall_s_per_collision=cost,
                steps_per_s=rate, pairs=pairs)
    n, err, cost, rate = map(list, zip(*runs["elastic"]))
    worst = max(e for k, e in zip(n, err) if k >= 50)
    case.record("worst relative kinetic-energy error of an elastic Hertz collision at dt <= tc/50", worst,
                "energy conservation (no damping, no friction)", 1e-4, suffix="elastic",
                dt_over_tc=[1 / k for k in n], errors=err, wall_s_per_collision=cost, steps_per_s=rate, pairs=pairs)

    fig, (ax1, ax2) = plt.subplots(1, 2, figsize=(11, 4.2))
    styles = {"viscoelastic": "bo-", "hertz": "rs-", "elastic": "g^-"}
    labels = {"viscoelastic": "visco-elastic, restitution", "hertz": "Hertz-Mindlin en = 0.5, restitution",
              "elastic": "elastic Hertz, energy"}
    for model, rows in runs.items():
        n, err, cost, rate = map(np.array, zip(*rows))
        err = np.maximum(err, 1e-16)
        ax1.loglog(1 / n, err, styles[model], label=labels[model])
        ax2.loglog(cost * 1e3, err, styles[model], label=labels[model])
        for k, c, e, r in zip(n, cost, err, rate):
            ax2.annotate(f"tc/{k}\n{r / 1e3:.0f}k st/s", (c * 1e3, e), textcoords="offset points", xytext=(3, 2),
                         fontsize=6)
    ax1.set_xlabel("dt / tc (tc: contact duration)")
    ax1.set_ylabel("relative error")
    ax1.set_title("error against the time-step safety factor")
    ax1.legend(fontsize=8)
    ax2.set_xlabel(f"wall time per collision (ms), {pairs} collisions at once")
    ax2.set_ylabel("relative error")
    ax2.set_title("error against cost (steps per second annotated)")
    fig.tight_layout()
    case.save_chart(fig)


if __name__ == "__main__":
    main()
