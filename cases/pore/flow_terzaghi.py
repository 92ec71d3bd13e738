"""Pore-scale flow case: Terzaghi consolidation of a saturated sphere packing in an oedometer,
DEM and pore flow coupled through the particle exchange interface.

Run:      build/bin/talus run cases/pore/flow_terzaghi.py [--quick] [--results DIR]
Set-up:   (after the seed's FlowEngine oedometer example) a seeded cloud between six frictionless
          walls, compacted to 10 kPa by growing the spheres (TriaxialStressController,
          internalCompaction, friction 3 deg), friction then set to 30 deg and the top wall alone
          servo-controlled (stressMask 2, bottom wall fixed, lateral walls fixed: oedometric).
          1. Drained reference: the vertical stress stepped from 10 to 11 kPa without fluid; the
             final settlement gives the oedometric modulus E_oed = 1 kPa / (s_final / H).
          2. Permeability K of the same packing (FlowEngine, pressure drop along y).
          3. Same step from the same saved state with the pore flow as an engine (talus.flow.
             FlowEngine, drained at the top wall only, the boundaries following the wall bodies,
             forces on spheres and walls, remeshing every 200 steps or at 5 % pore strain): the
             fluid first carries the load, then drains. Viscosity chosen so that the
             consolidation time H^2 / c_v, c_v = K E_oed / mu, is `--tc` seconds (0.6 s). Variant
             (not in quick mode unless --compressible): a compressible fluid, 10 tc, damping 0.6,
             the servo's gain matched to the undrained stiffness, fluidBulkModulus = n E_oed (Skempton
             B = m_v / (m_v + n / K_f) = 0.5): c_v = K / (mu (m_v + n / K_f)), initial excess
             pressure B * 1 kPa, instant settlement (1 - B) s_final, then s / s_final =
             1 - B (1 - U).
Checked:  degree of consolidation U = s(t) / s_final(drained) (compressible fluid:
          (s / s_final - 1 + B) / B) against Terzaghi's series
          U(Tv) = 1 - sum 8 / ((2m+1)^2 pi^2) exp(-(2m+1)^2 pi^2 Tv / 4), Tv = c_v t / H^2:
          worst |U - U_Terzaghi| for Tv in [0.05, 1] <= 0.05 (record flow.terzaghi, the issue's
          target "within 5 % of U after the initial transient"); the mean excess pore pressure
          over the pores against 1 - U (reported, record flow.terzaghi.pressure, bound 0.1).
Produces: records flow.terzaghi, flow.terzaghi.pressure (and flow.terzaghi.compressible in full
          mode); charts flow.terzaghi.png (U and mean pressure against Tv with Terzaghi's
          curves) and flow.terzaghi.error.png (U - U_Terzaghi against Tv).
"""
import math
import time

import numpy as np

from talus import results
from talus.dem import (FrictMat, GlobalStiffnessTimeStepper, InsertionSortCollider, InteractionLoop, NewtonIntegrator,
                       O, TriaxialStressController, setContactFriction, unbalancedForce, wall)
from talus.dem.step.engines import (Bo1_Sphere_Aabb, Bo1_Wall_Aabb, ForceResetter, Ig2_Sphere_Sphere_ScGeom,
                               Ig2_Wall_Sphere_ScGeom, Ip2_FrictMat_FrictMat_FrictPhys,
                               Law2_ScGeom_FrictPhys_CundallStrack)
from talus.dem.packing.pack import SpherePack
from talus.flow import FlowEngine

SIGMA0, DSIGMA, YOUNG = -1e4, -1e3, 1e6
WALLS = list(range(6))  # xmin, xmax, ymin, ymax, zmin, zmax as appended below


def terzaghi_u(tv):
    """Average degree of consolidation, one drained face."""
    tv = np.asarray(tv, dtype=float)
    u = np.ones_like(tv)
    for m in range(200):
        big_m = math.pi * (2 * m + 1) / 2
        u -= 2 / big_m ** 2 * np.exp(-big_m ** 2 * tv)
    return u


