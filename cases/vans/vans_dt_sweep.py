"""VANS case: error versus cost over the fluid time step, and the scheme past its limits.

Run:      build/bin/talus run cases/vans/vans_dt_sweep.py [--quick] [--results DIR]
Set-up:   1. Accuracy in time: a laminar film (water, nu 1e-6, 1 cm deep, 0.01 rad slope, free
             surface, iturbu = 0) starting from rest, observed at T = 5 s = 0.05 h^2/nu while it
             still accelerates; 1001 cells; dt = T/2 ... T/5000 (quick: ... T/1000). Compared with
             the series solution u = u_s(z) - sum_k 2 g_x/(nu h l_k^3) sin(l_k z) exp(-nu l_k^2 t),
             l_k = (2k+1) pi/(2h), u_s = g_x/nu (h z - z^2/2), at the time actually reached
             (lastStepCount dt: Yade's loop may take one step more than T/dt).
          2. Stability past the explicit limit: the same film run to its steady state (5000 s, at
             least 20 steps) with dt = 1e4 ... 1e9 times the explicit diffusion limit
             deltaZ^2/(2 nu) = 5e-5 s.
          3. The lagged eddy viscosity: the turbulent set-up of cases/vans/vans_loglaw.py (ilm = 1,
             viscous sub-layer, 10001 cells; quick 5001) from rest for 1000 s, dt = 0.05 ... 100 s,
             compared with its dt = 0.05 s result.
Checked:  vans.dt-sweep: observed order of the time error in part 1 >= 0.9 (backward Euler, 1).
          vans.dt-sweep.stability: worst relative RMS error of the steady film in part 2, against
          u_s, <= 1e-5 (what remains is the spatial error): no time-step limit.
          vans.dt-sweep.oscillation: in part 3, number of runs off by more than 1e-3 that
          fluidResolution did not flag as oscillating (``VansFluid.oscillating``, a warning):
          must be 0. Past dt of order the turbulent time scale h/(kappa u*) ~ 1 s, the lagged
          eddy viscosity flip-flops around the steady state instead of reaching it; the failure
          must be reported, never silent.
Produces: the three records and chart vans.dt-sweep.png (error against wall time for parts 1
          and 3, steady error against dt for part 2).
"""
import importlib.util
import math
import time
import warnings
from pathlib import Path

import numpy as np

from talus import results
from talus.flow import VansFluid, slope_gravity

NU, RHO = 1e-6, 1e3
FILM_H, FILM_SLOPE, FILM_T, FILM_CELLS = 0.01, 0.01, 5.0, 1001
GX = abs(slope_gravity(FILM_SLOPE)[0])


def film(dt: float, tfin: float) -> tuple[VansFluid, float]:
    fluid = VansFluid(nCell=FILM_CELLS, deltaZ=FILM_H / (FILM_CELLS - 1), densFluid=RHO, viscoDyn=NU * RHO,
                      gravity=slope_gravity(FILM_SLOPE), iturbu=0, iusl=1)
    start = time.perf_counter()
    fluid.fluidResolution(tfin, dt)
    return fluid, time.perf_counter() - start


def film_steady(z: np.ndarray) -> np.ndarray:
    return GX / NU * (FILM_H * z - 0.5 * z * z)


def film_exact(z: np.ndarray, t: float) -> np.ndarray:
    u = film_steady(z)
    for k in range(400):  # exp(-nu l_k^2 t) is below 1e-300 long before k = 400 at t = 5 s
        lk = (2 * k + 1) * math.pi / (2 * FILM_H)
        u -= 2 * GX / (NU * FILM_H * lk ** 3) * np.sin(lk * z) * math.exp(-NU * lk * lk * t)
    return u


def rel_rms(u: np.ndarray, ref: np.ndarray) -> float:
    return float(np.sqrt(np.mean((u - ref) ** 2)) / np.sqrt(np.mean(ref ** 2)))


