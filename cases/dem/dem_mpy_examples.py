"""DEM case: Yade's own MPI examples (scripts written for yade.mpy) run unchanged under mpirun in Talus.

Run:      build/bin/talus run cases/dem/dem_mpy_examples.py [--quick] [--results DIR]
Set-up:   the scripts of Yade 2023.02a's examples/mpi (/usr/share/doc/yade/examples/mpi), each run
          by `mpirun --oversubscribe -np N talus run -j 1 script.py` and by `mpirun --oversubscribe
          -np N yade -n -x script.py` (N = 3; 4 for reallocateBodies.py, which sets 4 subdomains;
          6 for testMPI_3D_bisection.py, which asks mpirun for 6: Yade's mpy hangs at fewer, trying
          to spawn the rest). The scripts' text is unchanged but for their step count (NSTEPS,
          to keep the case short) and, for the scripts that end by merging the scene, one line
          appended that prints from rank 0 what the merged scene holds (bodies, the sum of the
          spheres' heights, the kinetic energy). Quick: NSTEPS 100 (testMPI_2D.py: 200, and its
          blocks of N x M = 20 x 20 spheres per worker given on its command line); full: the
          scripts' NSTEPS but 1000 at most.
          In scope: the scripts that run in Yade 2023.02a here. Out of scope: the Python 2
          scripts (print statements: testMPI_3D.py, testMPI_strongScalability*.py,
          testMPI_weakScalability.py), which fail in Yade too, and helloMPY.py, which re-spawns
          workers (mp.disconnect(), mp.initialize(8)) and hangs under mpirun in Yade too.
Checked:  dem.mpi.mpy-examples: the in-scope scripts that do not run unchanged in Talus (0).
          dem.mpi.mpy-examples.yade: for each script its measured quantity against Yade's mpy run
          of the same script (the total force on the floor printed by the script, or the merged
          scene's sum of heights): the largest relative difference (<= 1e-3: both integrate the
          same linear contact law; the summation orders differ). For vtkRecorderExample.py the
          reference is Yade's run of its scene in one process (the script with yade.mpy's lines
          and its VTKRecorder taken out, see without_mpy): Yade's own mpy run of it departs from
          that (recorded in the details). Its packing is a lattice with no gap, whose pairs
          touch exactly: Talus decides when two spheres touch to the last bit as Yade does
          (dem/contact/SphereTouch.h), else its contacts, and with them the step
          GlobalStiffnessTimeStepper sets, would differ from Yade's from the first step.
          dem.mpi.mpy-examples.serial: testMPI_2D.py under mpirun against the same scene in one
          process (the script's own single-core branch, its number of blocks given on its command
          line), reallocateBodies.py and testMPI_3D_bisection.py against `talus run script.py`
          alone (yade.mpy in one process), vtkRecorderExample.py against its scene in one process
          (as above): the largest relative difference (<= 1e-10).
"""

import re
import shutil
import subprocess
import sys
import tempfile
from pathlib import Path

from talus import results
from talus.bench import child_environment

EXAMPLES = Path("/usr/share/doc/yade/examples/mpi")
MPIRUN = ["mpirun", "--allow-run-as-root", "--oversubscribe"]
# script: (processes, arguments, what is measured: the printed total force or the merged scene)
IN_SCOPE = {
    "testMPI_2D.py": (3, ["20", "20"], "force"),
    "parallelBodyInsert3D.py": (3, [], "force"),
    "mpyPerf.py": (3, [], "force"),
    "reallocateBodies.py": (4, [], "merged"),
    "testMPI_3D_bisection.py": (6, [], "merged"),
    "vtkRecorderExample.py": (3, [], "merged"),
}
OUT_OF_SCOPE = {
    "testMPI_3D.py": "Python 2 (print statements): fails in Yade 2023.02a too",
    "testMPI_strongScalability.py": "Python 2 (print statements): fails in Yade 2023.02a too",
    "testMPI_strongScalability_noAlignedBox.py": "Python 2 (print statements): fails in Yade 2023.02a too",
    "testMPI_weakScalability.py": "Python 2 (print statements): fails in Yade 2023.02a too",
    "helloMPY.py": "re-spawns workers (mp.disconnect(), then mp.initialize(8)): hangs under mpirun in Yade 2023.02a too",
}
# Those whose scene does not depend on the process count, run in one process too: testMPI_2D.py by
# its single-core branch (its number of blocks on its command line), the others by yade.mpy in one
# process (vtkRecorderExample.py is not: it ends by asking workers for their kinetic energy).
SERIAL = ("testMPI_2D.py", "reallocateBodies.py", "testMPI_3D_bisection.py")     # (and see without_mpy)
# what rank 0 prints of a merged scene (Yade's master holds it all after a merge; Talus's every process)
PROBE = ("\nif mp.rank == 0: print('PROBE', len(O.bodies), sum(b.state.pos[1] for b in O.bodies "
         "if isinstance(b.shape, Sphere)), kineticEnergy())\n")
NUMBER = r"(-?[0-9.]+(?:e[-+]?[0-9]+)?)"


def prepare(name: str, folder: Path, steps: int) -> Path:
    """The example with NSTEPS = min(its own, steps) and, for a merged scene, the probe appended."""
    text = (EXAMPLES / name).read_text()
    text = re.sub(r"^NSTEPS = (\d+)", lambda m: f"NSTEPS = {min(int(m.group(1)), steps)}", text, count=1, flags=re.M)
    if IN_SCOPE[name][2] == "merged":
        text += PROBE
    folder.mkdir(parents=True, exist_ok=True)
    script = folder / name
    script.write_text(text)
    return script


