"""CFD-DEM case: one sphere settling in the intermediate regime (Re_p ~ 5), volume-averaged
coupling with OpenFOAM (talusVolumeAveragedFoam spawned over MPI; its case written by
talus.coupling.case_builder).

Run:      build/bin/talus run cases/cfd/cfd_settling_sphere_va.py [--quick] [--results DIR] [--procs 2]
          [--envelope gaussian|cell]  (as root export OMPI_ALLOW_RUN_AS_ROOT=1
          OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1)
Set-up:   sphere d = 2 mm, rho_p = 2500 kg/m3, released from rest in a closed box of
          11 x 11 x 15 cells (no-slip walls) of fluid at rest, rho = 1000 kg/m3, nu = 3e-5 m2/s;
          gravity -9.81 m/s2. Schiller-Naumann terminal velocity w = 7.59 cm/s (Re_p = 5.1),
          Stokes relaxation time tau = rho_p d^2 / (18 mu) = 18.5 ms. Cell sizes dx = 40, 20,
          10 mm (d/dx = 0.05, 0.1, 0.2; the box scales with dx). Fluid step 1 ms, DEM step
          0.1 ms (10 sub-steps). Quick: 250 fluid steps (0.25 s = 13.5 tau); full: 600.
Checked:  the final velocity against the Schiller-Naumann terminal velocity within 2 % on the
          d/dx = 0.1 mesh, and the whole transient against the integrated equation of
          motion (m + C_m rho V) dv/dt = (m - rho V) g - 3 pi mu d v (1 + 0.15 Re^0.687),
          recorded as the largest deviation relative to w. The error that grows with d/dx is the
          particle's own wake seen through the envelope (as for point forces, weaker since the
          force is spread over ~3 cells). Serial against 2 fluid ranks: the d/dx = 0.1 run is
          repeated on the case decomposed in 2 (along z) and the settling velocities of the two
          runs must agree within 1e-6 relative at every fluid step.
Produces: records cfd.settling_sphere_va and cfd.settling_sphere_va.ranks; chart
          cfd.settling_sphere_va.png.
"""
import tempfile

import numpy as np

from talus import results
from talus.coupling.case_builder import FoamCase, cfd_case
from talus.coupling.cases import settle_sphere
from talus.coupling.settling import SettlingSphere, settling_row

RHO, NU, RHO_P, D, G, CM = 1000.0, 3e-5, 2500.0, 2e-3, 9.81, 0.5
SPHERE = SettlingSphere(D, RHO_P, RHO, NU, G, addedMassCoefficient=CM)
TAU = SPHERE.relaxation_time
CELL_SIZES = [0.04, 0.02, 0.01]
CHECKED = 0.02


def prepare_case(procs: int, dx: float, envelope: str) -> FoamCase:
    """The closed box (no-slip walls) of 11 x 11 x 15 cells of size dx, the sphere's axis through
    cell centres, meshed (and decomposed along z) in a new temporary folder."""
    return cfd_case(tempfile.mkdtemp(prefix="talus_cfd_settling_va_"), solver="volumeaveraged",
                    box=((-5.5 * dx, -5.5 * dx, 0), (5.5 * dx, 5.5 * dx, 15 * dx)), cells=(11, 11, 15), rho=RHO, nu=NU,
                    gravity=(0, 0, -G), coupling_interval=1e-3, procs=procs,
                    coupling_properties={"envelope": envelope, "addedMassCoefficient": CM})


def settle(procs: int, dx: float, fluid_steps: int, envelope: str):
    run = settle_sphere(prepare_case(procs, dx, envelope), diameter=D, density=RHO_P, position=(0.0, 0.0, 12.5 * dx),
                        dt=1e-4, fluid_steps=fluid_steps, remove_case=True)
    return run.t, run.v, run.coupling, run.elapsed


def main():
    parser = results.case_arguments(__doc__)
    parser.add_argument("--procs", type=int, default=1, help="fluid ranks (decomposed case)")
    parser.add_argument("--envelope", default="gaussian", choices=["gaussian", "cell"])
    args = parser.parse_args()
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    case = results.Case("cfd.settling_sphere_va" + ("" if args.envelope == "gaussian" else "_cell"),
                        quick=args.quick, folder=args.results)
    fluid_steps = 250 if args.quick else 600
    w = SPHERE.terminal_velocity()
    t_ref, v_ref = SPHERE.velocity_history(fluid_steps * 1e-3 + 1e-3, 1e-5)
    print(f"Schiller-Naumann terminal velocity {w:.6e} m/s (Re_p {w * D / NU:.2f}, tau {TAU:.3e} s)")
    fig, ax = plt.subplots(figsize=(5.5, 4))
    ax.plot(t_ref, v_ref * 100, "k--", lw=0.8, label="equation of motion (Schiller-Naumann)")
    rows, velocities = [], {}
    for dx in CELL_SIZES:
        t, v, coupling, elapsed = settle(args.procs, dx, fluid_steps, args.envelope)
        velocities[dx] = v
        rows.append(settling_row(t, v, w, (t_ref, v_ref), coupling, elapsed, D, dx, fluid_steps, args.procs, ax))
    ax.axhline(w * 100, color="grey", lw=0.5, ls=":")
    ax.set_xlabel("t [s]")
    ax.set_ylabel("settling velocity [cm/s]")
    ax.set_title(f"Settling sphere, Re_p = {w * D / NU:.1f}, volume-averaged coupling ({args.envelope})")
    ax.legend(fontsize=7)
    checked = next(r for r in rows if abs(r["d_over_dx"] - 0.1) < 1e-9)
    case.record("relative error of the final settling velocity, d/dx = 0.1", abs(checked["rel_error_end"]),
                "Schiller-Naumann terminal velocity", CHECKED, w_terminal=w, Re_p=w * D / NU, tau=TAU,
                fluid_procs=args.procs, fluid_steps=fluid_steps, envelope=args.envelope, meshes=rows)
    if args.procs == 1:
        _, v2, _, elapsed2 = settle(2, 0.02, fluid_steps, args.envelope)
        v1 = velocities[0.02]
        difference = float(np.max(np.abs(v2 - v1)[1:] / np.abs(v1[1:])))
        print(f"serial against 2 fluid ranks (d/dx 0.1): largest relative difference of the velocity {difference:.2e} "
              f"({elapsed2:.1f} s on 2 ranks)")
        case.record("largest relative difference of the settling velocity, serial against 2 fluid ranks", difference,
                    "the serial run", 1e-6, suffix="ranks", fluid_steps=fluid_steps, envelope=args.envelope)
    case.save_chart(fig)


if __name__ == "__main__":
    main()
