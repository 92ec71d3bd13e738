"""CFD-DEM case: cost of one coupling exchange against the particle count and the number of
fluid ranks, and the coupling's share of a coupled step at 10 000 particles (O(N/P)
data per rank, a bounded number of messages, overhead below 20 % of the step time).

Run:      build/bin/talus run cases/cfd/cfd_exchange_cost.py [--quick] [--results DIR]
          [--solver talusPointForceFoam|talusVolumeAveragedFoam] [--envelope-method pairwise|convolution]
Set-up:   the closed box of cases/cfd/cfd_settling_sphere.py (45 x 45 x 90 mm; rho = 1000 kg/m3,
          nu = 1e-3 m2/s) meshed 10 x 10 x 20 (cells 4.5 mm), decomposed along z for 2 ranks;
          fluid step 20 us; spheres r = 0.35 mm (d/dx = 0.16), rho_p = 2500 (relaxation time
          68 us).
          Exchange cost: N spheres at random positions (seed 1), one DEM step per fluid step
          without contacts; 2 warm-up exchanges, then 20 measured; N = 1000, 3000, 10000
          (quick), also 30000 and 100000 (full); 1 and 2 fluid ranks.
          Overhead: 10000 spheres on a jittered lattice (a dilute suspension, 1 % solid, no
          contact: the cheapest DEM step, so the largest share the coupling can take) with the
          usual DEM loop (collider, contact law, Newton; E = 50 MPa, DEM step 0.8 of the P-wave
          step: 11 sub-steps per fluid step; one DEM thread), 1 fluid rank; 2 warm-up fluid
          steps, then 20 (quick) or 50 (full) measured.
Measured: per exchange the messages (DEM <-> fluid and between fluid ranks), the doubles the
          DEM process sends and receives, the particles each fluid rank gets, and the time of
          one exchange = the DEM's own coupling work (gathering the particles' state, sorting it
          into the ranks' arrays, summing and applying the forces) + the slowest fluid rank's
          exchange (receiving the particles, locating them, computing the forces and their
          reactions, halo messages, sending the forces; timed by the rank itself, so the time
          the DEM waits while the fluid still solves is not counted); medians; as wall time and
          as CPU time (the machine is shared: its wall times scatter 2-4x between runs, they
          mostly measure the scheduler). The growth exponent against N (least squares in
          log-log). The DEM runs on one thread (see main).
          The coupled step = the fluid step's solution (the fluid rank's own time) + the DEM's
          11 sub-steps (the DEM loop minus the coupling's hooks) + the exchange; the overhead is
          the exchange's share of that sum in CPU time (what each part costs, whatever else runs
          on the machine; with a core each and an idle machine that is the share of wall time
          if the fluid and the DEM ran one after the other: they overlap, the fluid solving
          while the DEM sub-steps); the wall-time shares are recorded beside it.
Checked:  the messages do not depend on N (3 per fluid rank plus at most 1 per neighbouring
          rank and reduction); with 2 ranks no rank owns more than 60 % of the particles
          (O(N/P); the volume-averaged solver's ranks also get the particles within the
          envelope's cut-off of their cells, recorded as the share sent, and the fluid side's
          CPU time on 2 ranks against 1 at the largest N shows the work each does); growth
          exponent of the CPU time (1 rank) at most 1.2 (O(N)); overhead at most 0.2.
Produces: records cfd.exchange_cost (largest share of the particles owned by one of 2 ranks),
          cfd.exchange_cost.growth, cfd.exchange_cost.overhead (cfd.exchange_cost_va.* with the
          volume-averaged solver, cfd.exchange_cost_va_pairwise.* and _convolution.* with an
          explicit --envelope-method; their overhead records carry the fluid side's phases from
          the solver's log); chart cfd.exchange_cost.png (wall and CPU time per exchange
          against N for 1 and 2 fluid ranks, with the O(N) line).
"""
import shutil
import time
from pathlib import Path

import numpy as np

