"""VANS benchmark: the coupled sediment-transport example in Talus and in Yade, same run length.

Run:      OMP_NUM_THREADS=1 build/bin/talus run cases/vans/vans_bench_coupled.py [--quick] [--results DIR]
          [--develop SECONDS] [--coupled SECONDS]
Set-up:   the scene of cases/vans/vans_sediment_transport.py (1165 grains over 100 fixed ones, 6 mm,
          10 d x 10 d periodic cell, ndimz = 900, fluid step 1e-5 s, coupling every 1e-2 s),
          built once and given to both programs (positions, materials, engines as Yade's example:
          ForceResetter, collider, visco-elastic InteractionLoop, HydroForceEngine, a coupling
          PyRunner calling averageProfile() + fluidResolution(), NewtonIntegrator), single-threaded
          (yade -j1; OMP_NUM_THREADS=1 for Talus: talus -j1 comes too late, libgomp is already
          loaded when the CLI sets it). Each runs a deposition phase without fluid (timed), then
          the compared coupled phase (timed) from the same state, Talus's, written to a JSON
          file. Quick: 0.05 s deposition, then 0.1 s coupled from the deposited bed after Yade's
          1 s start-up fluid resolution. Full: 0.4 s deposition, then Talus develops the flow
          for 8 s of coupled transport (not timed, Talus only) and both programs restart from
          that state (positions, velocities, spins, fluid velocity profile; fresh contacts) for
          4 s of coupled transport. --develop and --coupled override the mode's lengths.
Checked:  speed ratio Yade time / Talus time of the compared coupled phase (the target
          >= 3), record vans.bench.coupled (wall times; the ratio of the single-threaded runs'
          CPU times, which the load of a shared machine does not skew, and the deposition
          ratios are extras). When the averaging
          window holds at least four 0.5 s blocks (full mode): the transport rate q_s* averaged
          over the compared phase (its second half when it starts from the deposited bed) in
          both programs, standard errors from 0.5 s block means; record vans.transport-vs-yade,
          the difference in standard errors (<= 3: within scatter). Yade's q_s* is computed from
          its averageProfile() of each coupling, as Talus's. If yade is not installed the case
          says so and records nothing.
"""
import json
import shutil
import subprocess
import tempfile
import time
from pathlib import Path

import numpy as np

from talus import results

import vans_sediment_transport as st

YADE_SCRIPT = r'''
import json, sys, time
from yade import *
cfg = json.load(open(sys.argv[-2]))
O.periodic = True
O.cell.setBox(*cfg["box"])
m = cfg["material"]
O.materials.append(ViscElMat(kn=m["kn"], cn=m["cn"], ks=m["ks"], cs=m["cs"], density=m["density"],
                             frictionAngle=m["frictionAngle"], label="Mat"))
for (x, y, z), fixed in zip(cfg["pos"], cfg["fixed"]):
    O.bodies.append(sphere((x, y, z), cfg["radius"], fixed=fixed, material="Mat"))
for i, v in enumerate(cfg["vel"]):
    O.bodies[i].state.vel = Vector3(*v)
h = cfg["hydro"]
hydro = HydroForceEngine(densFluid=h["densFluid"], viscoDyn=h["viscoDyn"], zRef=h["zRef"],
                         gravity=Vector3(*h["gravity"]), deltaZ=h["deltaZ"], expoRZ=3.1, lift=False,
                         nCell=h["nCell"], vCell=h["vCell"], radiusPart=h["radiusPart"], phiMax=h["phiMax"],
                         ids=cfg["mobile"], dead=True)
series = {"time": [], "qs": []}
scale = ((cfg["densPart"] / h["densFluid"] - 1) * abs(h["gravity"][2]) * cfg["diameter"] ** 3) ** 0.5
def fluidModel():
    hydro.averageProfile()
    hydro.fluidResolution(cfg["period"], cfg["dtFluid"])
    phi, v = hydro.phiPart, hydro.vPart
    series["time"].append(O.time)
    series["qs"].append(sum(phi[i] * v[i][0] for i in range(len(phi))) * h["deltaZ"] / scale)
newton = NewtonIntegrator(damping=0.2, gravity=Vector3(*h["gravity"]))
runner = PyRunner(command="fluidModel()", iterPeriod=cfg["couplingSteps"], dead=True)
O.engines = [ForceResetter(), InsertionSortCollider([Bo1_Sphere_Aabb()], allowBiggerThanPeriod=True),
             InteractionLoop([Ig2_Sphere_Sphere_ScGeom()], [Ip2_ViscElMat_ViscElMat_ViscElPhys()],
                             [Law2_ScGeom_ViscElPhys_Basic()]), hydro, runner, newton]
O.dt = cfg["dt"]
hydro.initialization()
t, c = time.perf_counter(), time.process_time()
O.run(cfg["depositionSteps"], True)
depo, depo_cpu = time.perf_counter() - t, time.process_time() - c
# The coupled phase starts from Talus's state (deposited, or with the flow developed), as Talus does.
for i, ((x, y, z), v, w) in enumerate(zip(cfg["pos2"], cfg["vel2"], cfg["angVel2"])):
    O.bodies[i].state.pos = Vector3(x, y, z)
    O.bodies[i].state.vel = Vector3(*v)
    O.bodies[i].state.angVel = Vector3(*w)
newton.damping = 0.0
hydro.dead = False
runner.dead = False
hydro.ReynoldStresses = [1e-4] * h["nCell"]
hydro.turbulentFluctuation()      # sizes Yade's fluctuation arrays (u* = 3e-4 m/s, negligible)
hydro.averageProfile()
if cfg["vxFluid2"]:               # a developed flow: Talus's fluid profile, no start-up
    hydro.vxFluid = cfg["vxFluid2"]
else:
    hydro.fluidResolution(cfg["initialFluid"], cfg["dtFluid"])
t, c = time.perf_counter(), time.process_time()
O.run(cfg["coupledSteps"], True)
coupled, coupled_cpu = time.perf_counter() - t, time.process_time() - c
json.dump({"deposition": depo, "coupled": coupled, "depositionCpu": depo_cpu, "coupledCpu": coupled_cpu,
           "series": series}, open(sys.argv[-1], "w"))
'''

