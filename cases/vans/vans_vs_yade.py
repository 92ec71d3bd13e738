"""VANS case: the fluid resolution side by side with Yade's HydroForceEngine, same input.

Run:      build/bin/talus run cases/vans/vans_vs_yade.py [--quick] [--results DIR]
Set-up:   four sets of synthetic solid-phase profiles and options, each given to Yade 2023.02a's
          HydroForceEngine.fluidResolution (``yade -n -x`` on a script this case writes to a
          temporary folder) and to talus.flow.VansFluid:
          - bedload: Yade's sediment-transport example (6 mm grains, 10 layers of bed, water
            17.5 d above, 0.05 rad slope, ndimz = 900), a bed at phiMax = 0.61 below 8 d with a
            tanh transition to clear water, particle velocity and drag rising across the bed
            surface, Li-Sawamoto mixing length, free surface; 1e-2 s with steps of 1e-5 s (one
            coupling period of the example);
          - sublayer: kappa z mixing length with viscous sub-layer, imposed top velocity, Einstein
            viscosity, a pressure gradient on top of gravity;
          - wallfriction: kappa z sqrt(1 - z/h), power-law viscosity, side-wall friction;
          - laminar: no turbulence, Einstein viscosity, drag from a loose suspension.
Checked:  max over nodes of |u_Talus - u_Yade| / max |u_Yade|, worst set: <= 1e-8 (record
          vans.yade-parity; the Reynolds stresses are compared the same way and reported).
          Speed: the bedload set (ndimz = 900, 1000 steps) timed inside each program, median of
          5 calls (quick: 3): record vans.bench.fluid-resolution, ratio >= 1 (the target).
          If yade is not installed the case says so and records nothing (exit status 0).
Produces: records vans.yade-parity and vans.bench.fluid-resolution; chart
          vans.yade-parity.profiles.png (the bedload profiles of both programs and their
          difference).
"""
import json
import shutil
import subprocess
import tempfile
import time
from pathlib import Path

import numpy as np

from talus import results
from talus.flow import VansFluid, slope_gravity

# The Yade side: reads the sets from JSON, runs HydroForceEngine.fluidResolution on each, writes
# the profiles and the timings back as JSON. phiPart gets one trailing zero: Yade's Li-Sawamoto
# loop reads phiPart[nCell], one past the nCell values it otherwise uses.
YADE_SCRIPT = r'''
import json, sys, time
sets = json.load(open(sys.argv[-2]))
out = {}
for name, s in sets.items():
    p = s["parameters"]
    e = HydroForceEngine(densFluid=p["densFluid"], viscoDyn=p["viscoDyn"], deltaZ=p["deltaZ"],
                         nCell=p["nCell"], gravity=Vector3(*p["gravity"]), dpdx=p["dpdx"],
                         phiMax=p["phiMax"], iturbu=p["iturbu"], ilm=p["ilm"], iusl=p["iusl"],
                         uTop=p["uTop"], viscousSubLayer=p["viscousSubLayer"], irheolf=p["irheolf"],
                         kappa=p["kappa"], fluidWallFriction=p["fluidWallFriction"],
                         channelWidth=p["channelWidth"], fluidFrictionCoef=p["fluidFrictionCoef"],
                         radiusPart=p["radiusPart"])
    e.initialization()
    times = []
    for _ in range(s["repeat"]):
        e.phiPart = s["phiPart"] + [0.0]
        e.vxPart = s["vxPart"]
        e.vPart = [Vector3(v, 0, 0) for v in s["vxPart"]]
        e.averageDrag = s["averageDrag"]
        e.vxFluid = s["vxFluid"]
        start = time.perf_counter()
        e.fluidResolution(s["tfin"], s["dt"])
        times.append(time.perf_counter() - start)
    out[name] = {"vxFluid": list(e.vxFluid), "ReynoldStresses": list(e.ReynoldStresses),
                 "taufsi": list(e.taufsi), "times": times}
json.dump(out, open(sys.argv[-1], "w"))
'''

YADE_DEFAULTS = dict(densFluid=1000.0, viscoDyn=1e-3, gravity=(0.0, 0.0, -9.81), dpdx=0.0,
                     phiMax=0.64, iturbu=1, ilm=2, iusl=1, uTop=1.0, viscousSubLayer=0, irheolf=0,
                     kappa=0.41, fluidWallFriction=False, channelWidth=1.0, fluidFrictionCoef=1.0,
                     radiusPart=0.0)


