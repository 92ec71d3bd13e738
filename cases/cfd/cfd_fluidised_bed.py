"""CFD-DEM case: fluidisation of a deposited bed (volume-averaged coupling,
talusVolumeAveragedFoam; its case written by talus.coupling.case_builder).

Run:      build/bin/talus run cases/cfd/cfd_fluidised_bed.py [--quick] [--results DIR] [--procs 2] [--fixed]
          [--envelope-method pairwise|convolution] [--trajectory FILE.npy] [--nudge K]
          or with the DEM split too: mpirun --allow-run-as-root --oversubscribe -np 2 build/bin/talus run
          cases/cfd/cfd_fluidised_bed.py --quick --procs 2 (2 DEM processes + 2 fluid ranks; the
          script is written for both: its ids mapped to each process's rows by shares.rows(s, ids), the
          sums over the particles added over the processes, the fluid case written and read back
          by process 0; cfd_mpi_parity.py compares it with the 1 + 1 run, cfd.mpi.parity.fluidised-bed)
Set-up:   a packing deposited like cfd_packed_bed.py's periodic one (900 spheres d = 1 mm,
          rho_p = 2500, quick; 1500 full; column 8 x 8 mm periodic across x and y, in the DEM and
          in the mesh) but with the visco-elastic contacts of the coupled run (ViscElMat
          tc = 0.15 ms, en = et = 0.3; cfd_packed_bed.deposit(tc=...), gravity brought down to
          the buoyant weight by halves), freed (friction 0.3 between spheres, 0 with the floor)
          on a floor that is the fluid's inlet; fluid rho = 1000, nu = 1e-5 m2/s (Re_p < 1.4).
          The superficial inlet velocity is ramped linearly from 0 to 2 U_mf (U_mf from Ergun at
          the packing's porosity, middle 40 % of the bed) over 0.5 s (quick; 1.5 s full) and
          held 0.08 s (0.15 s). Fluid cells 0.8 mm, Gaussian envelope 1.5 mm; fluid step 0.1 ms,
          14 DEM steps per fluid step, drag re-evaluated at each (implicitDrag); alphaf
          fixedValue 1 at the inlet (the builder's Inlet: U there is the superficial velocity); the fluid
          fraction relaxes over 5 ms (alphaRelaxationTime); no added mass. Before the coupling the
          packing settles under its buoyant weight (numerical damping only then).
          --fixed: the same with every particle held (the set-up's fixed-bed check).
Measured: the bed's pressure drop from the particles' side each fluid step: the vertical
          hydrodynamic force on all particles minus their hydrostatic buoyancy, per column area
          (model A: the fluid's pressure drop over the bed carries exactly that); at the end also
          from the fluid's pressure field (first cell above the inlet minus the outlet).
Checked:  the plateau (mean over the held phase) against the buoyant bed weight per area
          (rho_p - rho) g sum V_p / A within 5 %; the minimum fluidisation velocity (where the
          line fitted to the pressure drop below 0.6 of the plateau meets the plateau) against
          the Ergun estimate within 15 %.
Produces: records cfd.fluidised_bed.plateau and .umf (cfd.fluidised_bed_fixed.umf with
          --fixed; cfd.fluidised_bed_convolution.* with an explicit --envelope-method); chart
          cfd.fluidised_bed.png (pressure drop against the superficial velocity).
Result:   full, the default convolution envelope (2026-12-06): plateau -0.92 %, U_mf +12.47 % of
          Ergun, 16500 fluid steps x 14 DEM steps in 323 s; quick with it U_mf +19.9 % (the
          12-layer bed's loose top and layered floor weigh more, the faster ramp adds its lag).
          Pairwise (--envelope-method pairwise), quick (porosity 0.3677, Ergun U_mf 0.770 mm/s,
          buoyant weight 108.35 Pa): plateau
          106.68 Pa (-1.5 %; the fluid's own drop at the end 102.7 Pa), U_mf 0.872 mm/s
          (+13.2 %: the loose top layers and the envelope at the bed's top carry less drag than
          Ergun at the interior porosity); bed top rose 0.15 mm at 2 U_mf; 5800 fluid steps x
          14 DEM steps in 258 s on the loaded 2-core machine. --fixed: the held bed carries its
          buoyant weight at 0.844 mm/s (+9.6 %). How it got there (docs/coupling.md):
          undamped contacts made the pressure drop jump +-100 Pa per fluid step (visco-elastic
          contacts and the fluid fraction's relaxation time); the bed resting on the inlet got
          alpha U0 through it (0/alphaf); side walls channelled the flow (periodic column); a
          3 mm envelope on 1.6 mm cells smeared 4 of the 12 layers at each end (0.8 mm / 1.5 mm);
          soft contacts (tc = 1 ms: the bed rose 70 um when 30 % of its weight was taken off)
          let the bed creep up at half the superficial velocity, the pressure drop at half of
          Ergun's slope (plateau -23 %, U_mf +94 %); stiffer contacts need a packing deposited
          with them (settling one deposited with softer contacts launched particles).
"""
import math
import re
import shutil
import subprocess
import tempfile
import time