INITIAL_FLUID = 1.0   # s of fluid resolution before the coupled phase (not timed), as Yade's example
BLOCK = 0.5           # s: length of the blocks whose means give the standard error of the transport rate


def block_mean(t, q, start, block=BLOCK):
    """Mean of q over t > start and its standard error from block means (the series is
    correlated over a few couplings); also the number of blocks."""
    t, q = np.asarray(t), np.asarray(q)
    keep = t > start
    t, q = t[keep], q[keep]
    blocks = [q[(t >= a) & (t < a + block)] for a in np.arange(start, t.max(), block)]
    means = np.array([b.mean() for b in blocks if len(b)])
    error = means.std(ddof=1) / np.sqrt(len(means)) if len(means) > 1 else float("nan")
    return float(q.mean()), float(error), len(means)


def start_coupled(s, hydro, newton, vx_fluid=None):
    """The fluid switched on (st.start_fluid: the start-up resolution or, for a developed flow
    handed over from an earlier run, that run's fluid velocity profile) and the coupling attached."""
    st.start_fluid(hydro, newton, st.DT_FLUID, INITIAL_FLUID, vx_fluid)
    coupling = st.VansCoupling(hydro, st.PERIOD, st.DT_FLUID, densPart=st.RHO_P, diameterPart=st.D, changeLimit=0)
    coupling.attach()
    return coupling