def compacted_sample(num: int, seed: int):
    O.materials.append(FrictMat(young=YOUNG, poisson=0.5, frictionAngle=math.radians(3), density=2600, label="spheres"))
    O.materials.append(FrictMat(young=YOUNG, poisson=0.5, frictionAngle=0, density=2600, label="walls"))
    lo, hi = (0, 0, 0), (1, 1, 1)
    O.bodies.append([wall(corner[axis], axis=axis, material="walls") for axis in range(3) for corner in (lo, hi)])
    sp = SpherePack()
    sp.makeCloud(lo, hi, -1, 0.3333, num, False, 0.95, seed=seed)
    sp.toSimulation(material="spheres")
    triax = TriaxialStressController(maxMultiplier=1 + 2e4 / YOUNG, finalMaxMultiplier=1 + 2e3 / YOUNG, thickness=0,
                                     stressMask=7, internalCompaction=True, goal1=SIGMA0, goal2=SIGMA0, goal3=SIGMA0)
    newton = NewtonIntegrator(damping=0.2)
    O.engines = [ForceResetter(), InsertionSortCollider([Bo1_Sphere_Aabb(), Bo1_Wall_Aabb()]),
                 InteractionLoop([Ig2_Sphere_Sphere_ScGeom(), Ig2_Wall_Sphere_ScGeom()],
                                 [Ip2_FrictMat_FrictMat_FrictPhys()], [Law2_ScGeom_FrictPhys_CundallStrack()]),
                 GlobalStiffnessTimeStepper(timeStepUpdateInterval=100, timestepSafetyCoefficient=0.8),
                 triax, newton]
    while True:
        O.run(1000, True)
        if unbalancedForce() < 0.001 and abs(SIGMA0 - triax.meanStress) / abs(SIGMA0) < 0.001:
            break
        if O.iter > 300000:
            raise RuntimeError("the isotropic compaction did not converge")
    setContactFriction(math.radians(30))
    triax.internalCompaction = False
    triax.stressMask = 2
    triax.goal1 = triax.goal3 = 0
    triax.wall_bottom_activated = False
    triax.wall_left_activated = triax.wall_right_activated = False
    triax.wall_back_activated = triax.wall_front_activated = False
    O.run(2000, True)   # settle the oedometric state at 10 kPa with the final friction
    return triax, newton


def top():
    return float(np.asarray(O.positions())[3][1])


def bottom():
    return float(np.asarray(O.positions())[2][1])


def box():
    p = np.asarray(O.positions())
    return [p[0][0], p[1][0], p[2][1], p[3][1], p[4][2], p[5][2]]


def permeability() -> float:
    """Darcy permeability along y of the current packing, walls at the wall bodies, mu = 1."""
    flow = FlowEngine(bndCondIsPressure=[0, 0, 1, 1, 0, 0], bndCondValue=[0, 0, 1, 0, 0, 0],
                      boundaryUseMaxMin=[0] * 6, wallPosition=box())
    flow.triangulateScene(O)
    flow.solve()
    return flow.samplePermeability(2, 3)


