"""VANS case: two-way coupled bedload transport, the seed's sediment-transport example.

Run:      OMP_NUM_THREADS=1 build/bin/talus run cases/vans/vans_sediment_transport.py [--quick] [--results DIR]
Set-up:   Yade's twoWayCoupling/sedimentTransportExample_1DRANSCoupling.py: 6 mm grains
          (rho_p 2500 kg/m^3, visco-elastic contacts with restitution 0.7, friction 0.5, normal
          stiffness in the rigid limit 1e4 x the static bed pressure x d), 10 mobile layers over a
          rough bed of fixed grains at random heights, water (rho 1000, nu 1e-6 m^2/s) 17.5 d
          deep, slope 0.05 rad, 10 d x 10 d periodic cell; HydroForceEngine with the Dallavalle
          drag and Richardson-Zaki exponent 3.1, ndimz = 900, Li-Sawamoto mixing length
          (phiMax 0.61), free surface. Gravity deposition (damping 0.2, no fluid) for 0.4 s, then
          a 1 s fluid resolution, then DEM and fluid alternate every 1e-2 s (fluid step 1e-5 s).
          The grains start from a jittered lattice (Talus has no makeCloud yet) with a seed.
Checked:  the run stays stable (no overlap or non-finite force error, no grain out of the grid)
          and transports sediment: time-averaged dimensionless transport rate > 0 over the
          second half (record vans.sediment-transport, with the series' mean and standard
          error; Shields number and the coupling's fluid-change statistics as extras). The
          time-averaged rate against Yade's, from the same developed state, is
          cases/vans/vans_bench_coupled.py's full mode (record vans.transport-vs-yade).
          Quick: 0.3 s of deposition, 1 s of transport; full: 0.4 s and 10 s. Run it with
          OMP_NUM_THREADS=1 on a loaded machine (OpenMP threads waiting for a busy core cost far
          more than they gain; talus -j1 is too late, libgomp is loaded with the CLI).
Produces: record vans.sediment-transport; charts vans.sediment-transport.series.png (transport
          rate and Shields number against time) and vans.sediment-transport.profiles.png
          (solid fraction, particle and fluid velocity, averaged over the second half).
"""
import math
import random
import time

import numpy as np

from talus import results
from talus.dem import (ForceResetter, InsertionSortCollider, InteractionLoop, Ip2_ViscElMat_ViscElMat_ViscElPhys,
                       Law2_ScGeom_ViscElPhys_Basic, NewtonIntegrator, Scene, ViscElMat, sphere)
from talus.flow import HydroForceEngine, VansCoupling

D, RHO_P, PHI_MAX, EN, FRICTION = 6e-3, 2500.0, 0.61, 0.7, math.atan(0.5)
RHO_F, NU = 1000.0, 1e-6
WATER_DEPTH, N_LAYER, SLOPE = 17.5, 10, 0.05
DT_FLUID, PERIOD = 1e-5, 1e-2
N_CELL = 900
LENGTH = WIDTH = 10 * D
FLUID_HEIGHT = (N_LAYER + WATER_DEPTH) * D
HEIGHT = 5 * FLUID_HEIGHT
GROUND = HEIGHT / 4
GRAVITY = (9.81 * math.sin(SLOPE), 0.0, -9.81 * math.cos(SLOPE))


def material() -> ViscElMat:
    """Yade's example: kn from a Young modulus in the rigid limit; here the per-material spring
    and dashpot whose series (two equal grains) give the same contact kn and restitution EN."""
    max_pressure = (RHO_P - RHO_F) * PHI_MAX * N_LAYER * D * abs(GRAVITY[2])
    kn_contact = max_pressure * D * 1e4 / 2          # Yade: kn = 2 E r1 r2/(r1 + r2), E = k/d
    mass = RHO_P * math.pi / 6 * D ** 3
    ln = math.log(EN)
    cn_contact = -2 * math.sqrt(kn_contact * mass / 2) * ln / math.sqrt(math.pi ** 2 + ln ** 2)
    return ViscElMat(kn=2 * kn_contact, cn=2 * cn_contact, ks=kn_contact, cs=0.0, density=RHO_P,
                     frictionAngle=FRICTION)


def build(seed: int = 1):
    rnd = random.Random(seed)
    s = Scene()
    s.periodic = True
    s.cell.setBox(LENGTH, WIDTH, HEIGHT)
    s.materials.append(material())
    for x in range(10):                               # the rough bed: fixed grains
        for y in range(10):
            s.bodies.append(sphere((x * D, y * D, GROUND + (-0.5 + rnd.random()) * D), D / 2, fixed=True))
    count = int(N_LAYER * PHI_MAX * D * LENGTH * WIDTH / (math.pi / 6 * D ** 3))
    per_side = 9
    step = LENGTH / per_side
    mobile = []
    k = 0
    while len(mobile) < count:
        layer, rest = divmod(k, per_side * per_side)
        i, j = divmod(rest, per_side)
        centre = ((i + 0.5) * step + 0.3e-3 * (rnd.random() - 0.5), (j + 0.5) * step + 0.3e-3 * (rnd.random() - 0.5),
                  GROUND + 1.6 * D + 1.15 * D * layer)
        mobile.append(s.bodies.append(sphere(centre, D / 2)))
        k += 1
    dz = FLUID_HEIGHT / (N_CELL - 1)
    hydro = HydroForceEngine(densFluid=RHO_F, viscoDyn=NU * RHO_F, zRef=GROUND, gravity=GRAVITY, deltaZ=dz,
                             expoRZ=3.1, lift=False, nCell=N_CELL, vCell=LENGTH * WIDTH * dz, radiusPart=D / 2,
                             phiMax=PHI_MAX, ids=mobile, scene=s, dead=True, label="")
    return s, hydro, engines(s, hydro, GRAVITY), mobile


