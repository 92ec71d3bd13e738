"""CFD-DEM case: cost of one coupling exchange against the particle count and the number of
fluid ranks, and the coupling's share of a coupled step at 10 000 particles (issue #6: O(N/P)
data per rank, a bounded number of messages, overhead below 20 % of the step time).

Run:      build/bin/talus run cases/cfd_exchange_cost.py [--quick] [--results DIR]
          [--solver talusPointForceFoam|talusVolumeAveragedFoam]
Set-up:   the closed box of cases/cfd_settling_sphere/ (45 x 45 x 90 mm; rho = 1000 kg/m3,
          nu = 1e-3 m2/s) meshed 10 x 10 x 20 (cells 4.5 mm), decomposed along z for 2 ranks;
          fluid step 20 us; spheres r = 0.35 mm (d/dx = 0.16), rho_p = 2500 (relaxation time
          68 us).
          Exchange cost: N spheres at random positions (seed 1), one DEM step per fluid step
          without contacts; 2 warm-up exchanges, then 20 measured; N = 1000, 3000, 10000
          (quick), also 30000 and 100000 (full); 1 and 2 fluid ranks.
          Overhead: 10000 spheres on a jittered lattice (a dilute suspension, 1 % solid, no
          contact: the cheapest DEM step, so the largest share the coupling can take) with the
          usual DEM loop (collider, contact law, Newton; E = 50 MPa, DEM step 0.8 of the P-wave
          step: 11 sub-steps per fluid step), 1 fluid rank; 2 warm-up fluid steps, then 10
          (quick) or 30 (full) measured.
Measured: per exchange the messages (DEM <-> fluid and between fluid ranks), the doubles the
          DEM process sends and receives, the particles each fluid rank gets, and the time of
          one exchange = the DEM's own coupling work (gathering the particles' state, sorting it
          into the ranks' arrays, summing and applying the forces) + the slowest fluid rank's
          exchange (receiving the particles, locating them, computing the forces and their
          reactions, halo messages, sending the forces; timed by the rank itself, so the time
          the DEM waits while the fluid still solves is not counted); medians. The growth
          exponent of the exchange time against N (least squares in log-log, 1 rank).
          The coupled step = the fluid step's solution (the fluid rank's own time) + the DEM's
          11 sub-steps (the DEM loop's wall time minus the coupling's hooks) + the exchange;
          the overhead is the exchange's share of that sum (the fluid and the DEM sub-steps
          run at the same time when each has its own core: the share of the wall time between
          exchanges is recorded beside it).
Checked:  the messages do not depend on N (3 per fluid rank plus at most 1 per neighbouring
          rank and reduction); with 2 ranks no rank gets more than 60 % of the particles
          (O(N/P)); growth exponent at most 1.2 (O(N)); overhead at most 0.2.
Produces: records cfd.exchange_cost (largest share of the particles on one of 2 ranks),
          cfd.exchange_cost.growth, cfd.exchange_cost.overhead (cfd.exchange_cost_va.* with the
          volume-averaged solver); chart cfd.exchange_cost.png (time per exchange against N for
          1 and 2 fluid ranks, with the O(N) line).
"""
import time
from pathlib import Path

import numpy as np

from talus import results
from talus.coupling import FoamCoupling
from talus.coupling.cases import mesh_case
from talus.dem import (Bo1_Sphere_Aabb, ForceResetter, FrictMat, Ig2_Sphere_Sphere_ScGeom, InsertionSortCollider,
                       InteractionLoop, Ip2_FrictMat_FrictMat_FrictPhys, Law2_ScGeom_FrictPhys_CundallStrack,
                       NewtonIntegrator, PWaveTimeStep, Scene, sphere)

HERE = Path(__file__).resolve().parent
CASE = HERE / "cfd_settling_sphere"
RADIUS, RHO_P, RHO, NU, G = 3.5e-4, 2500.0, 1000.0, 1e-3, (0.0, 0.0, -9.81)
LOW, HIGH = np.array([-0.022, -0.022, 0.001]), np.array([0.022, 0.022, 0.089])  # inside the box
DT_FLUID = 2e-5  # the case's system/controlDict deltaT
OVERHEAD_N = 10000
MEASURED = 20  # exchanges measured per particle count (medians: the loaded machine's times scatter)