def without_mpy(name: str, folder: Path, steps: int) -> Path:
    """vtkRecorderExample.py made a script for one process (Yade's own mpy run of it departs from
    Yade's run of its scene in one process, and the script cannot run in one process as it is:
    its parallelMode needs MPI, it ends by asking workers): yade.mpy's lines and the VTKRecorder
    taken out, O.run(NSTEPS) for mp.mpirun(NSTEPS), the probe printed at the end."""
    text = prepare(name, folder, steps).read_text()
    text = text.replace("from yade import mpy as mp", "").replace(", parallelMode=True", "")
    text = re.sub(r"\n\s*VTKRecorder\(.*?\),\s*#[^\n]*\n", "\n", text, flags=re.S)
    text = text[:text.index("mp.ERASE_REMOTE_MASTER")] + "O.run(NSTEPS, True)\n" + PROBE.replace("if mp.rank == 0: ", "")
    script = folder / f"serial_{name}"
    script.write_text(text)
    return script


def run(command: list, folder: Path, timeout: float) -> tuple[int, str]:
    try:
        done = subprocess.run(command, cwd=folder, capture_output=True, text=True, timeout=timeout,
                              env=child_environment())
    except subprocess.TimeoutExpired as e:
        return -1, f"timed out after {timeout} s\n{e.stdout or ''}"
    return done.returncode, done.stdout + done.stderr


def measured(name: str, output: str) -> float | None:
    """The script's total force on the floor, or the merged scene's sum of the spheres' heights."""
    if IN_SCOPE[name][2] == "force":
        found = re.findall(r"Total force on floor=\s*" + NUMBER, output)
    else:
        found = re.findall(r"PROBE \d+ " + NUMBER, output)
    return float(found[-1]) if found else None


def main():
    args = results.case_arguments(__doc__).parse_args()
    case = results.Case("dem.mpi.mpy-examples", quick=args.quick, folder=args.results)
    steps = 100 if args.quick else 1000
    talus = [sys.executable, "-m", "talus", "run", "-j", "1"]
    have_yade = shutil.which("yade") is not None
    rows = {}
    with tempfile.TemporaryDirectory() as tmp:
        for name, (processes, arguments, _) in IN_SCOPE.items():
            row = rows[name] = {"processes": processes}
            script_steps = max(steps, 200) if name == "testMPI_2D.py" else steps
            for program in ("talus", "yade") if have_yade else ("talus",):
                folder = Path(tmp) / program / name[:-3]
                script = prepare(name, folder, script_steps)
                command = talus + [str(script), *arguments] if program == "talus" else \
                    ["yade", "-n", "-x", str(script), *arguments]
                code, output = run(MPIRUN + ["-np", str(processes)] + command, folder, 900)
                row[program] = measured(name, output)
                row[f"{program}_ran"] = code == 0 and row[program] is not None
                if not row[f"{program}_ran"]:
                    print(f"{name} under {program}: exit {code}\n{output[-3000:]}")
            folder = Path(tmp) / "serial" / name[:-3]
            if name in SERIAL:     # the same scene in one process
                script = prepare(name, folder, script_steps)
                serial_arguments = arguments + [str(processes)] if name == "testMPI_2D.py" else arguments
                code, output = run(talus + [str(script), *serial_arguments], folder, 900)
                row["serial"] = measured(name, output)
            if name == "vtkRecorderExample.py":     # its scene in one process, in Talus and in Yade
                script = without_mpy(name, folder, script_steps)
                row["serial"] = measured(name, run(talus + [str(script)], folder, 900)[1])
                if have_yade:
                    row["yade_serial"] = measured(name, run(["yade", "-n", "-x", str(script)], folder, 900)[1])
            print(f"{name}: {row}")

    def difference(a, b):   # (1: a run that gave no value, which the first record counts too)
        return abs(a - b) / max(abs(b), 1e-300) if a is not None and b is not None else 1.0

    failed = [name for name, row in rows.items() if not row["talus_ran"]]
    case.record(f"examples of Yade's mpy in scope (they run in Yade 2023.02a) that do not run unchanged under "
                f"mpirun in Talus, of {len(IN_SCOPE)}", len(failed), "0: every one runs", 0,
                ran=len(IN_SCOPE) - len(failed), in_scope=len(IN_SCOPE), failed=failed,
                out_of_scope=OUT_OF_SCOPE, examples=rows)
    if have_yade:
        versus = {name: difference(row["talus"], row.get("yade_serial", row["yade"]))
                  for name, row in rows.items() if row.get("yade_ran")}
        case.record("largest relative difference of each example's measured quantity (the total force on the floor "
                    "it prints, or the merged scene's sum of the spheres' heights) from Yade's mpy run of it (for "
                    "vtkRecorderExample.py, from Yade's run of its scene in one process, which Yade's mpy departs from)",
                    max(versus.values(), default=1.0), "Yade 2023.02a, same script and process count",
                    1e-3, suffix="yade", differences=versus,
                    yade_mpy_from_yade_serial={name: difference(row["yade"], row["yade_serial"])
                                               for name, row in rows.items() if "yade_serial" in row}, examples=rows)
    versus = {name: difference(row["talus"], row["serial"]) for name, row in rows.items() if "serial" in row}
    case.record("largest relative difference of an example's measured quantity under mpirun from the same scene "
                "in one process (talus run)", max(versus.values(), default=1.0),
                "Talus in one process", 1e-10, suffix="serial", differences=versus, examples=rows)


if __name__ == "__main__":
    main()