import numpy as np

import cfd_packed_bed as packed
from talus import results
from talus.coupling.case_builder import PERIODIC, FoamCase, Inlet, Outlet, cfd_case
from talus.coupling.cases import foam_environment
from talus.dem import (Bo1_Sphere_Aabb, Bo1_Wall_Aabb, ForceResetter, Ig2_Sphere_Sphere_ScGeom, Ig2_Wall_Sphere_ScGeom,
                       InsertionSortCollider, InteractionLoop, Ip2_ViscElMat_ViscElMat_ViscElPhys,
                       Law2_ScGeom_ViscElPhys_Basic, NewtonIntegrator, Scene, ViscElMat, distributed, sphere, wall)
from talus.dem.split import shares

RHO, NU, RHO_P, D, G = 1000.0, 1e-5, 2500.0, 1e-3, 9.81
MU = RHO * NU
L, FLOOR = packed.L, packed.FLOOR
# Fluid cells 0.8 mm and envelope width 1.5 mm: the envelope's cut-off (1.9 mm, 2 particle
# layers) smears the bed's top; with the packed bed's 1.6 mm / 3 mm it reached 4 of the 12
# layers at each end, and the bed carried 35 % less drag than its interior porosity gives
# (fluidised at ~1.9 U_mf).
DX = 0.8e-3
COUPLING = {
    "envelope": "gaussian", "envelopeWidth": 1.5e-3, "hindranceExponent": 2.65,
    # No added mass in a dense bed: the particles' accelerations there come from contacts
    # (vibrations at the contact period), and the explicit added mass built on the lagged
    # du_p/dt of two exchanges amplifies them (the bed blew apart within 15 fluid steps).
    "addedMassCoefficient": 0,
    # The fluid fraction relaxes towards the particles' over 5 ms (50 fluid steps, 5 contact
    # periods): without it the contact jitter's d(alphaf)/dt gave pressure pulses of +-200 Pa
    # over the bed that, lagged by a fluid step, pumped the bed up (docs/coupling.md).
    "alphaRelaxationTime": 5e-3,
}
HOLD = 0.08  # held at 2 U_mf this long (quick; 0.15 s full) to average the plateau
# Contact duration and restitution of the visco-elastic contacts: tc = 0.15 ms gives
# kn = m (pi^2 + ln^2 en) / tc^2 = 330 N/m between spheres, so the whole bed yields only a few
# um as the fluid takes its weight (with tc = 1 ms it rose 70 um per 30 % of its weight and
# crept up at half the superficial velocity); DEM step tc / 20; en = 0.3 damps a vibration
# within ~2 contact periods.
TC, EN = 1.5e-4, 0.3


def ergun(u0, eps):
    return 150 * MU * (1 - eps) ** 2 * u0 / (eps ** 3 * D ** 2) + 1.75 * RHO * (1 - eps) * u0 ** 2 / (eps ** 3 * D)


def ergun_umf(eps):
    """Superficial velocity at which Ergun's pressure gradient carries the buoyant bed weight."""
    lo, hi = 0.0, 1.0
    for _ in range(200):
        mid = 0.5 * (lo + hi)
        lo, hi = (mid, hi) if ergun(mid, eps) < (1 - eps) * (RHO_P - RHO) * G else (lo, mid)
    return 0.5 * (lo + hi)


