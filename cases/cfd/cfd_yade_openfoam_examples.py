"""CFD-DEM case: Yade's own OpenFOAM examples (examples/openfoam/example_icoFoamYade and
example_pimpleFoamYade, as Debian's yade package installs them) run with Talus: their
scriptYade.py and case folders, Talus's solvers under the names the cases give (icoFoamYade =
talusPointForceFoam, pimpleFoamYade = talusVolumeAveragedFoam).

Run:      build/bin/talus run cases/cfd/cfd_yade_openfoam_examples.py [--quick] [--results DIR]
          [--examples DIR]   (as root export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1)
Each example: copied to a temporary folder; `python3 -m talus.coupling.foam_case prepare .`
(blockMesh, decomposePar with the decomposeParDict bridged to OpenFOAM v1912); then the
documented equivalent of its run.sh line `mpiexec -n 1 python scriptYade.py : -n 2
icoFoamYade -parallel`:
          PYTHONPATH=<build>/python PATH=<build>/bin:$PATH /usr/bin/python3 scriptYade.py
(the DEM process starts the 2 fluid ranks of the decomposed case itself; docs/coupling.md,
"Running Yade's OpenFOAM examples"). Both examples end when the fluid reaches its controlDict
endTime (68 fluid steps of 0.5 ms, 17 of 2 ms), where Yade's solvers leave their time loop.
Quick: endTime lowered to 4 fluid steps in the copies.
Each example's scriptYade.py runs as shipped (facet walls in its periodic cell, with
InsertionSortCollider's allowBiggerThanPeriod).
Checked (each run, from the engine's summary, TALUS_FOAM_SUMMARY): exit status 0, every fluid
step up to endTime exchanged with both fluid ranks, forces and velocities finite, and
- icoFoamYade (walls at -/+ 0.05 m/s, fluid and spheres at rest at the start): the spheres in
  the cell rows along the walls move with the wall's fluid (mean u_x of the row's spheres of the
  wall's sign, 0.3-1.1 of the row's fluid velocity: the spheres lag the accelerating fluid by
  their relaxation time of 1.25 ms, 0.6 after 4 fluid steps, 0.98 after the example's 68), the
  others nearly at rest (< 5 % of the wall speed;
  1.4 % after 68 steps, the momentum reaching the second row), drag beta = 3 pi mu d (Stokes);
- pimpleFoamYade: the drag coefficient at rest is Schiller-Naumann's alpha^-2.65 over Stokes:
  beta / (3 pi mu d) within [1, 1.05] and the mean solid fraction the particles see (1 - alpha)
  between 0.5 and 3 times the packing's (1000 spheres of r = 7.5 mm in 1 m3: 1.77e-3; a particle
  sees its own volume too).
Produces: record cfd.yade-openfoam-examples (fraction of the two examples whose unchanged
          script passes; tolerance: both) with each run's numbers.
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

EXAMPLES = {"icoFoamYade": "example_icoFoamYade", "pimpleFoamYade": "example_pimpleFoamYade"}
DEFAULT_FOLDER = Path("/usr/share/doc/yade/examples/openfoam")


def build_dir() -> Path:
    import talus
    return Path(os.environ.get("TALUS_BUILD_DIR", Path(talus.__file__).resolve().parents[2]))


def environment(build: Path, summary: Path) -> dict:
    env = dict(os.environ, PYTHONPATH=str(build / "python"), PATH=f"{build / 'bin'}:{os.environ.get('PATH', '')}",
               WM_PROJECT_DIR=os.environ.get("WM_PROJECT_DIR", "/usr/share/openfoam"),
               OMPI_MCA_rmaps_base_oversubscribe="1", OMPI_MCA_btl_tcp_if_include="lo",
               OMPI_MCA_oob_tcp_if_include="lo", TALUS_FOAM_SUMMARY=str(summary))
    if os.geteuid() == 0:
        env.update(OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1")
    return env


def prepare(source: Path, work: Path, quick_steps: int | None) -> Path:
    from talus.coupling.foam_case import case_settings, prepare_case
    shutil.copytree(source, work)
    if quick_steps:
        control = work / "system" / "controlDict"
        s = case_settings(work)
        end = s["startTime"] + quick_steps * s["deltaT"]
        control.write_text(re.sub(r"(\n\s*endTime\s+)[^;]+;", rf"\g<1>{end:g};", control.read_text()))
    prepare_case(work)
    (work / "yadep").mkdir(exist_ok=True)  # the example's instructions: "make dir for VTK dump"
    return work


def run_script(case: Path, script: str, build: Path, timeout: float = 900) -> dict:
    summary = case / "summary.json"
    summary.unlink(missing_ok=True)
    start = time.perf_counter()
    done = subprocess.run(["/usr/bin/python3", script], cwd=case, env=environment(build, summary),
                          capture_output=True, text=True, timeout=timeout)
    out = dict(returncode=done.returncode, seconds=time.perf_counter() - start,
               output_tail=(done.stdout + done.stderr)[-1500:])
    if summary.is_file():
        out["summary"] = json.loads(summary.read_text())
    return out


def check(example: str, run: dict, expected_steps: int) -> tuple[bool, dict]:
    """The physical checks of one run (see the module's docstring)."""
    if run["returncode"] != 0 or "summary" not in run:
        error = [line for line in run["output_tail"].splitlines() if "Error" in line or "error" in line]
        return False, dict(reason=(error[-1] if error else f"exit {run['returncode']}")[:300])
    s = run["summary"]
    x, v = np.array(s["positions"]), np.array(s["velocities"])
    uf, ratio = np.array(s["fluid_velocities"]), np.array(s["beta_over_stokes"])
    info = dict(exchanges=s["exchanges"], fluid_steps=s["fluidSteps"], fluid_procs=s["fluidProcs"],
                dem_steps=s["iter"], exchange_interval=s["dataExchangeInterval"], seconds=run["seconds"],
                max_Re_p=s["maxReynolds"], beta_over_stokes_min=float(ratio.min()), beta_over_stokes_max=float(ratio.max()))
    ok = s["finite"] and s["exchanges"] == expected_steps and s["fluidProcs"] == 2
    if example == "icoFoamYade":
        dy = 0.1 / 20
        wall_speed = 0.05
        rows = {"y0": x[:, 1] < dy, "y1": x[:, 1] > 0.1 - dy}
        middle = ~(rows["y0"] | rows["y1"])
        for name, sign in (("y0", -1), ("y1", 1)):
            vp, vf = v[rows[name], 0].mean(), uf[rows[name], 0].mean()
            info[f"u_spheres_{name}"], info[f"u_fluid_{name}"] = float(vp), float(vf)
            ok &= bool(np.sign(vp) == sign == np.sign(vf) and 0.3 <= vp / vf <= 1.1)
        info["u_middle_max"] = float(np.abs(v[middle, 0]).max())
        ok &= info["u_middle_max"] < 0.05 * wall_speed
        ok &= bool(np.allclose(ratio, 1.0, rtol=1e-9))
    else:
        alpha = ratio ** (-1 / 2.65)
        packing = len(ratio) * 4 / 3 * np.pi * 0.0075 ** 3 / 1.0
        info["solid_fraction_seen"], info["solid_fraction_packing"] = float(1 - alpha.mean()), packing
        ok &= bool(ratio.min() >= 1 - 1e-12 and ratio.max() <= 1.05)
        ok &= bool(0.5 * packing <= 1 - alpha.mean() <= 3 * packing)
    return bool(ok), info


def main():
    parser = results.case_arguments(__doc__)
    parser.add_argument("--examples", type=Path, default=DEFAULT_FOLDER, help="Yade's examples/openfoam folder")
    args = parser.parse_args()
    case = results.Case("cfd.yade-openfoam-examples", quick=args.quick, folder=args.results)
    build = build_dir()
    quick_steps = 4 if args.quick else None
    outcome = {}
    with tempfile.TemporaryDirectory(prefix="talus_yade_foam_") as tmp:
        for example, folder in EXAMPLES.items():
            source = args.examples / folder
            if not source.is_dir():
                outcome[example] = (False, {"reason": f"{source} missing"})
                continue
            work = prepare(source, Path(tmp) / folder, quick_steps)
            from talus.coupling.foam_case import case_settings
            s = case_settings(work)
            steps = int(round((s["endTime"] - s["startTime"]) / s["deltaT"]))
            outcome[example] = check(example, run_script(work, "scriptYade.py", build), steps)
            print(f"{example}: {'pass' if outcome[example][0] else 'FAIL'} {outcome[example][1]}", flush=True)
    passed = sum(ok for ok, _ in outcome.values()) / len(EXAMPLES)
    print(f"examples whose unchanged script passes: {passed:.0%}")
    case.record("fraction of Yade's two OpenFOAM examples (example_icoFoamYade, example_pimpleFoamYade) whose "
                "unchanged scriptYade.py and case folder run with Talus's solvers and pass the physical checks",
                passed, "both examples", 1.0, comparison=">=", **{example: info for example, (_, info) in outcome.items()})


if __name__ == "__main__":
    main()