def loglaw_module():
    """cases/vans/vans_loglaw.py, for its set-up (aligned grid) rather than a copy of it."""
    spec = importlib.util.spec_from_file_location("vans_loglaw", Path(__file__).with_name("vans_loglaw.py"))
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def main():
    args = results.case_arguments(__doc__).parse_args()
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    case = results.Case("vans.dt-sweep", quick=args.quick, folder=args.results)

    # 1. Time accuracy on the accelerating film.
    divisions = [2, 5, 10, 20, 50, 100, 200, 500, 1000] + ([] if args.quick else [2000, 5000])
    dts, errors, walls = [], [], []
    for m in divisions:
        dt = FILM_T / m
        fluid, wall = min((film(dt, FILM_T) for _ in range(3)), key=lambda fw: fw[1])
        reached = fluid.lastStepCount * dt
        dts.append(dt)
        errors.append(rel_rms(fluid.vxFluid, film_exact(fluid.zFluid, reached)))
        walls.append(wall)
        print(f"film dt = T/{m:<5d} steps {fluid.lastStepCount:5d}  error {errors[-1]:.3e}  {wall * 1e3:8.2f} ms")
    order = float(np.polyfit(np.log(dts[-4:]), np.log(errors[-4:]), 1)[0])
    case.record("observed order in dt of the transient film error (backward Euler: 1)", order,
                "series solution of the laminar film started from rest", 0.9, comparison=">=",
                dt=dts, errors=errors, wall_s_per_resolution=walls, cells=FILM_CELLS)
    print(f"observed order {order:.2f}")

    # 2. Past the explicit limit: the steady film with huge steps.
    dt_explicit = (FILM_H / (FILM_CELLS - 1)) ** 2 / (2 * NU)
    factors = [1e4, 1e5, 1e6, 1e7, 1e8, 1e9]
    steady_errors = []
    for factor in factors:
        # long enough to settle: 50 viscous times h^2/nu, and at least 20 steps
        fluid, _ = film(factor * dt_explicit, max(5000.0, 20 * factor * dt_explicit))
        steady_errors.append(rel_rms(fluid.vxFluid, film_steady(fluid.zFluid)))
        print(f"steady film, dt = {factor:.0e} x explicit limit ({factor * dt_explicit:.3g} s, "
              f"{fluid.lastStepCount} steps): error {steady_errors[-1]:.2e}")
    case.record("worst relative RMS error of the steady film for dt = 1e4 ... 1e9 x the explicit limit",
                max(steady_errors), "steady film profile g_x/nu (h z - z^2/2)", 1e-5, suffix="stability",
                dt_over_explicit_limit=factors, errors=steady_errors)

    # 3. The lagged eddy viscosity on the turbulent steady flow.
    loglaw = loglaw_module()
    n_cell, sub_cells = (5001, 2) if args.quick else (10001, 5)
    h = loglaw.aligned_depth(n_cell, sub_cells)
    turbulent_dts = [0.05, 0.1, 0.2, 0.5, 1, 2, 5, 10, 20, 50, 100]
    runs = []
    for dt in turbulent_dts:
        fluid = VansFluid(nCell=n_cell, deltaZ=h / (n_cell - 1), densFluid=RHO, viscoDyn=NU * RHO,
                          gravity=slope_gravity(loglaw.ALPHA), iturbu=1, ilm=1, iusl=1, viscousSubLayer=1)
        with warnings.catch_warnings(record=True) as caught:
            warnings.simplefilter("always")
            start = time.perf_counter()
            fluid.fluidResolution(1000.0, dt)
            wall = time.perf_counter() - start
        warned = any("flip-flops" in str(w.message) for w in caught)
        runs.append((dt, fluid.vxFluid, wall, fluid.oscillating and warned))
    reference = runs[0][1]
    turbulent_errors = [rel_rms(u, reference) for _, u, _, _ in runs]
    silent = 0
    for (dt, _, wall, flagged), err in zip(runs, turbulent_errors):
        if err > 1e-3 and not flagged:
            silent += 1
        print(f"turbulent dt = {dt:6.2f} s  error {err:.2e}  {'OSCILLATING (warned)' if flagged else 'converged':22s}"
              f"{wall:7.3f} s")
    case.record("turbulent runs off by more than 1e-3 without an oscillation warning", silent,
                f"the dt = 0.05 s solution, {n_cell} cells", 0, suffix="oscillation",
                dt=turbulent_dts, errors=turbulent_errors, flagged=[r[3] for r in runs],
                wall_s_per_resolution=[r[2] for r in runs])

    # Chart.
    fig, axes = plt.subplots(1, 3, figsize=(14, 4.2))
    ax = axes[0]
    ax.loglog(walls, errors, "o-")
    for m, w, e in zip(divisions, walls, errors):
        ax.annotate(f"T/{m}", (w, e), textcoords="offset points", xytext=(4, 2), fontsize=7)
    ax.set_xlabel("wall time of fluidResolution (s)")
    ax.set_ylabel("relative RMS error at T")
    ax.set_title(f"1. laminar film at T = 5 s: order {order:.2f} in dt")
    ax = axes[1]
    ax.loglog(factors, steady_errors, "s-")
    ax.axhline(1e-5, color="gray", ls="--", lw=0.8, label="tolerance")
    ax.set_xlabel("dt / explicit limit $\\Delta z^2/(2\\nu)$")
    ax.set_ylabel("relative RMS error of the steady film")
    ax.set_ylim(1e-8, 1e-3)
    ax.set_title("2. no time-step limit (implicit)")
    ax.legend()
    ax = axes[2]
    walls3 = [r[2] for r in runs]
    flags = np.array([r[3] for r in runs])
    errs3 = np.maximum(turbulent_errors, 1e-12)
    ax.loglog(np.array(walls3)[~flags], errs3[~flags], "go", label="converged")
    ax.loglog(np.array(walls3)[flags], errs3[flags], "rx", ms=8, label="flagged: oscillating")
    for dt, w, e in zip(turbulent_dts, walls3, errs3):
        ax.annotate(f"{dt:g} s", (w, e), textcoords="offset points", xytext=(4, 2), fontsize=7)
    ax.axhline(1e-3, color="gray", ls="--", lw=0.8)
    ax.set_xlabel("wall time of fluidResolution (s), 1000 s simulated")
    ax.set_ylabel("relative RMS difference to dt = 0.05 s")
    ax.set_title("3. turbulent (lagged eddy viscosity)")
    ax.legend(fontsize=8)
    fig.tight_layout()
    case.save_chart(fig)


if __name__ == "__main__":
    main()