def prepare_case(procs: int, height: float, u_max: float, ramp: float, envelope_method: str | None,
                 pressure_tolerance: float | None = None) -> FoamCase:
    """The column periodic across x and y from the floor (the inlet, the distributor: no clear
    fluid below the bed for the envelope to smear the bed's fluid fraction into; pure fluid
    enters there, so its velocity is the superficial one, ramped linearly from 0 to ``u_max``
    over ``ramp`` s, then held) up to ``height`` (the outlet, p = 0); the pressure solved to
    ``pressure_tolerance`` in every corrector if given (else the case builder's tolerances)."""
    nz = round((height - FLOOR) / DX)
    extra = {} if envelope_method is None else {"envelopeMethod": envelope_method}
    solve = {} if pressure_tolerance is None else {"pressure_tolerance": pressure_tolerance,
                                                   "pressure_relative_tolerance": 0}
    return cfd_case(tempfile.mkdtemp(prefix="talus_cfd_fluidised_bed_"), solver="volumeaveraged",
                    box=((0, 0, FLOOR), (L, L, FLOOR + nz * DX)), cells=(round(L / DX), round(L / DX), nz), rho=RHO,
                    nu=NU, gravity=(0, 0, -G), coupling_interval=1e-4, procs=procs, write_every=10000,
                    boundaries={"z0": Inlet((0, 0, u_max), ramp=ramp), "z1": Outlet(), "x0": PERIODIC, "y0": PERIODIC},
                    coupling_properties={**COUPLING, **extra}, **solve)


def fluid_pressure_drop(fluid: FoamCase) -> float:
    """The fluid's own pressure drop at the end, from its last fields (reconstructed from the
    ranks' if decomposed): the first cell above the inlet (zeroGradient) to the outlet. The
    case's folder is removed."""
    work = fluid.path
    if fluid.procs > 1:
        subprocess.run(["reconstructPar", "-latestTime", "-case", str(work)], check=True, capture_output=True,
                       env=foam_environment())
    last = max((p for p in work.iterdir() if re.fullmatch(r"[0-9.e-]+", p.name) and p.name != "0"),
               key=lambda p: float(p.name))
    p = packed.read_internal_field(last / "p")
    nx = round(L / DX)
    p_z = RHO * p.reshape(-1, nx * nx).mean(axis=1)
    shutil.rmtree(work, ignore_errors=True)
    return float(p_z[0] - p_z[-1])