def engines(s, hydro, gravity):
    """The engines of Yade's example: the visco-elastic contacts, `hydro` and Cundall damping 0.2
    (for the deposition; start_fluid turns it off); dt 2e-5 s. Returns the NewtonIntegrator."""
    newton = NewtonIntegrator(damping=0.2, gravity=gravity)
    s.engines = [ForceResetter(), InsertionSortCollider(),
                 InteractionLoop([], [Ip2_ViscElMat_ViscElMat_ViscElPhys()], [Law2_ScGeom_ViscElPhys_Basic()]),
                 hydro, newton]
    s.dt = 2e-5
    return newton


def start_fluid(hydro, newton, dt_fluid=DT_FLUID, initial=1.0, vx_fluid=None):
    """Switch the fluid on as Yade's gravityDeposition() does: no damping, the engine alive, a
    Reynolds stress of 1e-4 in every cell, the solid phase averaged; then the start-up fluid
    resolution over `initial` seconds from those profiles or, for a developed flow handed over
    from an earlier run, that run's fluid velocity profile `vx_fluid`. The coupling is the
    caller's."""
    newton.damping = 0.0
    hydro.dead = False
    hydro.ReynoldStresses = np.full(hydro.nCell, 1e-4)
    hydro.averageProfile()
    if vx_fluid is None:
        hydro.fluidResolution(initial, dt_fluid)
    else:
        hydro.vxFluid = vx_fluid


def main():
    args = results.case_arguments(__doc__).parse_args()
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    case = results.Case("vans.sediment-transport", quick=args.quick, folder=args.results)
    deposition, transport = (0.3, 1.0) if args.quick else (0.4, 10.0)
    s, hydro, newton, mobile = build()
    start = time.perf_counter()
    s.run(round(deposition / s.dt))
    wall_depo = time.perf_counter() - start
    print(f"{len(mobile)} grains deposited in {wall_depo:.1f} s wall ({s.iter} steps)")

    start_fluid(hydro, newton)
    coupling = VansCoupling(hydro, PERIOD, DT_FLUID, densPart=RHO_P, diameterPart=D)
    coupling.attach()
    profiles = {"phi": [], "vx": [], "u": []}
    steps = round(transport / s.dt)
    chunk = round(PERIOD / s.dt)
    start = time.perf_counter()
    t0 = s.time
    while s.iter * s.dt < t0 + transport - 0.5 * s.dt and s.time < t0 + transport:
        s.run(chunk)
        if s.time - t0 > transport / 2:
            profiles["phi"].append(hydro.phiPart)
            profiles["vx"].append(hydro.vxPart * hydro.phiPart)    # phi-weighted, see below
            profiles["u"].append(hydro.vxFluid)
    wall = time.perf_counter() - start
    series = coupling.series
    t = np.array(series["time"]) - t0
    qs = np.array(series["transportRate"])
    shields = np.array(series["shieldsNumber"])
    second = t > transport / 2
    mean_qs = float(np.mean(qs[second]))
    err_qs = float(np.std(qs[second]) / math.sqrt(max(1, second.sum())))
    print(f"transport {transport:g} s in {wall:.1f} s wall ({steps} DEM steps, {len(t)} couplings): "
          f"qs* = {mean_qs:.4f} +- {err_qs:.4f}, Shields {np.mean(shields[second]):.4f}, "
          f"max fluid change between couplings (second half) "
          f"{np.max(np.array(series['fluidChange'])[second]):.3f}")
    case.record("time-averaged dimensionless transport rate (second half)", mean_qs,
                "sediment is transported (>= 1e-6); against Yade: vans.transport-vs-yade", 1e-6, comparison=">=",
                standard_error=err_qs, shields_mean=float(np.mean(shields[second])), couplings=len(t),
                transport_s=transport, wall_transport_s=wall, wall_deposition_s=wall_depo,
                grains=len(mobile), max_fluid_change=float(np.max(np.array(series["fluidChange"])[second])),
                dem_dt=s.dt)

    fig, (a1, a2) = plt.subplots(2, 1, figsize=(6, 5), sharex=True)
    a1.plot(t, qs, "b-", lw=0.8)
    a1.set_ylabel("transport rate $q_s^*$")
    a2.plot(t, shields, "r-", lw=0.8)
    a2.set_ylabel("Shields number")
    a2.set_xlabel("time since the fluid was switched on (s)")
    a1.set_title(f"Two-way coupled bedload: $q_s^*$ = {mean_qs:.3f} ± {err_qs:.3f} (second half)")
    case.save_chart(fig, "series")

    zc = (np.arange(N_CELL) + 0.5) * hydro.deltaZ / D
    fig, (b1, b2, b3) = plt.subplots(1, 3, figsize=(9, 4), sharey=True)
    b1.plot(np.mean(profiles["phi"], axis=0), zc)
    b1.set_xlabel("solid fraction")
    b1.set_ylabel("z / d")
    # Mean particle velocity weighted by the solid fraction: <phi v> / <phi> (layers that are
    # empty in some samples do not pull the mean down).
    phi_mean = np.mean(profiles["phi"], axis=0)
    occupied = phi_mean > 1e-4
    b2.plot(np.mean(profiles["vx"], axis=0)[occupied] / phi_mean[occupied], zc[occupied])
    b2.set_xlabel("particle velocity (m/s)")
    b3.plot(np.mean(profiles["u"], axis=0), (hydro.fluid.zFluid) / D)
    b3.set_xlabel("fluid velocity (m/s)")
    fig.suptitle("Profiles averaged over the second half")
    case.save_chart(fig, "profiles")


if __name__ == "__main__":
    main()
