"""CFD-DEM case: spheres in a shear (Couette) flow, point-force coupling with OpenFOAM
(talusPointForceFoam spawned over MPI; its case written by talus.coupling.case_builder). The set-up of Yade's
shipped example examples/openfoam/example_icoFoamYade (scriptYade.py, icoFoamYade).

Run:      build/bin/talus run cases/cfd/cfd_shear_flow.py [--quick] [--results DIR] [--procs 2] [--vtk DIR]
          (as root export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1)
Set-up:   as Yade's example: a 0.1 m cube of fluid (rho = 1000 kg/m3, nu = 1e-4 m2/s) between
          the walls y = 0 and y = 0.1 m moving at -/+ U_w = 0.05 m/s, periodic across x and z
          (cyclic patches; the DEM scene is periodic too, its cell 0.1 x 0.2 x 0.1 m so that the
          two walls lie inside it); 1000 spheres r = 0.75 mm +- 10 % (makeCloud, seed 1),
          FrictMat E = 5e6 Pa, friction 15 deg, density 1000 kg/m3, at rest, no gravity; fluid
          step 0.5 ms as Yade's. The fluid starts from the developed linear profile
          u = U_w (2 y / H - 1) (Yade's example sets it in the solver's source: it takes
          H^2 / nu = 100 s to develop from rest). Drag re-evaluated at every DEM sub-step
          (implicitDrag: the relaxation time rho_p d^2 / (18 mu) = 1.25 ms is only 2.5 fluid
          steps). Quick: 10^3 cells, 40 fluid steps (20 ms = 16 relaxation times); full: 20^3
          cells (Yade's mesh), 200 fluid steps.
Checked:  each sphere's velocity along x against the Stokes drag balance: the point-force
          solver drags it towards the fluid velocity of its cell, here the linear profile at
          the cell centre's height U_c, so u_p(t) = U_c (1 - exp(-t / tau_p)) with its own
          tau_p; the root-mean-square deviation over the spheres, relative to U_w, at every
          exchange within 2 % (the largest single deviation is recorded: the few spheres that
          meet another or cross into the next cell row leave the model).
          Recorded, not checked: the deviation at the end from the profile at the sphere's own
          height (the cell-value interpolation of point-force coupling: up to dx / H = 10 % of
          U_w on the quick mesh), the largest |v| (Yade's example raises above U_w), and the
          sphere velocities across the flow (y, z).
ParaView: --vtk DIR keeps the OpenFOAM case in DIR with the fluid fields every 10 fluid steps
          and the spheres at the same steps (the DEM's VTKRecorder, DIR/VTK/particles-spheres.pvd;
          positions as the periodic DEM keeps them, unwrapped); open DIR/case.foam and the .pvd.
Produces: record cfd.shear_flow; chart cfd.shear_flow.png (u_x against y at the end; mean
          relaxation against t / tau_p).
"""
import math
import re
import shutil
import subprocess
import tempfile
import time
from pathlib import Path

import numpy as np

from talus import results
from talus.coupling.case_builder import PERIODIC, Wall, cfd_case
from talus.coupling.cases import foam_environment
from talus.dem import (Bo1_Sphere_Aabb, Bo1_Wall_Aabb, ForceResetter, FrictMat, Ig2_Sphere_Sphere_ScGeom,
                       Ig2_Wall_Sphere_ScGeom, InsertionSortCollider, InteractionLoop,
                       Ip2_FrictMat_FrictMat_FrictPhys, Law2_ScGeom_FrictPhys_CundallStrack, NewtonIntegrator,
                       PWaveTimeStep, Scene, wall)
from talus.dem.packing import pack
from talus.dem.files.export import PvdCollection, write_spheres

RHO, NU, RHO_P, H, U_WALL = 1000.0, 1e-4, 1000.0, 0.1, 0.05
MU = RHO * NU
CHECKED = 0.02


def profile(y):
    """The imposed linear profile."""
    return U_WALL * (2 * np.asarray(y) / H - 1)


# With --vtk: the fluid's fields and the spheres are written every this many fluid steps.
VTK_EVERY = 10


def prepare_case(procs: int, cells: int, vtk: bool):
    """The fluid case: walls moving at -/+ U_w across y, periodic across x and z, the linear
    profile as the initial field, fields written every VTK_EVERY fluid steps with --vtk."""
    return cfd_case(tempfile.mkdtemp(prefix="talus_cfd_shear_flow_"), solver="pointforce", box=((0, 0, 0), (H, H, H)),
                    cells=(cells, cells, cells), rho=RHO, nu=NU, gravity=(0, 0, 0), coupling_interval=5e-4,
                    boundaries={"y0": Wall((-U_WALL, 0, 0)), "y1": Wall((U_WALL, 0, 0)), "x0": PERIODIC, "z0": PERIODIC},
                    initial_velocity=lambda x: np.outer(profile(x[:, 1]), (1, 0, 0)), procs=procs,
                    write_every=VTK_EVERY if vtk else 1000)


