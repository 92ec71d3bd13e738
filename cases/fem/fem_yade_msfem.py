"""Yade's FEMxDEM biaxialSmooth.py under run-escript: Yade's msFEM2D against Talus's drop-ins.

Run:      build/bin/talus run cases/fem/fem_yade_msfem.py [--quick] [--results DIR]
Set-up:   Yade's examples/FEMxDEM/prepareRVE.py run by Yade (400 disks, -100 kPa, friction 0.5)
          gives the packing; its cell, centres and radii are exported and built identically
          for both programs (Yade: O.save('0.yade.gz'); Talus: talus.fem.rveFromJSON), blocked
          in zXY, contacts detected without motion, damping 0.1. Yade's prepareRVE.py gives the
          disks the mass of a cylinder 0.1 thick (density 2650), which Talus cannot set
          (State.mass is read-only): both sides take sphere masses of the density that gives a
          sphere of the mean radius that mass, and its P-wave time step.
          Yade's biaxialSmooth.py is copied with a smaller mesh and fewer load steps (quick: 1 x 2
          elements, 8 Gauss points, 4 steps; full: 2 x 4 elements, 32 points, 20 steps; each
          step 0.1 % axial strain) and 2 pool processes for the 2 cores (it asks for 16), and run
          unchanged otherwise by `run-escript` twice: with Yade's FEMxDEM folder on PYTHONPATH
          (its modules and yadeimport.py -> /usr/bin/yade, as Yade's instructions say) and with
          Talus's (build/python/yade_femxdem:build/python, OMP_NUM_THREADS=2). Both runs get a
          sitecustomize giving Python 2's `file` (the example's output needs it; Talus's
          drop-ins give it themselves).
Checked:  fem.yade-msfem.biaxial: the largest relative difference of the top force (the
          axial stress times the width) from Yade's over the load steps (<= 2 %); the record's
          fields hold both curves, the wall times of both run-escript invocations and their
          ratio. fem.yade-msfem.speed: Yade's wall time / Talus's (>= 1).
Produces: the records and chart fem.yade-msfem.png (both curves; wall times).
"""
import json
import os
import re
import shutil
import subprocess
import tempfile
import time
from pathlib import Path

import numpy as np

from talus import results

EXAMPLES = Path("/usr/share/doc/yade/examples/FEMxDEM")
YADE_FEMXDEM = Path("/usr/lib/x86_64-linux-gnu/yade-double/py/yade/FEMxDEM")

EXPORT = """
import json
O.load('0.yade.gz')
h = O.cell.hSize
json.dump({"hSize": [[h[i, j] for j in range(3)] for i in range(3)],
           "pos": [list(O.cell.wrap(b.state.pos)) for b in O.bodies], "radius": [b.shape.radius for b in O.bodies],
           "blockedDOFs": "zXY", "dt": O.dt, "young": O.materials[0].young, "poisson": O.materials[0].poisson,
           "frictionAngle": O.materials[0].frictionAngle, "density": O.materials[0].density,
           "stress": [[x for x in r] for r in getStress()]}, open('rve.json', 'w'))
"""

BUILD = """
import json
d = json.load(open('rve.json'))
O.periodic = True
O.cell.hSize = Matrix3(*[x for r in d["hSize"] for x in r])
O.materials.append(FrictMat(young=d["young"], poisson=d["poisson"], frictionAngle=d["frictionAngle"], density=d["density"]))
for c, r in zip(d["pos"], d["radius"]):
    b = sphere(tuple(c), r)
    b.state.blockedDOFs = "xyzXYZ"     # for the step that detects the contacts: nothing moves
    O.bodies.append(b)
O.engines = [ForceResetter(), InsertionSortCollider([Bo1_Sphere_Aabb()]),
             InteractionLoop([Ig2_Sphere_Sphere_ScGeom()], [Ip2_FrictMat_FrictMat_FrictPhys()],
                             [Law2_ScGeom_FrictPhys_CundallStrack()]), NewtonIntegrator(damping=DAMPING)]
O.dt = d["dt"]
O.run(1, True)
for b in O.bodies:
    b.state.blockedDOFs = d["blockedDOFs"]
O.cell.trsf = Matrix3.Identity
O.cell.velGrad = Matrix3.Zero
for b in O.bodies:
    b.state.refPos = b.state.pos
    b.state.refOri = b.state.ori
O.save('0.yade.gz')
print("RVESTRESS", getStress()[0, 0], getStress()[1, 1])
"""


