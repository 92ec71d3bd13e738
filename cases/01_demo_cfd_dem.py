"""Case 01: the main demo -- three beads (plastic, glass, steel) settling side by side in a tank of
viscous liquid, CFD-DEM under mpirun: the DEM process and 2 OpenFOAM ranks (volume-averaged
coupling, talusVolumeAveragedFoam). The last step of ./setup.sh.

Run:      build/bin/talus run cases/01_demo_cfd_dem.py [--quick] [--results DIR] [--procs N]
          The script starts itself again under `mpirun -n 1` (the DEM rank), which spawns the N
          fluid ranks (default 2); as root it allows Open MPI to run as root. About a minute on
          a 2-core machine (quick: a third of it).
Set-up:   beads d = 2 mm of density 1500, 2500 and 7800 kg/m3, 80 mm apart, released from rest
          in a closed tank 290 x 130 x 200 mm (cells 10 mm: d/dx = 0.2; written by
          talus.coupling.case_builder.cfd_case) of liquid rho = 1000 kg/m3, nu = 3e-5 m2/s (30
          times water's); gravity -9.81 m/s2; fluid step 1 ms, DEM step 0.8 of the P-wave step
          (about 1000 per fluid step); 0.4 s (quick: 0.2 s), Re_p up to 16.
Checked:  each bead's velocity at the end against its Schiller-Naumann terminal velocity
          (3 pi mu d w (1 + 0.15 Re^0.687) = (rho_p - rho) V g) within 2 %. Recorded: the
          largest deviation over the whole fall from the integrated equation of motion (added
          mass 0.5), and the wall time (demo.cfd_dem.wall_time: about a minute asked).
Produces: records demo.cfd_dem and demo.cfd_dem.wall_time; chart demo.cfd_dem.png (velocities
          against time with the equation of motion; fluid speed in the beads' plane at the end);
          for ParaView, RESULTS/demo_cfd_dem/: the fluid case (open case.foam: U, p, alphaf every
          50 fluid steps) and the beads (open VTK/beads.pvd, same times).
"""
import math
import os
import re
import shutil
import subprocess
import sys
import time
from pathlib import Path

import numpy as np

from talus import results

RHO, NU, D, G, CM = 1000.0, 3e-5, 2e-3, 9.81, 0.5
BEADS = {"plastic": 1500.0, "glass": 2500.0, "steel": 7800.0}
SPACING, DX, DT = 0.08, 0.01, 1e-3
TANK = ((-0.145, -0.065, 0.0), (0.145, 0.065, 0.2))
START_Z = 0.175
WRITE_EVERY = 50
CHECKED = 0.02


def drag(v: float) -> float:
    return 3 * math.pi * RHO * NU * D * v * (1 + 0.15 * (abs(v) * D / NU) ** 0.687)


def terminal_velocity(rho_p: float) -> float:
    weight = (rho_p - RHO) * math.pi * D ** 3 / 6 * G
    lo, hi = 0.0, 10.0
    for _ in range(200):
        mid = 0.5 * (lo + hi)
        lo, hi = (mid, hi) if drag(mid) < weight else (lo, mid)
    return 0.5 * (lo + hi)


def equation_of_motion(rho_p: float, t: np.ndarray, dt: float = 1e-5) -> np.ndarray:
    """(m + C_m rho V) dv/dt = (m - rho V) g - drag(v) from rest (RK4), at the times t."""
    volume = math.pi * D ** 3 / 6
    accel = lambda v: ((rho_p - RHO) * volume * G - drag(v)) / ((rho_p + CM * RHO) * volume)
    ts, vs, v = [0.0], [0.0], 0.0
    for n in range(1, int(round(t[-1] / dt)) + 1):
        k1 = accel(v); k2 = accel(v + dt / 2 * k1); k3 = accel(v + dt / 2 * k2); k4 = accel(v + dt * k3)
        v += dt / 6 * (k1 + 2 * k2 + 2 * k3 + k4)
        ts.append(n * dt); vs.append(v)
    return np.interp(t, ts, vs)


def under_mpirun() -> bool:
    return "OMPI_COMM_WORLD_SIZE" in os.environ


