"""VANS case: Frey (2014) experiment 6 side by side with Yade from the same developed state.

Run:      OMP_NUM_THREADS=1 build/bin/talus run cases/vans_frey_vs_yade.py [--quick] [--results DIR]
          [--develop SECONDS] [--compare SECONDS] [--length D]
Why:      cases/vans_frey_experiments.py finds experiment 6's transport rate 1.5-1.7x the data while
          its profiles agree (60 d channel). This case tells whether that is the model and set-up
          (Maurin et al. 2015, Yade's validMaurin2015.py) or Talus: Yade 2023.02a's
          HydroForceEngine continues the same state with the same loop.
Set-up:   cases/vans_frey_experiments.py's channel for experiment 6 (build, 0.3 s deposition, the
          1 s start-up fluid resolution, then two-way coupled transport with Yade's eddy-turnover
          fluctuations) develops in Talus for --develop seconds (quick 2 s, full 4 s; 60 d long).
          Its state (every sphere's position, velocity and spin; fluid velocity and Reynolds-stress
          profiles) is handed to the scenario cases/yade/frey_bedload.py, which runs unchanged in
          Talus and in Yade (talus.dem.twin) for --compare seconds (quick 3 s, full 8 s): DEM for one
          coupling period, then averageProfile + fluidResolution, fluctuations redrawn every eddy
          turnover time; the profiles are averaged after the first second.
Checked:  the transport rate integral phi vx dz over the data's elevations (as the Frey case) of
          both programs, each with a standard error from 0.5 s block means of q_s*: their
          difference in combined standard errors (record vans.frey-vs-yade.exp6, <= 3: within
          the scatter); each program's error against the data, its profiles' RMS errors and the
          q_s* means are extras. If yade is not installed the case says so and records nothing.
Produces: record vans.frey-vs-yade.exp6; chart vans.frey-vs-yade.png (both programs' profiles
          and the data; q_s* against time).
"""
import math
import time
from pathlib import Path

import numpy as np

from talus import results
from talus.dem import twin

import vans_frey_experiments as frey
from vans_bench_coupled import block_mean

EXPERIMENT = 6
SCENARIO = Path(__file__).resolve().parent / "yade" / "frey_bedload.py"
AVERAGE_AFTER = 1.0   # s of the compared run left out of the profile averages


def developed_state(length_d: int, develop: float, seed: int) -> dict:
    """Talus develops the flow; the scenario's parameters (the state and every setting)."""
    hs_d, depth = frey.EXPERIMENTS[EXPERIMENT]
    s, hydro, newton, mobile = frey.build(length_d, hs_d, depth, seed)
    s.run(round(0.3 / s.dt))
    frey.start_transport(s, hydro, newton)
    s.run(round(develop / s.dt))
    spheres = [i for i in range(len(s.bodies)) if s.radii()[i] > 0]
    walls = [i for i in range(len(s.bodies)) if not s.radii()[i] > 0]
    mat = s.materials[0]
    dynamic = s._cpp.dynamic()
    cell = np.array([length_d * frey.D, frey.CELL_WIDTH, 5 * depth])
    return {"cell": cell.tolist(),
            "material": {"kn": mat.kn, "cn": mat.cn, "ks": mat.ks, "cs": mat.cs, "density": frey.RHO_P,
                         "frictionAngle": frey.FRICTION},
            "walls": [float(s.positions()[i][1]) for i in walls],
            "pos": np.mod(s.positions()[spheres], cell).tolist(), "vel": s.velocities()[spheres].tolist(),
            "angVel": s.angular_velocities()[spheres].tolist(), "radius": s.radii()[spheres].tolist(),
            "fixed": [not bool(dynamic[i]) for i in spheres],
            "hydro": {"densFluid": frey.RHO_F, "viscoDyn": frey.NU * frey.RHO_F, "zRef": 5 * depth / 2,
                      "gravity": list(frey.GRAVITY), "deltaZ": hydro.deltaZ, "expoRZ": 3.1, "nCell": frey.N_CELL,
                      "vCell": hydro.vCell, "radiusPart": frey.D / 2, "phiMax": frey.PHI_MAX,
                      "channelWidth": frey.W, "bedElevation": float(hydro.bedElevation)},
            "vxFluid": np.asarray(hydro.vxFluid).tolist(), "ReynoldStresses": np.asarray(hydro.ReynoldStresses).tolist(),
            "period": frey.PERIOD, "dtFluid": frey.DT_FLUID, "dt": s.dt, "diameter": frey.D}