def mesh(procs: int) -> Path:
    def cells(work: Path):
        block = work / "system" / "blockMeshDict"
        block.write_text(block.read_text().replace("(9 9 18)", "(10 10 20)"))
    return mesh_case(CASE, procs, edit=cells, prefix="talus_cfd_exchange_")


def scene_of(positions: np.ndarray, contacts: bool) -> Scene:
    s = Scene()
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


def measure_exchange(n: int, procs: int, solver: str) -> dict:
    """Cost of one exchange with n particles on procs fluid ranks (one DEM step per fluid step)."""
    work = mesh(procs)
    x = np.random.default_rng(1).uniform(LOW, HIGH, size=(n, 3))
    s = scene_of(x, contacts=False)
    s.dt = DT_FLUID
    coupling = FoamCoupling(s, work, rhoFluid=RHO, nu=NU, gravity=G, nProcs=procs, solver=solver).start()
    try:
        s.run(2, True)
        dem, fluid, messages, doubles = [], [], [], []
        for _ in range(MEASURED):
            before = coupling.times.copy()
            s.run(1, True)
            dem.append(coupling.times.since(before).dem)
            fluid.append(coupling.link.lastFluidExchangeSeconds)  # the previous exchange's
            messages.append(coupling.link.lastMessages)
            doubles.append(coupling.link.lastDemDoubles)
        boxes = np.array(coupling.link.boxes).reshape(-1, 7)
    finally:
        coupling.stop()
    per_rank = [int(np.all((x >= b[:3] - b[6]) & (x <= b[3:6] + b[6]), axis=1).sum()) for b in boxes]
    dem_s, fluid_s = float(np.median(dem)), float(np.median(fluid))
    return dict(n=n, procs=procs, seconds=dem_s + fluid_s, dem_seconds=dem_s, fluid_seconds=fluid_s,
                messages=int(max(messages)), dem_doubles=int(np.median(doubles)), particles_per_rank=per_rank)


def measure_overhead(solver: str, steps: int) -> dict:
    """Where the time of a coupled step goes with OVERHEAD_N particles and the full DEM loop."""
    work = mesh(1)
    s = scene_of(lattice(OVERHEAD_N, np.random.default_rng(2)), contacts=True)
    s.dt = 0.8 * PWaveTimeStep(s)
    coupling = FoamCoupling(s, work, rhoFluid=RHO, nu=NU, gravity=G, solver=solver).start()
    try:
        s.run(2 * coupling.substeps, True)
        before = coupling.times.copy()
        start = time.perf_counter()
        s.run(steps * coupling.substeps, True)
        wall = time.perf_counter() - start
        spent = coupling.times.since(before)
    finally:
        coupling.stop()
    exchange = spent.dem / spent.exchanges + spent.fluidExchange / spent.fluidReports
    fluid_step = spent.fluidSteps / spent.fluidReports
    dem_substeps = (wall - spent.dem - spent.waiting) / spent.exchanges
    return dict(substeps=coupling.substeps, exchange_s=exchange, dem_coupling_s=spent.dem / spent.exchanges,
                fluid_exchange_s=spent.fluidExchange / spent.fluidReports, fluid_step_s=fluid_step,
                dem_substeps_s=dem_substeps, wall_per_step_s=wall / spent.exchanges,
                share=exchange / (fluid_step + dem_substeps + exchange),
                share_of_wall=exchange / (wall / spent.exchanges))


def growth_exponent(rows) -> float:
    n = np.log([r["n"] for r in rows])
    t = np.log([r["seconds"] for r in rows])
    return float(np.polyfit(n, t, 1)[0])