def relaunch_under_mpirun() -> int:
    """This script again as the one DEM rank of `mpirun -n 1` (it spawns the fluid ranks)."""
    import talus
    env = dict(os.environ, WM_PROJECT_DIR=os.environ.get("WM_PROJECT_DIR", "/usr/share/openfoam"),
               PYTHONPATH=os.pathsep.join(filter(None, [str(Path(talus.__file__).parents[1]),
                                                        os.environ.get("PYTHONPATH")])),
               # one host: keep Open MPI's sockets on the loopback (containers may have no other)
               OMPI_MCA_btl_tcp_if_include="lo", OMPI_MCA_oob_tcp_if_include="lo")
    command = ["mpirun", "--oversubscribe", "-n", "1"]
    if os.geteuid() == 0:   # Open MPI refuses root unless told, and says so at length
        command.append("--allow-run-as-root")
        env.update(OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1")
    command += [sys.executable, "-m", "talus", "run", str(Path(__file__).resolve()), *sys.argv[1:]]
    print("$ " + " ".join(command), flush=True)
    return subprocess.run(command, env=env).returncode


def build_scene():
    from talus.dem import ForceResetter, FrictMat, NewtonIntegrator, PWaveTimeStep, Scene, sphere
    s = Scene()
    for k, (name, rho_p) in enumerate(BEADS.items()):
        s.materials.append(FrictMat(density=rho_p, label=name))
        s.bodies.append(sphere(((k - 1) * SPACING, 0.0, START_Z), D / 2, material=name))
    s.engines = [ForceResetter(), NewtonIntegrator(gravity=(0, 0, -G), damping=0.0)]
    s.dt = 0.8 * PWaveTimeStep(s)   # the contacts' stable step (FoamCoupling lowers it to divide DT)
    return s


def run_coupled(folder: Path, procs: int, fluid_steps: int):
    """The coupled run: velocities of the beads at every fluid step, with a progress line; the
    beads written for ParaView when the fluid writes its fields."""
    from talus.coupling.case_builder import cfd_case
    from talus.dem.files.export import PvdCollection, write_spheres
    from talus.dem.analysis.progress import Progress
    fluid = cfd_case(folder, solver="volumeaveraged", box=TANK, cell_size=DX, rho=RHO, nu=NU, gravity=(0, 0, -G),
                     coupling_interval=DT, procs=procs, write_every=WRITE_EVERY)
    s = build_scene()
    coupling = fluid.coupling(s).start()
    (folder / "VTK").mkdir()
    beads = PvdCollection(str(folder / "VTK" / "beads.pvd"))
    print(f"{len(BEADS)} beads, {fluid.cells} fluid cells on {procs} fluid ranks, {fluid_steps} fluid steps x "
          f"{coupling.substeps} DEM steps", flush=True)
    t, v = [0.0], [np.zeros(len(BEADS))]
    progress = Progress(target=fluid_steps * coupling.substeps)
    start = time.perf_counter()
    try:
        for step in range(1, fluid_steps + 1):
            s.run(coupling.substeps, True)
            t.append(s.time)
            v.append(-s.velocities()[:, 2].copy())
            progress.update(s.iter, s.time)
            if step % WRITE_EVERY == 0 or step == fluid_steps:
                path = folder / "VTK" / f"beads.{step}.vtu"
                write_spheres(s, str(path))
                beads.add(s.time, str(path))
    finally:
        coupling.stop()
    progress.finish(s.iter, s.time, fluid_steps * coupling.substeps)
    elapsed = time.perf_counter() - start
    beads.write()
    if procs > 1:   # one field set for ParaView's case.foam
        from talus.coupling.cases import foam_environment
        subprocess.run(["reconstructPar", "-case", str(folder)], check=True, capture_output=True,
                       env=foam_environment())
        for rank in folder.glob("processor*"):
            shutil.rmtree(rank)
    return np.array(t), np.array(v), s.positions().copy(), coupling.maxReynolds, elapsed


def last_fluid_speed(folder: Path) -> np.ndarray:
    """|U| of the last written time, as (nz, ny, nx) (blockMesh's x-fastest order)."""
    last = max((p for p in folder.iterdir() if re.fullmatch(r"[0-9.e-]+", p.name) and p.name != "0"),
               key=lambda p: float(p.name))
    text = (last / "U").read_text()
    body = re.search(r"internalField\s+nonuniform\s+List<vector>\s+\d+\s*\((.*?)\)\s*;", text, re.S).group(1)
    u = np.array(re.findall(r"\(([^()]*)\)", body), dtype=str)
    u = np.array([row.split() for row in u], dtype=float)
    counts = [round((hi - lo) / DX) for lo, hi in zip(*TANK)]
    return np.linalg.norm(u, axis=1).reshape(counts[2], counts[1], counts[0])


def chart(t, v, reference, positions, speed):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, (a, b) = plt.subplots(1, 2, figsize=(11, 4.2), gridspec_kw={"width_ratios": [1, 1.2]})
    for k, (name, rho_p) in enumerate(BEADS.items()):
        line, = a.plot(t, 100 * v[:, k], lw=1.6, label=f"{name} ({rho_p:g} kg/m3)")
        a.plot(t, 100 * reference[:, k], "k--", lw=0.8)
        a.axhline(100 * terminal_velocity(rho_p), color=line.get_color(), lw=0.5, ls=":")
    a.plot([], [], "k--", lw=0.8, label="equation of motion (Schiller-Naumann)")
    a.set_xlabel("t [s]")
    a.set_ylabel("settling velocity [cm/s]")
    a.set_title("CFD-DEM: beads settling in a viscous liquid")
    a.legend(fontsize=7)
    (x0, _, z0), (x1, _, z1) = TANK
    middle = speed.shape[1] // 2
    image = b.imshow(100 * speed[:, middle, :], origin="lower", extent=(100 * x0, 100 * x1, 100 * z0, 100 * z1),
                     cmap="viridis")
    b.plot(100 * positions[:, 0], 100 * positions[:, 2], "wo", ms=4, mec="k")
    b.set_xlabel("x [cm]")
    b.set_ylabel("z [cm]")
    b.set_title(f"fluid speed at t = {t[-1]:.2g} s (plane of the beads)")
    fig.colorbar(image, ax=b, label="|U| [cm/s]")
    fig.tight_layout()
    return fig


def main():
    parser = results.case_arguments(__doc__)
    parser.add_argument("--procs", type=int, default=2, help="fluid ranks (default 2)")
    args = parser.parse_args()
    if not under_mpirun():
        return relaunch_under_mpirun()
    case = results.Case("demo.cfd_dem", quick=args.quick, folder=args.results)
    folder = case.folder / "demo_cfd_dem"
    shutil.rmtree(folder, ignore_errors=True)
    fluid_steps = 200 if args.quick else 400
    t, v, positions, re_max, elapsed = run_coupled(folder, args.procs, fluid_steps)
    reference = np.stack([equation_of_motion(rho_p, t) for rho_p in BEADS.values()], axis=1)
    rows, worst = [], 0.0
    for k, (name, rho_p) in enumerate(BEADS.items()):
        w = terminal_velocity(rho_p)
        error = (v[-1, k] - w) / w
        transient = float(np.max(np.abs(v[:, k] - reference[:, k]))) / w
        rows.append(dict(bead=name, density=rho_p, v_end=float(v[-1, k]), w_terminal=w, Re_p=w * D / NU,
                         rel_error_end=error, max_transient_error=transient))
        worst = max(worst, abs(error))
        print(f"{name:8s} {rho_p:6.0f} kg/m3: v({t[-1]:.2f} s) {100 * v[-1, k]:.3f} cm/s, Schiller-Naumann terminal "
              f"{100 * w:.3f} cm/s (Re_p {w * D / NU:.1f}): {error:+.2%}; largest deviation from the equation of "
              f"motion {transient:.2%} of w")
    record = case.record("largest relative error of the beads' final velocities", worst,
                         "Schiller-Naumann terminal velocity", CHECKED, beads=rows, fluid_procs=args.procs,
                         fluid_steps=fluid_steps, max_Re_p=re_max)
    case.record("wall time of the coupled run [s]", elapsed, "about a minute on a 2-core machine", 120.0,
                suffix="wall_time", fluid_procs=args.procs, fluid_steps=fluid_steps)
    chart_path = case.save_chart(chart(t, v, reference, positions, last_fluid_speed(folder)))
    print(f"\nchecked: {'PASS' if record['pass'] else 'FAIL'} (every bead within {CHECKED:.0%} of its "
          f"terminal velocity; worst {worst:.2%}); coupled run {elapsed:.0f} s")
    print(f"chart:    {chart_path}")
    print(f"ParaView: paraview {folder / 'case.foam'}   (fluid: U, p, alphaf; then File > Open {folder / 'VTK' / 'beads.pvd'})")
    print(f"records:  {case.folder}/demo.cfd_dem*.json")
    print("\nNext, each in one line (docs/getting-started.md walks through them):")
    talus = "build/bin/talus"
    print(f"  {talus} run cases/dem/dem_gravity_deposition.py --quick        # plain DEM")
    print(f"  {talus} run cases/vans/vans_sediment_transport.py --quick       # 1D VANS sediment transport")
    print(f"  {talus} case permeability --out perm && {talus} run perm/permeability.py        # pore flow")
    print(f"  {talus} case femxdem --out femxdem && {talus} run femxdem/femxdem.py         # FEM x DEM")
    print(f"  {talus} case cfd --help                                    # your own CFD-DEM case")
    return 0 if record["pass"] else 1


if __name__ == "__main__":
    sys.exit(main())