def main():
    parser = results.case_arguments(__doc__)
    parser.add_argument("--procs", type=int, default=1, help="fluid ranks (decomposed case)")
    parser.add_argument("--fixed", action="store_true", help="every particle held: the fixed-bed check")
    parser.add_argument("--envelope-method", choices=["pairwise", "convolution"], default=None,
                        help="talusVolumeAveragedFoam's envelopeMethod (default: the solver's)")
    parser.add_argument("--pressure-tolerance", type=float, default=None,
                        help="solve the fluid's pressure to this tolerance in every corrector (relTol 0), so that "
                             "a decomposed fluid differs from one rank by rounding only (cfd_mpi_parity.py)")
    parser.add_argument("--trajectory", default=None,
                        help="also write every sphere's position every 200 fluid steps and at the last to this "
                             ".npy file (samples x spheres x 3; cfd_mpi_parity.py)")
    parser.add_argument("--nudge", type=int, default=None, metavar="K",
                        help="before the coupling, move the K-th sphere's x by one ulp: a change of the state "
                             "the size of one rounding, whose growth is the reference scale of cfd_mpi_parity.py")
    args = parser.parse_args()
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    case = results.Case("cfd.fluidised_bed" + ("_fixed" if args.fixed else "") +
                        ("" if args.envelope_method is None else "_" + args.envelope_method), quick=args.quick,
                        folder=args.results)
    n = 900 if args.quick else 1500
    ramp = 0.5 if args.quick else 1.5
    hold = HOLD if args.quick else 0.15
    x, r = packed.deposit(n, periodic=True, tc=TC)
    bed_top = float(np.max(x[:, 2] + r))
    eps = packed.slab_porosity(x, r, FLOOR + 0.3 * (bed_top - FLOOR), FLOOR + 0.7 * (bed_top - FLOOR))
    u_mf = ergun_umf(eps)
    volume = float(np.sum(4 / 3 * math.pi * r ** 3))
    weight = (RHO_P - RHO) * G * volume / (L * L)
    print(f"{n} spheres, porosity {eps:.4f}, Ergun U_mf {u_mf:.4e} m/s, buoyant weight / area {weight:.3f} Pa")

    # One fluid case for the run, written by process 0 under mpirun, its path shared.
    fluid = shares.once(prepare_case, args.procs, bed_top + 12e-3, 2 * u_mf, ramp, args.envelope_method,
                             args.pressure_tolerance)
    # Visco-elastic contacts (spring-dashpot, Yade's ViscElMat as Yade users fluidise beds): the
    # dashpot acts on the relative velocity at the contact only, so it quiets the contact
    # vibrations without touching the fluid-particle balance (Cundall's numerical damping acts
    # on the absolute velocity and would resist the bed's lift like a second drag).
    s = Scene()
    s.materials.append(ViscElMat(tc=TC, en=EN, et=EN, frictionAngle=0.3, density=RHO_P, label="grains"))
    s.materials.append(ViscElMat(tc=TC, en=EN, et=EN, frictionAngle=0.0, density=RHO_P, label="walls"))
    # Periodic across x and y (no side walls: their loose wall layers channel the flow, more so
    # the finer the envelope), the floor at the inlet, a lid below the outlet.
    s.periodic = True
    s.cell.setBox(L, L, 4 * (bed_top + 12e-3))
    s.bodies.append([wall((0, 0, FLOOR), axis=2, material="walls"), wall((0, 0, bed_top + 10e-3), axis=2, material="walls")])
    ids = s.bodies.append([sphere(tuple(p), float(ri), material="grains") for p, ri in zip(x, r)])
    s.engines = [ForceResetter(), InsertionSortCollider([Bo1_Sphere_Aabb(), Bo1_Wall_Aabb()]),
                 InteractionLoop([Ig2_Sphere_Sphere_ScGeom(), Ig2_Wall_Sphere_ScGeom()],
                                 [Ip2_ViscElMat_ViscElMat_ViscElPhys()], [Law2_ScGeom_ViscElPhys_Basic()]),
                 NewtonIntegrator(gravity=(0, 0, -G), damping=0.0)]
    s.dt = TC / 20
    # The packing was deposited under 10 g with softer contacts: quench it (velocities zeroed
    # every 10 steps while the stiffer contacts push the overlaps out), then let it settle under
    # its buoyant weight (the fluid at rest adds the buoyancy once coupled), damped; numerical
    # damping only here, before the coupling starts. The arrays are a process's own rows under
    # mpirun: shares.rows(s, ids) are those of the spheres it owns (the ids themselves in one process).
    s.engines[-1].gravity = (0, 0, -G * (1 - RHO / RHO_P))
    for _ in range(200):
        s.run(10, True)
        s.velocities()[shares.rows(s, ids)] = 0.0
    s.engines[-1].damping = 0.7
    s.run(2000, True)
    s.engines[-1].damping = 0.0
    s.engines[-1].gravity = (0, 0, -G)
    s.velocities()[shares.rows(s, ids)] = 0.0
    if args.nudge is not None:
        nudged = shares.rows(s, ids[args.nudge:args.nudge + 1])   # on its owner only under mpirun
        s.positions()[nudged, 0] = np.nextafter(s.positions()[nudged, 0], np.inf)
    if args.fixed:
        held = set(ids)
        for b in s.bodies:   # every body on every process; a body's owner holds it
            if b.id in held:
                b.state.blockedDOFs = "xyzXYZ"
    coupling = fluid.coupling(s, ids=ids, implicitDrag=True).start()
    dt_fluid = coupling.link.fluidDt
    steps = round((ramp + hold) / dt_fluid)
    t_start = s.time  # the fluid's clock starts at the coupling, after the DEM-only relaxation
    t, u0, dp, trajectory = [], [], [], []
    start = time.perf_counter()
    for _ in range(steps):
        s.run(coupling.substeps, True)
        t.append(s.time - t_start)
        u0.append(2 * u_mf * min(1.0, t[-1] / ramp))
        # the force on every particle: under mpirun each process has its own particles' (summed)
        dp.append((shares.total(float(np.sum(coupling.lastForces[:, 2]))) - RHO * G * volume) / (L * L))
        if len(t) % 200 == 0:
            if args.trajectory:
                trajectory.append(distributed.positions(s)[ids])
            rows = shares.rows(s, ids)
            v = s.velocities()[rows]
            v_z, count = shares.total([np.sum(v[:, 2]), len(v)])
            fastest = shares.largest(np.max(np.linalg.norm(v, axis=1), initial=0.0))
            top = shares.largest(np.max(s.positions()[rows][:, 2], initial=-np.inf))
            print(f"t {t[-1]:.4f} s: U0 {u0[-1]:.3e} m/s, particles' pressure drop {dp[-1]:.2f} Pa, mean v_z "
                  f"{v_z / count:+.2e} m/s, largest |v| {fastest:.2e} m/s, bed top {top * 1e3:.3f} mm", flush=True)
    elapsed = time.perf_counter() - start
    coupling.stop()
    fluid_dp = shares.once(fluid_pressure_drop, fluid)  # the fluid ranks have written their fields

    t, u0, dp = np.array(t), np.array(u0), np.array(dp)
    held = t > ramp
    plateau = float(np.mean(dp[held]))
    if args.fixed:
        # A held bed has no plateau: U_mf is where its pressure drop reaches the buoyant weight.
        u_mf_measured = float(np.interp(weight, dp[t <= ramp], u0[t <= ramp]))
    else:
        rising = (t <= ramp) & (dp < 0.6 * plateau) & (dp > 0)
        slope = np.polyfit(u0[rising], dp[rising], 1)
        u_mf_measured = float((plateau - slope[1]) / slope[0])
    rows = shares.rows(s, ids)
    bed_expansion = shares.largest(float(np.max(s.positions()[rows][:, 2] + s.radii()[rows], initial=-np.inf))) - bed_top
    if args.trajectory:     # every sphere's positions, on every process (collective)
        last = [] if steps % 200 == 0 else [distributed.positions(s)[ids]]
        shares.once(np.save, args.trajectory, np.array(trajectory + last))
    print(f"plateau {plateau:.3f} Pa ({(plateau - weight) / weight:+.2%} vs buoyant weight), fluid's own "
          f"pressure drop at the end {fluid_dp:.3f} Pa ({(fluid_dp - weight) / weight:+.2%}); U_mf {u_mf_measured:.4e} m/s "
          f"({(u_mf_measured - u_mf) / u_mf:+.2%} vs Ergun); bed top rose {bed_expansion * 1e3:.2f} mm; Re_p max "
          f"{coupling.maxReynolds:.3f}; {steps} fluid steps x {coupling.substeps} DEM steps in {elapsed:.1f} s")

    fig, ax = plt.subplots(figsize=(5.5, 4))
    ax.plot(u0[t <= ramp] * 1e3, dp[t <= ramp], "-", lw=1, label="talusVolumeAveragedFoam (ramp)")
    us = np.linspace(0, 2 * u_mf, 50)
    ax.plot(us * 1e3, np.minimum(ergun(us, eps) * (bed_top - FLOOR), 1e9), "k--", lw=0.8,
            label=f"Ergun x bed height, porosity {eps:.3f}")
    ax.axhline(weight, color="grey", lw=0.8, ls=":", label="buoyant bed weight / area")
    ax.axvline(u_mf * 1e3, color="grey", lw=0.5, ls="--")
    ax.set_ylim(0, 1.5 * weight)
    ax.set_xlabel("superficial velocity U0 [mm/s]")
    ax.set_ylabel("bed pressure drop [Pa]")
    ax.set_title(f"Fluidisation, {n} spheres, volume-averaged coupling")
    ax.legend(fontsize=7)
    if not args.fixed:
        case.record("relative deviation of the pressure-drop plateau from the buoyant bed weight per area",
                    abs(plateau - weight) / weight, "(rho_p - rho) g sum V_p / A", 0.05, suffix="plateau",
                    plateau=plateau, weight=weight, fluid_pressure_drop=fluid_dp, spheres=n, fluid_procs=args.procs,
                    dem_procs=distributed.RANKS)
    case.record("relative deviation of the minimum fluidisation velocity from the Ergun estimate",
                abs(u_mf_measured - u_mf) / u_mf, "Ergun at the packing's porosity", 0.15, suffix="umf",
                u_mf=u_mf_measured, u_mf_ergun=u_mf, porosity=eps, bed_expansion=bed_expansion)
    case.save_chart(fig)


if __name__ == "__main__":
    main()