def smooth_step(z, z0, width):
    """0 well below z0, 1 well above, a tanh transition of the given width."""
    return 0.5 * (1.0 + np.tanh((z - z0) / width))


def synthetic_set(n_cell, height, *, bed, d, phi_max, vx_max, drag_max, u_max, tfin, dt, repeat,
                  **options):
    """Profiles of a bed of solid fraction phi_max below `bed` with a tanh transition of width d/2
    to clear water, particle velocity and drag per particle rising across it, and a smooth
    initial fluid profile."""
    dz = height / (n_cell - 1)
    zc = (np.arange(n_cell) + 0.5) * dz            # cell centres
    above = smooth_step(zc, bed, 0.5 * d)
    phi = phi_max * (1.0 - above)
    phi[zc < bed - 2 * d] = phi_max                # exactly packed at the bottom
    vx = vx_max * smooth_step(zc, bed, d)
    drag = drag_max * smooth_step(zc, bed - d, d)
    zn = np.concatenate([[0.0], (np.arange(n_cell - 1) + 0.5) * dz, [height]])
    u0 = u_max * smooth_step(zn, bed, 2 * d) * np.sqrt(np.clip(zn / height, 0, 1))
    parameters = {**YADE_DEFAULTS, **options, "nCell": n_cell, "deltaZ": dz, "phiMax": phi_max,
                  "radiusPart": d / 2}
    return {"parameters": parameters, "phiPart": phi.tolist(), "vxPart": vx.tolist(),
            "averageDrag": drag.tolist(), "vxFluid": u0.tolist(), "tfin": tfin, "dt": dt,
            "repeat": repeat}


def parity_sets(repeat: int) -> dict:
    d = 6e-3
    return {
        "bedload": synthetic_set(900, 27.5 * d, bed=8 * d, d=d, phi_max=0.61, vx_max=0.4,
                                 drag_max=2e-4, u_max=1.2, tfin=1e-2, dt=1e-5, repeat=repeat,
                                 gravity=slope_gravity(0.05), ilm=2, iusl=1),
        "sublayer": synthetic_set(300, 0.05, bed=0.01, d=2e-3, phi_max=0.6, vx_max=0.05,
                                  drag_max=1e-5, u_max=0.5, tfin=0.5, dt=1e-3, repeat=1,
                                  gravity=slope_gravity(0.01), ilm=0, iusl=0, uTop=0.6,
                                  viscousSubLayer=1, irheolf=1, dpdx=-2.0),
        "wallfriction": synthetic_set(400, 0.1, bed=0.02, d=4e-3, phi_max=0.6, vx_max=0.1,
                                      drag_max=5e-5, u_max=0.8, tfin=0.2, dt=1e-3, repeat=1,
                                      gravity=slope_gravity(0.02), ilm=1, iusl=1, irheolf=2,
                                      fluidWallFriction=True, channelWidth=0.2, fluidFrictionCoef=1.5),
        "laminar": synthetic_set(200, 0.02, bed=0.004, d=1e-3, phi_max=0.55, vx_max=0.002,
                                 drag_max=1e-8, u_max=0.05, tfin=2.0, dt=1e-2, repeat=1,
                                 gravity=slope_gravity(0.001), iturbu=0, iusl=1, irheolf=1,
                                 viscoDyn=1e-2),
    }


def run_talus(s: dict) -> dict:
    p = s["parameters"]
    fluid = VansFluid(**{k: v for k, v in p.items()})
    times = []
    for _ in range(s["repeat"]):
        fluid.phiPart, fluid.vxPart = s["phiPart"], s["vxPart"]
        fluid.averageDrag, fluid.vxFluid = s["averageDrag"], s["vxFluid"]
        start = time.perf_counter()
        fluid.fluidResolution(s["tfin"], s["dt"])
        times.append(time.perf_counter() - start)
    return {"vxFluid": fluid.vxFluid, "ReynoldStresses": fluid.ReynoldStresses, "taufsi": fluid.taufsi,
            "times": times, "z": fluid.zFluid, "clipped": fluid.clippedDragCells}


def run_yade(yade: str, sets: dict) -> dict:
    with tempfile.TemporaryDirectory(prefix="talus-vans-yade-") as tmp:
        tmp = Path(tmp)
        (tmp / "sets.json").write_text(json.dumps(sets))
        (tmp / "vans_yade.py").write_text(YADE_SCRIPT)
        done = subprocess.run([yade, "-n", "-j1", "-x", str(tmp / "vans_yade.py"), str(tmp / "sets.json"),
                               str(tmp / "out.json")], capture_output=True, text=True, timeout=600,
                              cwd=tmp)
        if done.returncode != 0 or not (tmp / "out.json").is_file():
            raise SystemExit(f"yade failed (status {done.returncode}):\n{done.stdout[-3000:]}\n{done.stderr[-3000:]}")
        return json.loads((tmp / "out.json").read_text())