import cfd_settling_sphere as settling
import talus
from talus import results
from talus.coupling.case_builder import FoamCase
from talus.dem import (Bo1_Sphere_Aabb, ForceResetter, FrictMat, Ig2_Sphere_Sphere_ScGeom, InsertionSortCollider,
                       InteractionLoop, Ip2_FrictMat_FrictMat_FrictPhys, Law2_ScGeom_FrictPhys_CundallStrack,
                       NewtonIntegrator, PWaveTimeStep, Scene, sphere)

RADIUS, RHO_P, G = 3.5e-4, 2500.0, (0.0, 0.0, -9.81)
LOW, HIGH = np.array([-0.022, -0.022, 0.001]), np.array([0.022, 0.022, 0.089])  # inside the box
DT_FLUID = 2e-5  # the settling case's fluid step
OVERHEAD_N = 10000
BED_SIDE = 22  # the dense bed's 22^3 = 10648 spheres
MEASURED = 20  # exchanges measured per particle count (medians: the loaded machine's times scatter)


def mesh(procs: int, solver: str, envelope_method: str | None) -> FoamCase:
    """The settling case's box meshed 10 x 10 x 20 for ``solver`` on ``procs`` fluid ranks."""
    return settling.prepare_case(procs, (10, 20), solver, coupling_properties=None if envelope_method is None
                                 else {"envelopeMethod": envelope_method})


def exchange_phases(work: Path, solver: str) -> dict:
    """The volume-averaged solver's CPU time per exchange by phase [s], from the last line it
    logs (empty for the point-force solver)."""
    log = work / f"log.{solver}"
    lines = [l for l in log.read_text().splitlines() if l.startswith("Exchange phases")] if log.exists() else []
    if not lines:
        return {}
    words = lines[-1].rsplit(":", 1)[1].replace("(", " ").replace(")", " ").split()
    return {name: float(value) * 1e-3 for name, value in zip(words[::2], words[1::2])}


def scene_of(positions: np.ndarray, contacts: bool, period: float | None = None) -> Scene:
    """The spheres at ``positions``; ``period``: in a periodic cube of that side (origin 0)."""
    s = Scene()
    if period is not None:
        s.periodic = True
        s.cell.setBox(period, period, period)
    s.materials.append(FrictMat(density=RHO_P, young=5e7, poisson=0.3, frictionAngle=0.5))
    s.bodies.append([sphere(tuple(p), RADIUS) for p in positions])
    loop = [InsertionSortCollider([Bo1_Sphere_Aabb()]),
            InteractionLoop([Ig2_Sphere_Sphere_ScGeom()], [Ip2_FrictMat_FrictMat_FrictPhys()],
                            [Law2_ScGeom_FrictPhys_CundallStrack()])] if contacts else []
    s.engines = [ForceResetter(), *loop, NewtonIntegrator(gravity=G, damping=0.0)]
    return s


def lattice(n: int, rng) -> np.ndarray:
    """n points on a jittered lattice filling the box (no two spheres overlap)."""
    span = HIGH - LOW
    per = np.ceil(span * (n / np.prod(span)) ** (1 / 3)).astype(int)
    idx = np.stack(np.meshgrid(*[np.arange(k) for k in per], indexing="ij"), -1).reshape(-1, 3)[:n]
    pitch = span / per
    return LOW + (idx + 0.5 + rng.uniform(-0.25, 0.25, idx.shape)) * pitch


def bed(side: int) -> tuple[np.ndarray, float]:
    """side^3 touching spheres on a simple cubic lattice filling a periodic cube (6 contacts
    each, overlapping by 0.1 % of the diameter, in balance: a free lattice would spring apart):
    the contacts of a dense bed without depositing one. Returns the positions and the period."""
    pitch = 2 * RADIUS * (1 - 1e-3)
    idx = np.stack(np.meshgrid(*[np.arange(side)] * 3, indexing="ij"), -1).reshape(-1, 3)
    return (idx + 0.5) * pitch, side * pitch


