"""CFD-DEM case: accuracy and cost of the two couplings against the particle-to-cell size ratio,
on the Stokes settling sphere of cases/cfd/cfd_settling_sphere.py (its case, written by the case
builder for either solver).

Run:      build/bin/talus run cases/cfd/cfd_coupling_accuracy.py [--quick] [--results DIR]
Set-up:   as cfd_settling_sphere.py (d = 1 mm, rho_p = 2500, mu = 1 Pa s, Stokes w = 0.8175 mm/s,
          tau = 0.139 ms, closed 45 x 45 x 90 mm box), meshes of 3, 5, 9, 15 and 21 cells across
          (d/dx = 0.067, 0.11, 0.2, 0.33, 0.47), each with talusPointForceFoam (Stokes drag in
          the particle's cell) and talusVolumeAveragedFoam (Gaussian envelope 3 cells wide,
          Schiller-Naumann drag: +0.1 % over Stokes at Re_p = 8e-4). Quick: 200 fluid steps
          (29 tau); full: 1000.
Measured: the settling velocity at the end against Stokes, and the wall time, per coupling
          and mesh. Checked: the volume-averaged coupling stays within 2 % of Stokes on every
          mesh up to d/dx = 0.47 (the point-force one is only recorded: its error grows with
          d/dx as the particle's own reaction moves its cell's fluid).
Produces: record cfd.coupling_accuracy; chart cfd.coupling_accuracy.png (error against d/dx and
          against wall time).
"""
import cfd_settling_sphere as settling
from talus import results

MESHES = [(3, 6), (5, 10), (9, 18), (15, 30), (21, 42)]
SOLVERS = {"talusPointForceFoam": "point force", "talusVolumeAveragedFoam": "volume-averaged"}


def main():
    parser = results.case_arguments(__doc__)
    args = parser.parse_args()
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    case = results.Case("cfd.coupling_accuracy", quick=args.quick, folder=args.results)
    steps = 200 if args.quick else 1000
    rows = []
    for solver in SOLVERS:
        for cells in MESHES:
            t, v, coupling, elapsed = settling.settle(1, cells, steps, solver)
            ratio = settling.D / (settling.BOX / cells[0])
            row = dict(solver=solver, d_over_dx=ratio, v_end=float(v[-1]), t_end=float(t[-1]),
                       rel_error=float(v[-1] - settling.W_STOKES) / settling.W_STOKES, wall_time_s=elapsed)
            rows.append(row)
            print(f"{SOLVERS[solver]:16s} d/dx {ratio:.3f}: v({t[-1] * 1e3:.1f} ms) {v[-1]:.5e} m/s "
                  f"({row['rel_error']:+.2%} vs Stokes), {elapsed:.1f} s")
    fig, (a1, a2) = plt.subplots(1, 2, figsize=(9, 3.8))
    for solver, label in SOLVERS.items():
        sel = [r for r in rows if r["solver"] == solver]
        a1.plot([r["d_over_dx"] for r in sel], [100 * r["rel_error"] for r in sel], "o-", label=label)
        a2.plot([r["wall_time_s"] for r in sel], [100 * abs(r["rel_error"]) for r in sel], "o", label=label)
    a1.axhline(2, color="grey", lw=0.5, ls=":")
    a1.axhline(-2, color="grey", lw=0.5, ls=":")
    a1.set_xlabel("particle diameter / cell size")
    a1.set_ylabel(f"settling velocity error at {steps} steps [%]")
    a1.legend(fontsize=7)
    a2.set_xscale("log")
    a2.set_yscale("log")
    a2.set_xlabel("wall time [s]")
    a2.set_ylabel("|error| [%]")
    fig.suptitle("Settling sphere (Stokes): point force against volume-averaged coupling")
    worst = max(abs(r["rel_error"]) for r in rows if r["solver"] == "talusVolumeAveragedFoam")
    case.record("largest relative error of the volume-averaged settling velocity over d/dx 0.067-0.47", worst,
                "Stokes terminal velocity", 0.02, fluid_steps=steps, rows=rows)
    case.save_chart(fig)


if __name__ == "__main__":
    main()