def relative_difference(ours, theirs) -> float:
    ours, theirs = np.asarray(ours), np.asarray(theirs)
    scale = np.max(np.abs(theirs))
    return float(np.max(np.abs(ours - theirs)) / scale) if scale > 0 else float(np.max(np.abs(ours)))


def main():
    args = results.case_arguments(__doc__).parse_args()
    yade = shutil.which("yade")
    if yade is None:
        print("yade is not installed (apt-get install yade): no comparison recorded")
        return
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    repeat = 3 if args.quick else 5
    sets = parity_sets(repeat)
    theirs = run_yade(yade, sets)
    parity = results.Case("vans.yade-parity", quick=args.quick, folder=args.results)
    ours = {name: run_talus(s) for name, s in sets.items()}

    diff_u = {name: relative_difference(ours[name]["vxFluid"], theirs[name]["vxFluid"]) for name in sets}
    diff_rs = {name: relative_difference(ours[name]["ReynoldStresses"], theirs[name]["ReynoldStresses"])
               for name in sets}
    diff_tau = {name: relative_difference(ours[name]["taufsi"], theirs[name]["taufsi"]) for name in sets}
    for name in sets:
        print(f"{name:13s} vxFluid {diff_u[name]:.2e}  ReynoldStresses {diff_rs[name]:.2e}  "
              f"taufsi {diff_tau[name]:.2e}  (max |u| {np.max(np.abs(theirs[name]['vxFluid'])):.3g} m/s)")
    worst = max(diff_u.values())
    parity.record("max relative difference of the fluid velocity profile, worst of four option sets",
                  worst, "yade 2023.02a HydroForceEngine.fluidResolution on the same profiles", 1e-8,
                  per_set=diff_u, reynolds_stress_per_set=diff_rs, taufsi_per_set=diff_tau)

    # Speed: the bedload set, ndimz = 900, 1000 steps, median of the calls in each program.
    t_ours = float(np.median(ours["bedload"]["times"]))
    t_theirs = float(np.median(theirs["bedload"]["times"]))
    ratio = t_theirs / t_ours
    bench = results.Case("vans.bench.fluid-resolution", quick=args.quick, folder=args.results)
    bench.record("fluidResolution(1e-2, 1e-5) at ndimz = 900: Yade's time over Talus's", ratio,
                 "yade 2023.02a HydroForceEngine.fluidResolution, same input, same machine", 1.0,
                 comparison=">=", peer="yade 2023.02a, 1 thread", ours=t_ours, theirs=t_theirs, unit="s",
                 ratio=ratio)
    print(f"fluidResolution at ndimz = 900, 1000 steps: Talus {t_ours * 1e3:.2f} ms, "
          f"Yade {t_theirs * 1e3:.2f} ms: {ratio:.1f}x faster")

    # Chart: the bedload profiles and their difference.
    z = ours["bedload"]["z"]
    u_t, u_y = ours["bedload"]["vxFluid"], np.asarray(theirs["bedload"]["vxFluid"])
    phi = np.asarray(sets["bedload"]["phiPart"])
    fig, (ax1, ax2) = plt.subplots(1, 2, figsize=(8, 4.5), sharey=True)
    zc = (np.arange(len(phi)) + 0.5) * sets["bedload"]["parameters"]["deltaZ"]
    ax1.plot(u_y, z, "k-", lw=3, alpha=0.4, label="Yade 2023.02a")
    ax1.plot(u_t, z, "r--", lw=1.2, label="Talus")
    ax1.plot(phi, zc, "b:", label="solid fraction (input)")
    ax1.set_xlabel("$u_x^f$ (m/s), $\\phi$")
    ax1.set_ylabel("z (m)")
    ax1.legend(fontsize=8)
    ax1.set_title("bedload set, ndimz = 900")
    ax2.plot(np.abs(u_t - u_y) / np.max(np.abs(u_y)) + 1e-20, z, "m-")
    ax2.set_xscale("log")
    ax2.set_xlabel("|u_Talus - u_Yade| / max|u_Yade|")
    ax2.set_title(f"bedload: {diff_u['bedload']:.1e} (worst of 4 sets: {worst:.1e})", fontsize=10)
    parity.save_chart(fig, "profiles")


if __name__ == "__main__":
    main()