def main():
    parser = results.case_arguments(__doc__)
    parser.add_argument("--develop", type=float, help="seconds of coupled transport Talus runs before the compared "
                                                      "phase (overrides the mode's)")
    parser.add_argument("--coupled", type=float, help="seconds of the compared coupled phase (overrides the mode's)")
    args = parser.parse_args()
    yade = shutil.which("yade")
    if yade is None:
        print("yade is not installed: nothing to compare with, no record written")
        return
    case = results.Case("vans.bench.coupled", quick=args.quick, folder=args.results)
    transport_case = results.Case("vans.transport-vs-yade", quick=args.quick, folder=args.results)
    deposition, develop, coupled = (0.05, 0.0, 0.1) if args.quick else (0.4, 8.0, 4.0)
    develop = develop if args.develop is None else args.develop
    coupled = coupled if args.coupled is None else args.coupled
    s, hydro, newton, mobile = st.build()
    n_depo, n_develop, n_coupled = round(deposition / s.dt), round(develop / s.dt), round(coupled / s.dt)
    mat = s.materials[0]
    cfg = {"box": [st.LENGTH, st.WIDTH, st.HEIGHT], "radius": st.D / 2,
           "material": {"kn": mat.kn, "cn": mat.cn, "ks": mat.ks, "cs": mat.cs, "density": st.RHO_P,
                        "frictionAngle": st.FRICTION},
           "pos": s.positions().tolist(), "vel": s.velocities().tolist(),
           "fixed": [not bool(d) for d in s._cpp.dynamic()], "mobile": [int(i) for i in mobile],
           "hydro": {"densFluid": st.RHO_F, "viscoDyn": st.NU * st.RHO_F, "zRef": st.GROUND,
                     "gravity": list(st.GRAVITY), "deltaZ": hydro.deltaZ, "nCell": st.N_CELL,
                     "vCell": hydro.vCell, "radiusPart": st.D / 2, "phiMax": st.PHI_MAX},
           "period": st.PERIOD, "dtFluid": st.DT_FLUID, "couplingSteps": round(st.PERIOD / s.dt), "dt": s.dt,
           "depositionSteps": n_depo, "coupledSteps": n_coupled, "initialFluid": INITIAL_FLUID,
           "densPart": st.RHO_P, "diameter": st.D}

    start, cpu = time.perf_counter(), time.process_time()
    s.run(n_depo)
    talus_depo, talus_depo_cpu = time.perf_counter() - start, time.process_time() - cpu
    vx_fluid = None
    if n_develop:
        # Develop the flow in Talus (not timed), then restart both programs from that state in
        # fresh scenes: positions, velocities, spins and the fluid profile, no contact history.
        start_coupled(s, hydro, newton)
        s.run(n_develop)
        vx_fluid = hydro.vxFluid
        state = s.positions().copy(), s.velocities().copy(), s.angular_velocities().copy()
        s, hydro, newton, mobile = st.build()
        for view, values in zip((s.positions(), s.velocities(), s.angular_velocities()), state):
            view[:] = values
    cfg["pos2"], cfg["vel2"] = s.positions().tolist(), s.velocities().tolist()
    cfg["angVel2"] = s.angular_velocities().tolist()
    cfg["vxFluid2"] = [] if vx_fluid is None else vx_fluid.tolist()
    coupling = start_coupled(s, hydro, newton, vx_fluid)
    start, cpu = time.perf_counter(), time.process_time()
    s.run(n_coupled)
    talus_coupled, talus_coupled_cpu = time.perf_counter() - start, time.process_time() - cpu

    with tempfile.TemporaryDirectory() as tmp:
        script, cfg_path, out = Path(tmp, "bench.py"), Path(tmp, "cfg.json"), Path(tmp, "out.json")
        script.write_text(YADE_SCRIPT)
        cfg_path.write_text(json.dumps(cfg))
        done = subprocess.run([yade, "-n", "-j1", "-x", str(script), str(cfg_path), str(out)], cwd=tmp,
                              capture_output=True, text=True, timeout=4 * 3600)
        if done.returncode != 0 or not out.exists():
            raise RuntimeError("yade failed:\n" + done.stdout[-3000:] + done.stderr[-3000:])
        theirs = json.loads(out.read_text())
    # Wall times of the two programs, run one after the other, carry whatever load the shared
    # machine had at each moment; the CPU times of these single-threaded runs do not (the record's
    # value is the wall-time ratio, the CPU-time ratio is an extra).
    ratio = theirs["coupled"] / talus_coupled
    cpu_ratio = theirs["coupledCpu"] / talus_coupled_cpu
    print(f"coupled {coupled:g} s ({n_coupled} steps, after {develop:g} s of development in Talus): Talus "
          f"{talus_coupled:.2f} s wall / {talus_coupled_cpu:.2f} s CPU, Yade {theirs['coupled']:.2f} / "
          f"{theirs['coupledCpu']:.2f} s, ratio {ratio:.2f} wall, {cpu_ratio:.2f} CPU; deposition {deposition:g} s: "
          f"Talus {talus_depo:.2f} s, Yade {theirs['deposition']:.2f} s, ratio {theirs['deposition'] / talus_depo:.2f}")
    case.record("Yade time / Talus time, coupled sediment transport (same steps, one thread)", ratio,
                "Yade 2023.02a HydroForceEngine example, same scene and run length", 3.0, comparison=">=",
                talus_s=talus_coupled, yade_s=theirs["coupled"], cpu_ratio=cpu_ratio, talus_cpu_s=talus_coupled_cpu,
                yade_cpu_s=theirs["coupledCpu"], steps=n_coupled, developed_s=develop,
                deposition_ratio=theirs["deposition"] / talus_depo, talus_deposition_s=talus_depo,
                yade_deposition_s=theirs["deposition"],
                deposition_cpu_ratio=theirs["depositionCpu"] / talus_depo_cpu)
    # Transport rate averaged over the compared phase (its second half when it starts from the
    # deposited bed, whose flow is still developing), in both programs.
    first = 0.0 if develop else coupled / 2
    if coupled - first < 4 * BLOCK:
        print(f"transport-rate comparison needs at least {4 * BLOCK:g} s of averaging: not recorded")
        return
    ours = block_mean(np.array(coupling.series["time"]) - (s.time - coupled), coupling.series["transportRate"], first)
    yade_t0 = theirs["series"]["time"][0] - st.PERIOD if theirs["series"]["time"] else 0.0
    yade = block_mean(np.array(theirs["series"]["time"]) - yade_t0, theirs["series"]["qs"], first)
    sigmas = abs(ours[0] - yade[0]) / np.hypot(ours[1], yade[1])
    print(f"transport rate ({first:g}-{coupled:g} s, {ours[2]} blocks of {BLOCK:g} s): Talus {ours[0]:.4f} +- "
          f"{ours[1]:.4f}, Yade {yade[0]:.4f} +- {yade[1]:.4f}, {sigmas:.1f} standard errors apart")
    transport_case.record(
        "difference of the time-averaged transport rates in standard errors (Talus vs Yade)", float(sigmas),
        "Yade 2023.02a, same scene and state, coupled example", 3.0,
        talus_mean=ours[0], talus_error=ours[1], yade_mean=yade[0], yade_error=yade[1], blocks=ours[2],
        block_s=BLOCK, averaged_from_s=first, coupled_s=coupled, developed_s=develop)


if __name__ == "__main__":
    main()
