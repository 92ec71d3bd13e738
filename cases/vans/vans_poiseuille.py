"""VANS case: laminar Poiseuille flow, no particles, against the analytic profile.

Run:      build/bin/talus run cases/vans/vans_poiseuille.py [--quick] [--results DIR]
Set-up:   Yade's fluidValidation/poiseuille.py: water (rho 1000 kg/m^3, nu 1e-6 m^2/s) between two
          fixed walls 1 m apart (no-slip bottom, iusl = 0 with uTop = 0), driven by dpdx = -0.1 Pa/m,
          no turbulence (iturbu = 0); resolved from rest for 1e7 s with steps of 1e4 s (ten viscous
          times h^2/nu, so the profile is steady).
Checked:  u(z) = -dpdx/(2 mu) z (h - z) at the nCell + 1 velocity nodes, 201 cells: relative RMS
          error < 1e-4 (Yade's own script uses 101 cells and accepts 0.15 %). Then the cell count
          is swept (11 ... 1601 cells; quick: 11 ... 401): the observed order in deltaZ must be >= 1.9
          (the finite-volume scheme is second order, its wall half-cells included).
Produces: records vans.poiseuille and vans.poiseuille.order; charts vans.poiseuille.profile.png
          (numeric and analytic profiles) and vans.poiseuille.cost.png (error versus wall time
          over the cell count).
"""
import time

import numpy as np

from talus import results
from talus.flow import VansFluid

H, DPDX, RHO, NU = 1.0, -0.10, 1e3, 1e-6
TFIN, DT = 1e7, 1e4


def solve(n_cell: int) -> tuple[VansFluid, float]:
    """Steady Poiseuille flow on n_cell cells; returns the solver and the wall time of the call."""
    fluid = VansFluid(nCell=n_cell, deltaZ=H / (n_cell - 1), densFluid=RHO, viscoDyn=NU * RHO,
                      dpdx=DPDX, gravity=(0.0, 0.0, -9.81), iturbu=0, iusl=0, uTop=0.0)
    start = time.perf_counter()
    fluid.fluidResolution(TFIN, DT)
    return fluid, time.perf_counter() - start


def analytic(z: np.ndarray) -> np.ndarray:
    return -DPDX / (2 * NU * RHO) * z * (H - z)


def rms_error(fluid: VansFluid) -> float:
    exact = analytic(fluid.zFluid)
    return float(np.sqrt(np.mean((fluid.vxFluid - exact) ** 2)) / np.sqrt(np.mean(exact ** 2)))


def main():
    args = results.case_arguments(__doc__).parse_args()
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    # 1. The validation point: 201 cells.
    case = results.Case("vans.poiseuille", quick=args.quick, folder=args.results)
    fluid, wall = solve(201)
    err = rms_error(fluid)
    case.record("relative RMS error of the steady velocity profile (201 cells)", err,
                "analytic Poiseuille profile -dpdx/(2 mu) z (h - z)", 1e-4, cells=201, wall_resolution_s=wall)
    print(f"Poiseuille, 201 cells: relative RMS error {err:.3e} ({wall * 1e3:.1f} ms)")

    fig, ax = plt.subplots(figsize=(5, 4))
    z = np.linspace(0, H, 400)
    ax.plot(analytic(z), z, "r-", lw=2, label="analytic")
    ax.plot(fluid.vxFluid[::5], fluid.zFluid[::5], "bo", ms=3, label="Talus VANS (every 5th node)")
    ax.set_xlabel("$u_x^f$ (m/s)")
    ax.set_ylabel("z (m)")
    ax.set_title(f"Poiseuille flow, 201 cells: RMS error {err:.1e}")
    ax.legend()
    case.save_chart(fig, "profile")

    # 2. Error versus cost over the cell count; observed order from the finest pairs.
    counts = [11, 26, 51, 101, 201, 401] + ([] if args.quick else [801, 1601])
    errors, walls = [], []
    for n in counts:
        f, w = min((solve(n) for _ in range(3)), key=lambda fw: fw[1])
        errors.append(rms_error(f))
        walls.append(w)
        print(f"  {n:5d} cells: error {errors[-1]:.3e}, {w * 1e3:7.2f} ms")
    dz = np.array([H / (n - 1) for n in counts])
    order = float(np.polyfit(np.log(dz[-4:]), np.log(errors[-4:]), 1)[0])
    case.record("observed order of convergence in deltaZ (relative RMS error)", order,
                "second-order finite volumes", 1.9, suffix="order", comparison=">=",
                cells=counts, errors=errors, wall_s_per_resolution=walls)
    print(f"observed order {order:.2f}")

    fig, ax = plt.subplots(figsize=(5, 4))
    ax.loglog(walls, errors, "o-")
    for n, w, e in zip(counts, walls, errors):
        ax.annotate(str(n), (w, e), textcoords="offset points", xytext=(4, 2), fontsize=7)
    ax.axhline(1e-4, color="gray", ls="--", lw=0.8, label="tolerance 1e-4")
    ax.set_xlabel("wall time of fluidResolution (s), 1000 steps")
    ax.set_ylabel("relative RMS error")
    ax.set_title(f"Poiseuille: error vs cost over nCell (order {order:.2f})")
    ax.legend()
    case.save_chart(fig, "cost")


if __name__ == "__main__":
    main()