def run(procs: int, cells: int, fluid_steps: int, vtk: Path | None = None):
    fluid = prepare_case(procs, cells, vtk is not None)
    work = fluid.path
    s = Scene()
    s.periodic = True
    s.cell.setBox(H, 2 * H, H)
    s.materials.append(FrictMat(young=5e6, poisson=0.5, frictionAngle=math.radians(15), density=RHO_P,
                                label="spheres"))
    s.materials.append(FrictMat(young=5e6, poisson=0.5, frictionAngle=0.0, density=RHO_P, label="walls"))
    s.bodies.append([wall((0, 0, 0), axis=1, material="walls"), wall((0, H, 0), axis=1, material="walls")])
    sp = pack.SpherePack()
    sp.makeCloud((2e-8, 2e-8, 2e-8), (0.099, 0.099, 0.099), 0.00075, 0.10, 1000, False, seed=1)
    ids = np.asarray(sp.toSimulation(s, material="spheres"))
    s.engines = [ForceResetter(), InsertionSortCollider([Bo1_Sphere_Aabb(), Bo1_Wall_Aabb()]),
                 InteractionLoop([Ig2_Sphere_Sphere_ScGeom(), Ig2_Wall_Sphere_ScGeom()],
                                 [Ip2_FrictMat_FrictMat_FrictPhys()], [Law2_ScGeom_FrictPhys_CundallStrack()]),
                 NewtonIntegrator(gravity=(0, 0, 0), damping=0.0)]
    s.dt = 0.7 * PWaveTimeStep(s)
    coupling = fluid.coupling(s, ids=ids, implicitDrag=True, reynoldsLimit=1.0).start()
    r = s.radii()[ids]
    tau = RHO_P * (2 * r) ** 2 / (18 * MU)
    t, u = [0.0], [s.velocities()[ids].copy()]
    y_start = s.positions()[ids][:, 1].copy()
    if vtk is not None:
        (work / "VTK").mkdir()
        spheres = PvdCollection(str(work / "VTK" / "particles-spheres.pvd"))
    start = time.perf_counter()
    try:
        for k in range(1, fluid_steps + 1):
            s.run(coupling.substeps, True)
            t.append(s.time)
            u.append(s.velocities()[ids].copy())
            if vtk is not None and k % VTK_EVERY == 0:  # when the fluid writes its fields
                path = work / "VTK" / f"particles-spheres.{k}.vtu"
                write_spheres(s, str(path))
                spheres.add(s.time, str(path))
        elapsed = time.perf_counter() - start
    finally:
        coupling.stop()
    y_end = s.positions()[ids][:, 1]
    if procs > 1:
        subprocess.run(["reconstructPar", "-case", str(work)] + ([] if vtk else ["-latestTime"]), check=True,
                       capture_output=True, env=foam_environment())
    last = max((p for p in work.iterdir() if re.fullmatch(r"[0-9.e-]+", p.name) and p.name != "0"),
               key=lambda p: float(p.name))
    fluid_u = (last / "U").read_text()
    if vtk is not None:
        shutil.copytree(work, vtk, dirs_exist_ok=True)   # with case.foam, what ParaView's OpenFOAM reader opens
        print(f"ParaView: open {vtk / 'case.foam'} (fluid) and {vtk / 'VTK' / 'particles-spheres.pvd'} (spheres)")
    shutil.rmtree(work, ignore_errors=True)
    return dict(t=np.array(t), u=np.array(u), tau=tau, y_start=y_start, y_end=y_end, coupling=coupling,
                elapsed=elapsed, fluid_U=fluid_u, substeps=coupling.substeps)


def fluid_profile(text: str, cells: int) -> np.ndarray:
    """The laterally averaged x velocity of the fluid in each row of cells along y."""
    m = re.search(r"internalField\s+nonuniform\s+List<vector>\s+(\d+)\s*\(\s*(.*?)\)\s*;", text, re.S)
    if m is None:
        raise RuntimeError("the fluid's U has no nonuniform internalField")
    u = np.array([v.split() for v in re.findall(r"\(([^()]*)\)", m.group(2))], dtype=float)
    if len(u) != int(m.group(1)):
        raise RuntimeError(f"the fluid's U lists {len(u)} of {m.group(1)} values")
    return u[:, 0].reshape(cells, cells, cells).mean(axis=(0, 2))   # axes z, y, x