def load_step(steps: int, sample_every: int, flow=None):
    """Step the top stress to SIGMA0 + DSIGMA; series of time, settlement, mean excess pressure."""
    t0, y0 = O.time, top()
    series = {"t": [0.0], "s": [0.0], "p": [0.0]}
    [e for e in O.engines if isinstance(e, TriaxialStressController)][0].goal2 = SIGMA0 + DSIGMA
    for _ in range(steps // sample_every):
        O.run(sample_every, True)
        series["t"].append(O.time - t0)
        series["s"].append(y0 - top())
        if flow is not None:
            v = np.maximum(flow.cellVoidVolumes, 0)
            series["p"].append(float(np.sum(flow.pressures * v) / np.sum(v)))
    return {k: np.array(v) for k, v in series.items()}


def main():
    parser = results.case_arguments(__doc__)
    parser.add_argument("--tc", type=float, default=0.6, help="consolidation time H^2/c_v in seconds")
    parser.add_argument("--damping", type=float, default=0.2, help="NewtonIntegrator damping while loading")
    parser.add_argument("--compressible", action="store_true", help="run the compressible variant in quick mode too")
    parser.add_argument("--compressible-damping", type=float, default=0.6,
                        help="NewtonIntegrator damping of the compressible run")
    args = parser.parse_args()
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    case = results.Case("flow.terzaghi", quick=args.quick, folder=args.results)
    num = 400 if args.quick else 1000
    start = time.perf_counter()
    triax, newton = compacted_sample(num, seed=1)
    # the servo-loaded top wall rings (the drained settlement swings by +-50 % for a few periods
    # of ~0.25 s at damping 0.2); more damping slows the loading down instead (0.7: the excess
    # pressure peaks at half the load only): 0.2 is the better compromise here
    newton.damping = args.damping
    height = top() - bottom()
    print(f"compacted {num} spheres in {time.perf_counter() - start:.1f} s, {O.iter} steps, dt {O.dt:.3g} s, "
          f"porosity {triax.porosity:.3f}, height {height:.4f}")
    # fixed dt from here on (the time series and the compressible storage term use it)
    O.engines = [e for e in O.engines if not isinstance(e, GlobalStiffnessTimeStepper)]
    O.saveTmp("oedometer")

    k = permeability()
    # drained reference: long enough for the settlement to stop
    steps = int(round(3 * args.tc / O.dt))
    every = max(1, steps // 300)
    drained = load_step(2 * steps, every)
    s_final = float(np.mean(drained["s"][-len(drained["s"]) // 3:]))   # the wall still swings a little
    e_oed = abs(DSIGMA) / (s_final / height)
    porosity = float(triax.porosity)
    print(f"K = {k:.4e} m^2 (mu = 1), drained settlement {s_final:.4e} m, E_oed {e_oed:.4e} Pa, n {porosity:.3f}")

    def coupled(bulk: float, tc: float):
        O.loadTmp("oedometer", engines="current")
        m_v = 1 / e_oed
        storage = m_v + (porosity / bulk if bulk > 0 else 0.0)
        # The servo moves the wall by (force gap) / (contact stiffness) x (1 - stressDamping),
        # but a compressible pore fluid stiffens the sample at once, to E_oed / (1 - B): the
        # loop gain is (1 - stressDamping) / (1 - B), 1.5 at B = 0.5 with the default 0.25,
        # and the wall rings. 1 - stressDamping = (1 - B) / 2 halves the gap each step. (An
        # incompressible fluid keeps the default: the fluid takes the load and the wall stays.)
        triax.stressDamping = 1 - 0.5 * (1 - m_v / storage) if bulk > 0 else 0.25
        # The sudden undrained response (1 - B) s_final also sets the column ringing in its first
        # elastic mode (period 4 H / c ~ 0.19 s here, seen as U swinging by 0.17 up to Tv 0.25):
        # more damping for the compressible run, where that mode is excited
        newton.damping = args.compressible_damping if bulk > 0 else args.damping
        mu = k * tc / (height ** 2 * storage)
        flow = FlowEngine(bndCondIsPressure=[0, 0, 0, 1, 0, 0], bndCondValue=[0] * 6, boundaryUseMaxMin=[0] * 6,
                          wallIds=WALLS, viscosity=mu, meshUpdateInterval=200, defTolerance=0.05,
                          fluidBulkModulus=bulk)
        # loadTmp(engines="current") keeps the engine list: drop the previous run's flow engine,
        # else two pore flows act at once (its stale mesh, its forces counted twice)
        engines = [e for e in O.engines if not isinstance(e, FlowEngine)]
        engines.insert(3, flow)   # after the contact forces, before the time stepper and the controller
        O.engines = engines
        n_steps = int(round(3 * tc / O.dt))
        series = load_step(n_steps, max(1, n_steps // 300), flow)
        series["Tv"] = series["t"] / tc
        b = m_v / storage
        # the fluid's compression settles (1 - B) of s_final at once; the rest consolidates:
        # s / s_final = 1 - B (1 - U)
        series["U"] = (series["s"] / s_final - (1 - b)) / b
        series["p_rel"] = series["p"] / (b * abs(DSIGMA))
        return series, flow, mu, b

    wet, flow, mu, _ = coupled(0.0, args.tc)
    window = (wet["Tv"] >= 0.05) & (wet["Tv"] <= 1.0)
    u_an = terzaghi_u(wet["Tv"])
    err = float(np.max(np.abs(wet["U"] - u_an)[window]))
    p_err = float(np.max(np.abs(wet["p_rel"] - (1 - u_an))[window]))
    print(f"incompressible: mu {mu:.4g}, worst |U - U_T| {err:.4f}, worst |p/dsigma - (1 - U_T)| {p_err:.4f}, "
          f"remeshes {flow.remeshCount()}, solver {flow.solverStats()}")
    common = dict(spheres=num, height=height, permeability=k, E_oed=e_oed, porosity=porosity, viscosity=mu,
                  dt=O.dt, tc=args.tc, remeshes=list(flow.remeshCount()))
    case.record("worst |U - U_Terzaghi| for Tv in [0.05, 1] (incompressible fluid)", err,
                "Terzaghi's series with c_v = K E_oed / mu (K and E_oed measured on the same packing)", 0.05,
                **common)
    case.record("worst |mean excess pore pressure / load - (1 - U_Terzaghi)| for Tv in [0.05, 1]", p_err,
                "Terzaghi's series (mean excess pressure = 1 - U)", 0.1, suffix="pressure", **common)
    runs = [("incompressible", wet)]
    if not args.quick or args.compressible:
        # ten times slower, so that the ringing of the instant (1 - B) settlement (a few periods
        # of the column's first mode, ~0.2 s) is over by Tv 0.05
        comp, flow_c, mu_c, b = coupled(porosity * e_oed, 10 * args.tc)
        window_c = (comp["Tv"] >= 0.05) & (comp["Tv"] <= 1.0)
        err_c = float(np.max(np.abs(comp["U"] - terzaghi_u(comp["Tv"]))[window_c]))
        print(f"compressible (B = {b:.2f}): worst |U - U_T| {err_c:.4f}")
        case.record("worst |U - U_Terzaghi| for Tv in [0.05, 1], compressible fluid (Skempton B = 0.5)", err_c,
                    "Terzaghi's series with c_v = K / (mu (m_v + n / K_f))", 0.05, suffix="compressible",
                    B=b, **common)
        runs.append((f"compressible, B = {b:.2f}", comp))

    tv = np.linspace(0, wet["Tv"].max(), 300)
    fig, ax = plt.subplots(figsize=(6, 4.5))
    ax.plot(tv, terzaghi_u(tv), "k-", label="Terzaghi U")
    ax.plot(tv, 1 - terzaghi_u(tv), "k--", label="Terzaghi 1 - U (mean excess pressure)")
    for (label, s), c in zip(runs, ("C0", "C1")):
        ax.plot(s["Tv"], s["U"], "o", color=c, ms=3, mfc="none", label=f"U, {label}")
        ax.plot(s["Tv"], s["p_rel"], "x", color=c, ms=3, label=f"p / (B load), {label}")
    ax.plot(drained["t"] / args.tc, drained["s"] / s_final, ":", color="gray", label="drained (no fluid)")
    ax.set_xlabel("Tv = c_v t / H$^2$")
    ax.set_ylabel("U, normalised mean pore pressure")
    ax.set_xlim(0, min(2.0, tv.max()))
    ax.set_title(f"Terzaghi consolidation, {num} spheres, DEM + pore flow")
    ax.legend(fontsize=7)
    case.save_chart(fig)

    fig, ax = plt.subplots(figsize=(6, 3.5))
    for (label, s), c in zip(runs, ("C0", "C1")):
        ax.plot(s["Tv"], s["U"] - terzaghi_u(s["Tv"]), "-", color=c, label=label)
    ax.axhspan(-0.05, 0.05, color="0.9", label="5 % band")
    ax.axvspan(0, 0.05, color="0.8", alpha=0.5, label="initial transient (excluded)")
    ax.set_xlim(0, min(2.0, tv.max()))
    ax.set_xlabel("Tv")
    ax.set_ylabel("U - U_Terzaghi")
    ax.legend(fontsize=7)
    case.save_chart(fig, "error")


if __name__ == "__main__":
    main()