def main():
    parser = results.case_arguments(__doc__)
    parser.add_argument("--develop", type=float, help="seconds of transport Talus develops first")
    parser.add_argument("--compare", type=float, help="seconds both programs run from the developed state")
    parser.add_argument("--length", type=int, default=60, help="channel length in grain diameters")
    parser.add_argument("--seed", type=int, default=1)
    args = parser.parse_args()
    if not twin.yade_available():
        print("yade is not installed: nothing to compare with, no record written")
        return
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    develop, compare = (2.0, 3.0) if args.quick else (4.0, 8.0)
    develop = args.develop or develop
    compare = args.compare or compare
    case = results.Case("vans.frey-vs-yade", quick=args.quick, folder=args.results)
    data = frey.load_data(EXPERIMENT)
    if data is None:
        print(f"no Frey (2014) data under {frey.DATA}: nothing to compare")
        return
    start = time.perf_counter()
    params = {**developed_state(args.length, develop, args.seed), "duration": compare, "average": AVERAGE_AFTER}
    print(f"developed {develop:g} s in Talus ({time.perf_counter() - start:.0f} s wall)")
    z = (np.arange(frey.N_CELL) + 0.5) * params["hydro"]["deltaZ"] / frey.D
    runs = {}
    for program in ("talus", "yade"):
        t0 = time.perf_counter()
        out = twin.run(SCENARIO, params, program, timeout=6 * 3600)
        sim = {"z": z, "phi": np.array(out["phi"]), "phivx": np.array(out["phivx"])}
        c = frey.compare(sim, data)
        mean, error, blocks = block_mean(out["time"], out["qs"], AVERAGE_AFTER)
        runs[program] = {**c, "sim": sim, "qs_mean": mean, "qs_error": error, "blocks": blocks,
                         "series": (np.array(out["time"]), np.array(out["qs"])), "wall_s": time.perf_counter() - t0}
        print(f"{program}: q {c['q_sim']:.3e} m^2/s ({c['q_sim'] / c['q_exp']:.2f}x data), qs* {mean:.4f} +- {error:.4f} "
              f"({blocks} blocks), phi {c['phi_err']:.3f}, vx {c['vx_err']:.3f}; {runs[program]['wall_s']:.0f} s wall")
    ours, theirs = runs["talus"], runs["yade"]
    # The standard error of q (the integral over the data's range) taken as that of q_s* in relative terms.
    sigma = math.hypot(ours["q_sim"] * ours["qs_error"] / ours["qs_mean"],
                       theirs["q_sim"] * theirs["qs_error"] / theirs["qs_mean"])
    gap = abs(ours["q_sim"] - theirs["q_sim"]) / sigma
    case.record("difference of the transport rates (integral of phi vx dz over the data's range) in combined "
                f"standard errors, Talus vs Yade from the same developed state, experiment {EXPERIMENT}",
                gap, "Yade 2023.02a HydroForceEngine, same state and coupling loop", 3.0, suffix=f"exp{EXPERIMENT}",
                develop_s=develop, compare_s=compare, length_d=args.length,
                **{f"{p}_{k}": runs[p][k] for p in runs for k in ("q_sim", "qs_mean", "qs_error", "phi_err", "vx_err")},
                q_exp=ours["q_exp"], talus_over_data=ours["q_sim"] / ours["q_exp"],
                yade_over_data=theirs["q_sim"] / theirs["q_exp"])

    fig, (a1, a2, a3) = plt.subplots(1, 3, figsize=(11, 4))
    a1.plot(data["phi"], data["z"], "ko", ms=3, label="Frey (2014)")
    a2.plot(data["vx"], data["z"], "ko", ms=3)
    for program, style in (("talus", "b-"), ("yade", "r--")):
        sim = runs[program]["sim"]
        keep = sim["z"] < data["z"].max() + 1.5
        a1.plot(sim["phi"][keep], sim["z"][keep], style, label=program)
        occupied = keep & (sim["phi"] > 0.01)
        a2.plot(sim["phivx"][occupied] / sim["phi"][occupied], sim["z"][occupied], style)
        t, q = runs[program]["series"]
        a3.plot(t, q, style, lw=0.8, label=f"{program}: {runs[program]['q_sim'] / runs[program]['q_exp']:.2f}x data")
    a1.set_xlabel("solid fraction")
    a1.set_ylabel("z / d above the ground")
    a1.legend(fontsize=8)
    a2.set_xlabel("particle velocity (m/s)")
    a3.set_xlabel("time after the hand-over (s)")
    a3.set_ylabel("q_s*")
    a3.legend(fontsize=8)
    fig.suptitle(f"Frey exp {EXPERIMENT}, {args.length} d: Talus and Yade from the same state after {develop:g} s "
                 f"(difference {gap:.1f} standard errors)")
    fig.tight_layout()
    case.save_chart(fig)


if __name__ == "__main__":
    main()