def main():
    parser = results.case_arguments(__doc__)
    parser.add_argument("--solver", default="talusPointForceFoam")
    args = parser.parse_args()
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    case = results.Case("cfd.exchange_cost" + ("" if args.solver == "talusPointForceFoam" else "_va"),
                        quick=args.quick, folder=args.results)
    counts = [1000, 3000, 10000] if args.quick else [1000, 3000, 10000, 30000, 100000]
    rows = []
    for procs in (1, 2):
        for n in counts:
            row = measure_exchange(n, procs, args.solver)
            rows.append(row)
            print(f"{args.solver}, {procs} fluid rank(s), {n} particles: {row['seconds'] * 1e3:.2f} ms per exchange "
                  f"(DEM side {row['dem_seconds'] * 1e3:.2f}, fluid side {row['fluid_seconds'] * 1e3:.2f}), "
                  f"{row['messages']} messages, {row['dem_doubles']} doubles through the DEM, particles per rank "
                  f"{row['particles_per_rank']}", flush=True)
    exponents = {procs: growth_exponent([r for r in rows if r["procs"] == procs]) for procs in (1, 2)}
    print(f"growth exponent of the exchange time: {exponents[1]:.2f} (1 rank), {exponents[2]:.2f} (2 ranks)")

    fig, ax = plt.subplots(figsize=(5.5, 4))
    for procs in (1, 2):
        sel = [r for r in rows if r["procs"] == procs]
        ax.loglog([r["n"] for r in sel], [r["seconds"] * 1e3 for r in sel], "o-",
                  label=f"{procs} fluid rank{'s' if procs > 1 else ''} (slope {exponents[procs]:.2f})")
    first = rows[0]
    ns = np.array([counts[0], counts[-1]], dtype=float)
    ax.loglog(ns, first["seconds"] * 1e3 * ns / first["n"], "k--", lw=0.8, label="O(N)")
    ax.set_xlabel("particles N")
    ax.set_ylabel("wall time per exchange [ms]")
    ax.set_title(f"Coupling exchange ({args.solver}; loaded 2-core machine)", fontsize=9)
    ax.legend(fontsize=7)
    case.save_chart(fig)

    two = [r for r in rows if r["procs"] == 2]
    share = max(max(r["particles_per_rank"]) / r["n"] for r in two)
    bounded = all(len({r["messages"] for r in rows if r["procs"] == p}) == 1 for p in (1, 2))
    case.record("largest share of the particles sent to one of 2 fluid ranks", share,
                "O(N/P): at most 0.6 with 2 ranks", 0.6, messages_independent_of_n=bounded, rows=rows)
    case.record("growth exponent of the time per exchange against the particle count (1 fluid rank, "
                f"N = {counts[0]}-{counts[-1]}; loaded machine)", exponents[1], "O(N): 1", 1.2,
                suffix="growth", exponent_two_ranks=exponents[2])

    steps = 10 if args.quick else 30
    o = measure_overhead(args.solver, steps)
    print(f"coupled step with {OVERHEAD_N} particles, {o['substeps']} DEM sub-steps: exchange "
          f"{o['exchange_s'] * 1e3:.2f} ms (DEM side {o['dem_coupling_s'] * 1e3:.2f}, fluid side "
          f"{o['fluid_exchange_s'] * 1e3:.2f}), fluid solution {o['fluid_step_s'] * 1e3:.2f} ms, DEM sub-steps "
          f"{o['dem_substeps_s'] * 1e3:.2f} ms: coupling share {o['share']:.3f} of the step "
          f"({o['share_of_wall']:.3f} of the wall time between exchanges, {o['wall_per_step_s'] * 1e3:.2f} ms)")
    case.record(f"coupling share of a coupled step at {OVERHEAD_N} particles: exchange (DEM-side coupling work + "
                f"the fluid rank's exchange) / (fluid step's solution + {o['substeps']} DEM sub-steps with collider "
                "and contact law, dilute suspension + exchange), 1 fluid rank, loaded machine", o["share"],
                "issue #6: below 20 % of the step time", 0.2, suffix="overhead", steps=steps, **o)
    if not bounded:
        raise SystemExit("the number of messages per exchange depends on the particle count")


if __name__ == "__main__":
    main()