def measure_exchange(n: int, procs: int, solver: str, envelope_method: str | None) -> dict:
    """Cost of one exchange with n particles on procs fluid ranks (one DEM step per fluid step),
    as wall and as CPU time."""
    foam = mesh(procs, solver, envelope_method)
    x = np.random.default_rng(1).uniform(LOW, HIGH, size=(n, 3))
    s = scene_of(x, contacts=False)
    s.dt = DT_FLUID
    coupling = foam.coupling(s).start()
    try:
        s.run(2, True)
        dem, fluid, messages, doubles = [], [], [], []
        for _ in range(MEASURED):
            before = coupling.times.copy()
            s.run(1, True)
            spent = coupling.times.since(before)
            dem.append((spent.dem, spent.demCpu))
            link = coupling.link  # the fluid side's figures are the previous exchange's
            fluid.append((link.lastFluidExchangeSeconds, link.lastFluidExchangeCpuSeconds))
            messages.append(link.lastMessages)
            doubles.append(link.lastDemDoubles)
        boxes = np.array(coupling.link.boxes).reshape(-1, 7)
    finally:
        coupling.stop()
        shutil.rmtree(foam.path, ignore_errors=True)
    # A rank gets the particles in its sub-mesh's box widened by the envelope's cut-off (the
    # volume-averaged solver: those whose envelope reaches its cells; it computes their pairs
    # with its own cells only) and owns those inside the box itself.
    sent = [int(np.all((x >= b[:3] - b[6]) & (x <= b[3:6] + b[6]), axis=1).sum()) for b in boxes]
    owned = [int(np.all((x >= b[:3]) & (x <= b[3:6]), axis=1).sum()) for b in boxes]
    (dem_s, dem_cpu), (fluid_s, fluid_cpu) = np.median(dem, axis=0), np.median(fluid, axis=0)
    return dict(n=n, procs=procs, seconds=float(dem_s + fluid_s), dem_seconds=float(dem_s),
                fluid_seconds=float(fluid_s), cpu_seconds=float(dem_cpu + fluid_cpu), dem_cpu_seconds=float(dem_cpu),
                fluid_cpu_seconds=float(fluid_cpu), messages=int(max(messages)), dem_doubles=int(np.median(doubles)),
                particles_per_rank=owned, particles_sent_per_rank=sent)


def measure_overhead(solver: str, envelope_method: str | None, steps: int, positions: np.ndarray,
                     period: float | None = None) -> dict:
    """Where the time of a coupled step goes with the particles at ``positions`` (in a periodic
    cube of side ``period``, inside the mesh) and the full DEM loop (on one thread, see main),
    as wall and as CPU time; with the volume-averaged solver also its exchange's phases (CPU,
    averaged over the run's exchanges after its first two)."""
    foam = mesh(1, solver, envelope_method)
    s = scene_of(positions, contacts=True, period=period)
    s.dt = 0.8 * PWaveTimeStep(s)
    coupling = foam.coupling(s).start()
    try:
        s.run(2 * coupling.substeps, True)
        before = coupling.times.copy()
        start, start_cpu = time.perf_counter(), time.thread_time()
        s.run(steps * coupling.substeps, True)
        wall, cpu = time.perf_counter() - start, time.thread_time() - start_cpu
        spent = coupling.times.since(before)
        contacts = s._cpp.realContactCount()
    finally:
        coupling.stop()
    phases = exchange_phases(foam.path, solver)
    shutil.rmtree(foam.path, ignore_errors=True)
    k, reports = spent.exchanges, spent.fluidReports
    exchange = spent.dem / k + spent.fluidExchange / reports
    fluid_step = spent.fluidSteps / reports
    dem_substeps = (wall - spent.dem - spent.waiting) / k
    exchange_cpu = spent.demCpu / k + spent.fluidExchangeCpu / reports
    fluid_step_cpu = spent.fluidStepsCpu / reports
    dem_substeps_cpu = (cpu - spent.demCpu) / k  # one DEM thread: all of its work is this thread's
    return dict(substeps=coupling.substeps, dem_threads=talus._dem.threadCount(), contacts=contacts,
                exchange_cpu_s=exchange_cpu, dem_coupling_cpu_s=spent.demCpu / k,
                fluid_exchange_cpu_s=spent.fluidExchangeCpu / reports, fluid_step_cpu_s=fluid_step_cpu,
                dem_substeps_cpu_s=dem_substeps_cpu,
                share=exchange_cpu / (fluid_step_cpu + dem_substeps_cpu + exchange_cpu),
                exchange_s=exchange, dem_coupling_s=spent.dem / k, fluid_exchange_s=spent.fluidExchange / reports,
                fluid_step_s=fluid_step, dem_substeps_s=dem_substeps, wall_per_step_s=wall / k,
                share_wall=exchange / (fluid_step + dem_substeps + exchange), share_of_wall=exchange / (wall / k),
                fluid_exchange_phases_cpu_s=phases)


