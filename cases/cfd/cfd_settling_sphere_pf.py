"""CFD-DEM case: one sphere settling at finite particle Reynolds number (Re_p ~ 20 and ~ 450),
point-force coupling with OpenFOAM (talusPointForceFoam with `dragModel SchillerNaumann` in
constant/couplingProperties; its case written by talus.coupling.case_builder).

Run:      build/bin/talus run cases/cfd/cfd_settling_sphere_pf.py [--quick] [--results DIR]
          [--procs 2] [--re 20|450] [--drag-model NAME]  (as root export
          OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1)
Set-up:   a glass sphere (rho_p = 2500 kg/m3) released from rest in water at rest (rho = 1000
          kg/m3, nu = 1e-6 m2/s), gravity -9.81 m/s2: d = 0.38 mm (Schiller-Naumann terminal
          velocity 5.38 cm/s, Re_p = 20.5; Stokes drag would give 11.8 cm/s) or d = 1.83 mm
          (24.8 cm/s, Re_p = 454). Closed box of 5 x 5 x 20 cells of size dx (no-slip walls),
          the sphere starting at the cell centre (0, 0, 18.5 dx). Fluid step 1 ms (Re_p 20) or
          4 ms (Re_p 450), about 1/6 of the relaxation time m / (dF/dv) at the terminal velocity,
          10 DEM sub-steps. Quick: d/dx = 0.05 only, 100 fluid steps (Re_p 20: 15 relaxation
          times) or 75 (Re_p 450: 12); full: d/dx = 0.05, 0.1 and 0.2, 500 or 150 fluid steps
          (the sphere crosses up to 15 cells).
Checked:  the final velocity on the d/dx = 0.05 mesh against the Schiller-Naumann terminal
          velocity, within 2 %. Recorded per mesh: that error, and the largest deviation of the
          whole transient from the equation of motion m dv/dt = (m - rho V) g - 3 pi mu d v
          (1 + 0.15 Re^0.687) (no added mass: the point-force solver has none) relative to the
          terminal velocity. The error growing with d/dx is the point-force approach's own: the
          drag uses the velocity of the particle's cell, which its reaction sets moving.
Produces: records cfd.settling_sphere_pf_re20 and cfd.settling_sphere_pf_re450; charts of the
          same names (velocity against time, one curve per d/dx, and the equation of motion).
"""
import tempfile


from talus import results
from talus.coupling.case_builder import FoamCase, cfd_case
from talus.coupling.cases import settle_sphere
from talus.coupling.settling import SettlingSphere, settling_row

RHO, NU, RHO_P, G = 1000.0, 1e-6, 2500.0, 9.81
CHECKED_D_OVER_DX, TOLERANCE = 0.05, 0.02
# Per Reynolds number: diameter [m], fluid step [s], fluid steps (quick, full).
SETTINGS = {20: (0.38e-3, 1e-3, (100, 500)), 450: (1.83e-3, 4e-3, (75, 150))}


def sphere(re: int) -> SettlingSphere:
    return SettlingSphere(SETTINGS[re][0], RHO_P, RHO, NU, G)


def prepare_case(procs: int, dx: float, fluid_dt: float, drag_model: str) -> FoamCase:
    """The closed box (no-slip walls) of 5 x 5 x 20 cells of size dx, the sphere's axis through
    cell centres, with the fluid step and the drag law, meshed in a new temporary folder."""
    return cfd_case(tempfile.mkdtemp(prefix="talus_cfd_settling_pf_"), solver="pointforce",
                    box=((-2.5 * dx, -2.5 * dx, 0), (2.5 * dx, 2.5 * dx, 20 * dx)), cells=(5, 5, 20), rho=RHO, nu=NU,
                    gravity=(0, 0, -G), coupling_interval=fluid_dt, procs=procs, write_every=1000,
                    coupling_properties={"dragModel": drag_model})


def settle(re: int, d_over_dx: float, fluid_steps: int, procs: int = 1, drag_model: str = "SchillerNaumann"):
    """One run; returns times, velocities, the coupling, the wall time."""
    d, fluid_dt, _ = SETTINGS[re]
    dx = d / d_over_dx
    run = settle_sphere(prepare_case(procs, dx, fluid_dt, drag_model), diameter=d, density=RHO_P,
                        position=(0.0, 0.0, 18.5 * dx), dt=fluid_dt / 10, fluid_steps=fluid_steps, remove_case=True)
    return run.t, run.v, run.coupling, run.elapsed


def run_reynolds(re: int, args, plt):
    case = results.Case(f"cfd.settling_sphere_pf_re{re}", quick=args.quick, folder=args.results)
    ball = sphere(re)
    d, fluid_dt, steps = SETTINGS[re]
    fluid_steps = steps[0] if args.quick else steps[1]
    w = ball.terminal_velocity()
    t_ref, v_ref = ball.velocity_history(fluid_steps * fluid_dt + fluid_dt, fluid_dt / 100)
    print(f"Re_p {re}: d {d * 1e3:g} mm, Schiller-Naumann terminal velocity {w:.6e} m/s (Re_p {ball.reynolds(w):.1f}), "
          f"drag {args.drag_model}")
    fig, ax = plt.subplots(figsize=(5.5, 4))
    ax.plot(t_ref, v_ref * 100, "k--", lw=0.8, label="equation of motion (Schiller-Naumann)")
    rows = []
    for d_over_dx in [CHECKED_D_OVER_DX] + ([] if args.quick else [0.1, 0.2]):
        t, v, coupling, elapsed = settle(re, d_over_dx, fluid_steps, args.procs, args.drag_model)
        rows.append(settling_row(t, v, w, (t_ref, v_ref), coupling, elapsed, d, d / d_over_dx, fluid_steps,
                                 args.procs, ax))
    ax.axhline(w * 100, color="grey", lw=0.5, ls=":")
    ax.set_xlabel("t [s]")
    ax.set_ylabel("settling velocity [cm/s]")
    ax.set_title(f"Settling sphere, Re_p = {ball.reynolds(w):.0f}, point forces ({args.drag_model})")
    ax.legend(fontsize=7)
    case.record(f"relative error of the final settling velocity, d/dx = {CHECKED_D_OVER_DX}",
                abs(rows[0]["rel_error_end"]), "Schiller-Naumann terminal velocity", TOLERANCE, w_terminal=w,
                Re_p=ball.reynolds(w), diameter=d, fluid_dt=fluid_dt, drag_model=args.drag_model,
                fluid_procs=args.procs, fluid_steps=fluid_steps, meshes=rows)
    case.save_chart(fig)


def main():
    parser = results.case_arguments(__doc__)
    parser.add_argument("--procs", type=int, default=1, help="fluid ranks (decomposed case)")
    parser.add_argument("--re", type=int, choices=sorted(SETTINGS), action="append",
                        help="particle Reynolds number (default: both)")
    parser.add_argument("--drag-model", default="SchillerNaumann",
                        help="the solver's dragModel (Stokes shows what the default drag law gives here)")
    args = parser.parse_args()
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    for re in args.re or sorted(SETTINGS):
        run_reynolds(re, args, plt)


if __name__ == "__main__":
    main()