def main():
    parser = results.case_arguments(__doc__)
    parser.add_argument("--procs", type=int, default=1, help="fluid ranks (decomposed case)")
    parser.add_argument("--vtk", type=Path, default=None,
                        help="keep the fluid case with its fields and the spheres every 10 fluid steps here")
    args = parser.parse_args()
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    case = results.Case("cfd.shear_flow", quick=args.quick, folder=args.results)
    cells, fluid_steps = (10, 40) if args.quick else (20, 200)
    res = run(args.procs, cells, fluid_steps, args.vtk)
    t, u, tau = res["t"], res["u"], res["tau"]
    dx = H / cells
    # Spheres barely move across the flow (checked below), so the cell row of the start holds.
    row = np.clip(np.floor(res["y_start"] / dx), 0, cells - 1)
    u_cell = profile((row + 0.5) * dx)
    expected = u_cell[None, :] * (1 - np.exp(-t[:, None] / tau[None, :]))
    error = (u[:, :, 0] - expected) / U_WALL
    deviation = float(np.max(np.sqrt(np.mean(error ** 2, axis=1))))
    worst = float(np.max(np.abs(error)))
    own_height = float(np.max(np.abs(u[-1, :, 0] - profile(res["y_end"])))) / U_WALL
    across = float(np.max(np.abs(u[:, :, 1:]))) / U_WALL
    largest = float(np.max(np.linalg.norm(u[-1], axis=1)))
    drift = float(np.max(np.abs(res["y_end"] - res["y_start"])))
    u_fluid = fluid_profile(res["fluid_U"], cells)
    fluid_change = float(np.max(np.abs(u_fluid - profile((np.arange(cells) + 0.5) * dx)))) / U_WALL
    print(f"{len(tau)} spheres, tau_p {tau.min() * 1e3:.3f}..{tau.max() * 1e3:.3f} ms, {fluid_steps} fluid steps x "
          f"{res['substeps']} DEM steps in {res['elapsed']:.1f} s on {args.procs} fluid rank(s)")
    print(f"deviation from U_c (1 - exp(-t/tau_p)): rms over the spheres {deviation:.3%} of U_w at worst, largest "
          f"single sphere {worst:.2%} (a sphere that met another or crossed a cell row); at the end from the profile at the "
          f"sphere's height {own_height:.2%} of U_w (cell size dx/H = {dx / H:.0%}); velocity across the flow "
          f"{across:.2e} U_w, drift across {drift * 1e3:.3f} mm; largest |v| {largest:.4f} m/s (Yade's check: < "
          f"{U_WALL}); fluid profile changed by {fluid_change:.2e} U_w; Re_p max {res['coupling'].maxReynolds:.3f}")

    fig, (a, b) = plt.subplots(1, 2, figsize=(9, 4))
    ys = np.linspace(0, H, 50)
    a.plot(profile(ys) * 100, ys * 100, "k-", lw=0.8, label="imposed linear profile")
    a.plot(u_fluid * 100, (np.arange(cells) + 0.5) * dx * 100, "ks", ms=4, mfc="none", label="fluid cells (end)")
    a.plot(u[-1, :, 0] * 100, res["y_end"] * 100, ".", ms=2, label="spheres (end)")
    a.set_xlabel("u_x [cm/s]")
    a.set_ylabel("y [cm]")
    a.legend(fontsize=7)
    moving = np.abs(u_cell) > 0.05 * U_WALL
    ratio = (u[:, moving, 0] / u_cell[moving]).mean(axis=1)
    tt = t / tau.mean()
    b.plot(tt, 1 - np.exp(-tt), "k--", lw=0.8, label="1 - exp(-t / tau_p)")
    b.plot(tt, ratio, "o", ms=3, label="spheres: mean u_x / U_c")
    b.set_xlabel("t / tau_p")
    b.set_ylabel("u_x / U_c")
    b.legend(fontsize=7)
    fig.suptitle(f"Shear flow (Yade's example), {len(tau)} spheres, point-force coupling, {cells}^3 cells")
    fig.tight_layout()
    case.record("rms deviation of the sphere velocities from the Stokes relaxation towards the cell's fluid "
                "velocity, relative to the wall velocity (largest over the exchanges)", deviation,
                "U_c (1 - exp(-t / tau_p))", CHECKED, largest_single_deviation=worst,
                cells=cells, fluid_steps=fluid_steps, fluid_procs=args.procs, deviation_own_height=own_height,
                velocity_across=across, largest_speed=largest, drift_across=drift, fluid_profile_change=fluid_change,
                max_Re_p=res["coupling"].maxReynolds, wall_time_s=res["elapsed"])
    case.save_chart(fig)


if __name__ == "__main__":
    main()