def growth_exponent(rows, key: str) -> float:
    n = np.log([r["n"] for r in rows])
    t = np.log([r[key] for r in rows])
    return float(np.polyfit(n, t, 1)[0])


def main():
    parser = results.case_arguments(__doc__)
    parser.add_argument("--solver", default="talusPointForceFoam")
    parser.add_argument("--envelope-method", choices=["pairwise", "convolution"], default=None,
                        help="talusVolumeAveragedFoam's envelopeMethod (default: the solver's)")
    args = parser.parse_args()
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    # The DEM on one thread throughout: OpenMP threads spin at every barrier, and on a loaded
    # machine two of them ran the overhead's sub-steps many times slower than one, which made the
    # coupling's share look much smaller than it is (docs/coupling.md, "Measurements behind the
    # code").
    talus._dem.setThreadCount(1)
    name = "cfd.exchange_cost" + ("" if args.solver == "talusPointForceFoam" else "_va")
    case = results.Case(name + ("" if args.envelope_method is None else "_" + args.envelope_method),
                        quick=args.quick, folder=args.results)
    counts = [1000, 3000, 10000] if args.quick else [1000, 3000, 10000, 30000, 100000]
    rows = []
    for procs in (1, 2):
        for n in counts:
            row = measure_exchange(n, procs, args.solver, args.envelope_method)
            rows.append(row)
            print(f"{args.solver}, {procs} fluid rank(s), {n} particles: {row['seconds'] * 1e3:.2f} ms per exchange "
                  f"(DEM side {row['dem_seconds'] * 1e3:.2f}, fluid side {row['fluid_seconds'] * 1e3:.2f}), CPU "
                  f"{row['cpu_seconds'] * 1e3:.2f} ms ({row['dem_cpu_seconds'] * 1e3:.2f} + "
                  f"{row['fluid_cpu_seconds'] * 1e3:.2f}), {row['messages']} messages, {row['dem_doubles']} doubles "
                  f"through the DEM, particles per rank {row['particles_per_rank']} (sent {row['particles_sent_per_rank']})",
                  flush=True)
    exponents = {(procs, key): growth_exponent([r for r in rows if r["procs"] == procs], key)
                 for procs in (1, 2) for key in ("seconds", "cpu_seconds")}
    print("growth exponent of the exchange time: " + ", ".join(
        f"{exponents[p, k]:.2f} ({p} rank{'s' if p > 1 else ''}, {'wall' if k == 'seconds' else 'CPU'})"
        for p in (1, 2) for k in ("seconds", "cpu_seconds")))

    fig, ax = plt.subplots(figsize=(5.5, 4))
    for procs, colour in ((1, "C0"), (2, "C1")):
        sel = [r for r in rows if r["procs"] == procs]
        for key, style, what in (("seconds", "o-", "wall"), ("cpu_seconds", "s--", "CPU")):
            ax.loglog([r["n"] for r in sel], [r[key] * 1e3 for r in sel], style, color=colour, ms=4,
                      label=f"{procs} fluid rank{'s' if procs > 1 else ''}, {what} (slope {exponents[procs, key]:.2f})")
    first = rows[0]
    ns = np.array([counts[0], counts[-1]], dtype=float)
    ax.loglog(ns, first["cpu_seconds"] * 1e3 * ns / first["n"], "k:", lw=1, label="O(N)")
    ax.set_xlabel("particles N")
    ax.set_ylabel("time per exchange [ms]")
    ax.set_title(f"Coupling exchange ({args.solver}; loaded 2-core machine)", fontsize=9)
    ax.legend(fontsize=6)
    case.save_chart(fig)

    two = [r for r in rows if r["procs"] == 2]
    share = max(max(r["particles_per_rank"]) / r["n"] for r in two)
    sent_share = max(max(r["particles_sent_per_rank"]) / r["n"] for r in two)
    largest = {p: next(r for r in rows if r["procs"] == p and r["n"] == counts[-1]) for p in (1, 2)}
    bounded = all(len({r["messages"] for r in rows if r["procs"] == p}) == 1 for p in (1, 2))
    print(f"largest share of the particles owned by one of 2 ranks {share:.3f}, sent to one {sent_share:.3f}; "
          f"fluid side's CPU time at {counts[-1]} particles, 2 ranks / 1 rank: "
          f"{largest[2]['fluid_cpu_seconds'] / largest[1]['fluid_cpu_seconds']:.2f}", flush=True)
    case.record("largest share of the particles owned by one of 2 fluid ranks (the rest of those sent to it are "
                "within the envelope's cut-off of its cells: it computes their pairs with its own cells only)",
                share, "O(N/P): at most 0.6 with 2 ranks", 0.6, messages_independent_of_n=bounded,
                largest_share_sent=sent_share,
                fluid_cpu_two_ranks_over_one=largest[2]["fluid_cpu_seconds"] / largest[1]["fluid_cpu_seconds"],
                rows=rows)
    case.record("growth exponent of the CPU time per exchange (DEM side + slowest fluid rank) against the particle "
                f"count, 1 fluid rank, N = {counts[0]}-{counts[-1]}", exponents[1, "cpu_seconds"], "O(N): 1", 1.2,
                suffix="growth", exponent_two_ranks=exponents[2, "cpu_seconds"],
                exponent_wall_loaded=exponents[1, "seconds"], exponent_wall_loaded_two_ranks=exponents[2, "seconds"])

    steps = 20 if args.quick else 50
    bed_positions, bed_period = bed(BED_SIDE)
    for suffix, what, positions, period in (
            ("overhead", "dilute suspension (1 % solid, no contact: the cheapest DEM step)",
             lattice(OVERHEAD_N, np.random.default_rng(2)), None),
            ("overhead_bed", f"dense bed ({BED_SIDE}^3 touching spheres on a simple cubic lattice, periodic)",
             bed_positions, bed_period)):
        o = measure_overhead(args.solver, args.envelope_method, steps, positions, period)
        print(f"coupled step with {len(positions)} particles, {what}, {o['contacts']} contacts, {o['substeps']} DEM "
              f"sub-steps, CPU: exchange {o['exchange_cpu_s'] * 1e3:.2f} ms (DEM side {o['dem_coupling_cpu_s'] * 1e3:.2f}, "
              f"fluid side {o['fluid_exchange_cpu_s'] * 1e3:.2f}), fluid solution {o['fluid_step_cpu_s'] * 1e3:.2f} ms, "
              f"DEM sub-steps {o['dem_substeps_cpu_s'] * 1e3:.2f} ms: coupling share {o['share']:.3f}; wall (loaded): "
              f"exchange {o['exchange_s'] * 1e3:.2f} ms ({o['dem_coupling_s'] * 1e3:.2f} + "
              f"{o['fluid_exchange_s'] * 1e3:.2f}), fluid solution {o['fluid_step_s'] * 1e3:.2f} ms, DEM sub-steps "
              f"{o['dem_substeps_s'] * 1e3:.2f} ms: share {o['share_wall']:.3f} ({o['share_of_wall']:.3f} of the wall "
              f"time between exchanges, {o['wall_per_step_s'] * 1e3:.2f} ms)" + "".join(
                  f"\n  fluid side's {phase}: {seconds * 1e3:.2f} ms CPU"
                  for phase, seconds in o["fluid_exchange_phases_cpu_s"].items()), flush=True)
        case.record(f"coupling share of a coupled step at {len(positions)} particles in CPU time: exchange (DEM-side "
                    f"coupling work + the fluid rank's exchange) / (fluid step's solution + {o['substeps']} DEM "
                    f"sub-steps with collider and contact law, {what}, 1 DEM thread + exchange), 1 fluid rank",
                    o["share"], "below 20 % of the step time", 0.2, suffix=suffix, steps=steps, **o)
    if not bounded:
        raise SystemExit("the number of messages per exchange depends on the particle count")


if __name__ == "__main__":
    main()