def _run(command, cwd, env, timeout=7200):
    start = time.perf_counter()
    done = subprocess.run(command, cwd=cwd, env=env, capture_output=True, text=True, timeout=timeout)
    wall = time.perf_counter() - start
    if done.returncode != 0:
        raise RuntimeError(f"{' '.join(map(str, command))} failed in {cwd}:\n{done.stdout[-3000:]}\n{done.stderr[-3000:]}")
    return wall, done.stdout


def _curve(folder: Path):
    rows = [l.split() for l in (folder / "result" / "biaxial_surf.dat").read_text().splitlines() if not l.startswith("#")]
    elapsed = [l for l in (folder / "result" / "biaxial_surf.dat").read_text().splitlines() if l.startswith("#")]
    hours = float(elapsed[0].split(":")[1]) if elapsed else float("nan")
    return np.array([[float(x) for x in r] for r in rows]), hours * 3600


def main():
    args = results.case_arguments(__doc__).parse_args()
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    import talus
    from talus.fem import rveFromJSON
    case = results.Case("fem.yade-msfem", quick=args.quick, folder=args.results)
    if shutil.which("yade") is None or shutil.which("run-escript") is None:
        raise SystemExit("fem_yade_msfem: needs yade and run-escript (./setup.sh installs both)")
    nx, ny, steps = (1, 2, 4) if args.quick else (2, 4, 20)
    damping = 0.1                      # Yade's prepareRVE.py
    work = Path(tempfile.mkdtemp(prefix="fem_yade_msfem_"))
    python = Path(talus.__file__).resolve().parent.parent
    # Yade's FEMxDEM folder as Yade's instructions make it: its modules and yadeimport.py -> yade
    yfem, shim = work / "yade_femxdem", work / "py2"
    yfem.mkdir()
    shim.mkdir()
    for f in YADE_FEMXDEM.glob("*.py"):
        (yfem / f.name).symlink_to(f)
    (yfem / "yadeimport.py").symlink_to(shutil.which("yade"))
    (shim / "sitecustomize.py").write_text("import builtins\nbuiltins.file = open\n")

    # the packing: Yade's prepareRVE.py, exported, built the same way in both programs
    prep = work / "prepare"
    prep.mkdir()
    shutil.copy(EXAMPLES / "prepareRVE.py", prep)
    _run(["yade", "-n", "-x", "prepareRVE.py"], prep, dict(os.environ))
    (prep / "export.py").write_text(EXPORT)
    _run(["yade", "-n", "-x", "export.py"], prep, dict(os.environ))
    packing = json.loads((prep / "rve.json").read_text())
    # Yade's disks have the mass of a cylinder 0.1 thick of density 2650, and its time step is the
    # P-wave step of those masses; with one density for spheres, that of a sphere of the mean radius
    # with that mass, and the P-wave step of it (as prepareRVE.py takes, without a safety factor)
    r = np.array(packing["radius"])
    packing["density"] = 2650 * 0.1 * 3 / (4 * r.mean())
    packing["dt"] = float(r.min() / np.sqrt(packing["young"] / packing["density"]))
    (prep / "rve.json").write_text(json.dumps(packing))
    script = (EXAMPLES / "biaxialSmooth.py").read_text()
    for old, new in ((r"^nx = 8", f"nx = {nx}"), (r"^ny = 16", f"ny = {ny}"), (r"^nump = 16", "nump = 2"),
                     (r"while t < 100:", f"while t < {steps}:")):
        script, n = re.subn(old, new, script, flags=re.M)
        if n != 1:
            raise RuntimeError(f"biaxialSmooth.py changed: {old!r} not found once")
    runs = {}
    for program in ("yade", "talus"):
        folder = work / program
        folder.mkdir()
        (folder / "biaxialSmooth.py").write_text(script)
        shutil.copy(prep / "rve.json", folder)
        if program == "yade":
            (folder / "build.py").write_text(BUILD.replace("DAMPING", repr(damping)))
            _run(["yade", "-n", "-x", "build.py"], folder, dict(os.environ))
            env = {**os.environ, "PYTHONPATH": f"{shim}:{yfem}"}
        else:
            rveFromJSON(packing, folder / "0.yade.gz", damping=damping)
            env = {**os.environ, "PYTHONPATH": f"{shim}:{python / 'yade_femxdem'}:{python}", "OMP_NUM_THREADS": "2",
                   "TALUS_MSFEM": json.dumps({"damping": damping})}
        wall, out = _run(["run-escript", "biaxialSmooth.py"], folder, env)
        curve, inside = _curve(folder)
        iterations = [int(m) for m in re.findall(r"Convergence reached after (\d+) iteration", out)]
        runs[program] = dict(wall=wall, inside=inside, curve=curve, iterations=iterations)
        print(f"{program}: {wall:.1f} s (solve loop {inside:.1f} s), Newton iterations {iterations}, "
              f"top force {curve[:, 1].round(1).tolist()}", flush=True)
    y, t = runs["yade"]["curve"], runs["talus"]["curve"]
    if y.shape != t.shape:
        raise RuntimeError(f"the runs wrote {len(y)} and {len(t)} load steps")
    diff = np.abs(t[:, 1] - y[:, 1]) / np.abs(y[:, 1])
    rise = np.abs((t[:, 1] - t[0, 1]) - (y[:, 1] - y[0, 1]))[1:] / np.abs(y[1:, 1] - y[0, 1])
    ratio = runs["yade"]["wall"] / runs["talus"]["wall"]
    common = dict(peer="yade 2023.02a", gauss_points=4 * nx * ny, load_steps=steps, spheres=len(packing["radius"]),
                  strain=y[:, 0].tolist(), force_yade=y[:, 1].tolist(), force_talus=t[:, 1].tolist(),
                  wall_yade_s=runs["yade"]["wall"], wall_talus_s=runs["talus"]["wall"],
                  solve_yade_s=runs["yade"]["inside"], solve_talus_s=runs["talus"]["inside"], speed_ratio=ratio,
                  iterations_yade=runs["yade"]["iterations"], iterations_talus=runs["talus"]["iterations"],
                  rise_difference=float(rise.max()))
    print(f"largest relative difference of the top force {diff.max():.2e} (of its rise from the confinement "
          f"{rise.max():.2e}); wall time Yade {runs['yade']['wall']:.1f} s, Talus {runs['talus']['wall']:.1f} s: "
          f"{ratio:.2f}x", flush=True)
    case.record(f"largest relative difference of the top force of Yade's biaxialSmooth.py from Yade's msFEM2D, "
                f"Talus's drop-ins ({4 * nx * ny} Gauss points, {steps} load steps; of the rise from the "
                f"confinement {rise.max():.1e})", float(diff.max()),
                "Yade 2023.02a FEMxDEM msFEM2D under run-escript, same packing and script", 0.02, suffix="biaxial",
                **common)
    case.record("wall time of run-escript biaxialSmooth.py, Yade's msFEM2D / Talus's drop-ins", ratio,
                "Yade 2023.02a FEMxDEM msFEM2D (2 pool processes) against Talus (2 OpenMP threads)", 1.0,
                comparison=">=", suffix="speed", **common)
    fig, (ax, bars) = plt.subplots(1, 2, figsize=(10, 3.8), gridspec_kw={"width_ratios": [2, 1]})
    ax.plot(-100 * y[:, 0], -y[:, 1] / 0.05 / 1e3, "o-", label="Yade msFEM2D")
    ax.plot(-100 * t[:, 0], -t[:, 1] / 0.05 / 1e3, "s--", mfc="none", label="Talus drop-ins")
    ax.set_xlabel("axial strain (%)")
    ax.set_ylabel("mean axial stress on the top (kPa)")
    ax.set_title(f"biaxialSmooth.py, {4 * nx * ny} Gauss points: largest difference {100 * diff.max():.2f} %",
                 fontsize=9)
    ax.legend()
    bars.bar(["Yade", "Talus"], [runs["yade"]["wall"], runs["talus"]["wall"]], color=["C0", "C1"])
    bars.set_ylabel("wall time of run-escript (s)")
    bars.set_title(f"Yade / Talus = {ratio:.2f}", fontsize=9)
    case.save_chart(fig)


if __name__ == "__main__":
    main()
