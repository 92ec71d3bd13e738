"""CFD-DEM case: the DEM and the fluid both decomposed give the run of one DEM process and one
fluid rank (the coupling's many-to-many exchange, docs/coupling.md).

Run:      build/bin/talus run cases/cfd/cfd_mpi_parity.py [--quick] [--results DIR]
Set-up:   cases/scenes/fluidised_column.py, unchanged in every run (a smaller variant of
          cfd_fluidised_bed.py that the distributed DEM runs: 288 spheres d = 1 mm, quick, 432
          full, on a jittered lattice in an 8 x 8 mm column with walls, the linear law, falling
          through an upward flow ramped to 5 mm/s over 5 ms; talusVolumeAveragedFoam, cells 0.8
          mm, Gaussian envelope 1.5 mm, implicit drag), run as DEM processes + fluid ranks
          1 + 1 and 1 + 2 by `talus run`, 2 + 1 and 2 + 2 by `mpirun --oversubscribe -np 2 talus
          run -j 1` (2 cores here: the 2 + 2 run has 4 processes); the fluid's pressure solved to
          1e-13 in every corrector (the case builder's pressure_tolerance and
          pressure_relative_tolerance 0), so that a decomposed fluid differs from the serial one by
          rounding only (with relTol 0.01 in the first corrector it differs by the solver's
          tolerance: 2.4e-10 in the positions after 20 fluid steps). Quick: 100 fluid steps; full: 400.
          Then the same in the fluidised bed's periodic column (the scene's `periodic`: a periodic
          cell across x and y, a floor wall at the inlet and a lid, the mesh's x and y patches
          cyclic, its slabs along z), run as 1 + 1, 1 + 2 and 2 + 2.
Checked:  cfd.mpi.parity: the largest difference of a body's position in the 2 + 2 run from the
          1 + 1 run's, every 20 fluid steps over the first 100 (the quick run), over the largest
          coordinate (relative; <= 1e-9: round-off). The details hold the same for 1 + 2, 2 + 1
          and 2 + 2 against 1 + 2 (a decomposed DEM against one process with the same fluid ranks:
          0, the same bits), the largest differences over the whole run, and each DEM process's
          particles, messages and fluid ranks at the last exchange. cfd.mpi.parity.periodic-bed:
          the same for the periodic column (the decomposed fluidised bed, 2 + 2 against 1 + 1).
          cfd.mpi.parity.fluidised-bed: cfd_fluidised_bed.py itself, quick (its 5 800 fluid steps,
          whatever this case's mode; the pressure solved to 1e-13 as above), run as 1 + 1, 1 + 2
          and 2 + 2, every sphere's position taken every 200 fluid steps. Over that many steps of
          a bed resting on its contacts any rounding grows by orders of magnitude, so "within
          round-off" is measured against rounding itself: the 1 + 1 run is repeated three times
          with one sphere (the first, the middle, the last) moved by one ulp in x before the
          coupling, and the record is the largest difference of 2 + 2 from 1 + 1 over the run
          divided by the largest difference any of these one-ulp runs reaches from 1 + 1 (<= 1:
          the decomposed run lies no further from the serial one than a single rounding takes
          the serial run from itself). The details hold each pair's largest and final
          differences and the case's outputs (plateau, the fluid's pressure drop, U_mf, the bed's
          rise); cfd.mpi.parity.fluidised-bed-dem-split: the largest difference of 2 + 2 from
          1 + 2 over the run (the DEM's split alone, <= 1e-9).
Result:   quick (2026-12-07): 2 + 2 against 1 + 1 3.6e-16; 2 + 2 against 1 + 2 and 2 + 1 against
          1 + 1: 0. Full (432 spheres, 400 fluid steps): 2 + 2 against 1 + 2 and 2 + 1 against
          1 + 1 still 0 at every sample; against 1 + 1, about 3e-16 over the first 100 fluid steps,
          then growing as the bed forms on the floor (about 2e-13 at step 220, 3e-9 at 300,
          1.7e-6 at 400): the decomposed fluid's rounding, amplified by the contacts as any
          rounding is in a dense granular flow. The periodic column, quick (2026-12-07): 2 + 2
          against 1 + 1 2.2e-16, 2 + 2 against 1 + 2: 0. The fluidised bed (2026-12-07): 2 + 2
          against 1 + 2 0 over the whole run (positions and outputs); 2 + 2 and 1 + 2 against
          1 + 1 5.8e-14 at fluid step 200, 1.3e-9 at 3 000 (the bed lifting off its floor), 1.8e-6
          at the end, the largest; the three one-ulp runs reach 1.2e-5 to 1.4e-5 (2.1e-6 to 2.6e-6
          at the end): the record 0.13 (passes); the outputs of 2 + 2 within 2.4e-8 (plateau) and
          2.7e-8 (U_mf) of 1 + 1's, the one-ulp runs' within 4e-8 to 1e-7 (2026-12-07, 967 s for
          the whole case at load 7).
Produces: the records and charts cfd.mpi.parity, cfd.mpi.parity.periodic-bed and
          cfd.mpi.parity.fluidised-bed (the differences over the run, the one-ulp runs' dashed),
          and the record cfd.mpi.parity.fluidised-bed-dem-split.
"""
import json
import shutil
import subprocess
import sys
import tempfile
from pathlib import Path

import numpy as np

from talus import bench, results
from talus.coupling.case_builder import PERIODIC, Inlet, Outlet, cfd_case

SCENE = Path(__file__).resolve().parents[1] / "scenes" / "fluidised_column.py"
BED = Path(__file__).resolve().parent / "cfd_fluidised_bed.py"
L, DX, HEIGHT = 8e-3, 0.8e-3, 16e-3


def fluid_case(folder: Path, procs: int, solver: str = "volumeaveraged", column: str = "walled"):
    """The column's fluid (the mesh's walls at the DEM's; with ``column`` periodic, its x and y
    patches cyclic), decomposed into ``procs`` slabs along z, for ``solver`` (the case builder's
    name: volumeaveraged or pointforce)."""
    envelope = {"envelope": "gaussian", "envelopeWidth": 1.5e-3, "addedMassCoefficient": 0}
    sides = {"x0": PERIODIC, "y0": PERIODIC} if column == "periodic" else {}
    return cfd_case(folder, solver=solver, box=((0, 0, 0), (L, L, HEIGHT)),
                    cells=(round(L / DX), round(L / DX), round(HEIGHT / DX)), rho=1000.0, nu=1e-5,
                    gravity=(0, 0, -9.81), coupling_interval=1e-4, procs=procs, write_every=100000,
                    pressure_tolerance=1e-13, pressure_relative_tolerance=0,
                    boundaries={"z0": Inlet((0, 0, 5e-3), ramp=5e-3), "z1": Outlet(), **sides},
                    coupling_properties=envelope if solver == "volumeaveraged" else None)


def talus_run(dem: int, arguments: list[str]):
    """``talus run -j 1`` with ``arguments`` (a script and its own), in one process or under
    mpirun with ``dem`` processes; raises with the output if it fails."""
    talus = [sys.executable, "-m", "talus", "run", "-j", "1", *arguments]
    # the loopback for every process's traffic, as FoamCoupling asks for in one process
    command = talus if dem == 1 else ["mpirun", "--allow-run-as-root", "--oversubscribe", "--mca", "btl_tcp_if_include",
                                      "lo", "--mca", "oob_tcp_if_include", "lo", "-np", str(dem), *talus]
    done = subprocess.run(command, capture_output=True, text=True, timeout=3600, env=bench.child_environment())
    if done.returncode != 0:
        raise RuntimeError(f"{' '.join(command)} failed:\n{done.stdout}\n{done.stderr}")


def run(dem: int, fluid: int, steps: int, layers: int, folder: Path, solver: str = "volumeaveraged",
        drop: float = 0.0, column: str = "walled") -> dict:
    """The scene with ``dem`` processes and ``fluid`` fluid ranks (the spheres starting at ``drop``
    m/s vertically; the column walled or periodic); its JSON output."""
    name = f"run-{dem}-{fluid}-{solver}-{drop}-{column}"
    case = fluid_case(folder / name, fluid, solver, column)
    out = folder / f"{name}.json"
    talus_run(dem, [str(SCENE), str(case.path), str(fluid), str(steps), str(out), str(layers), case.solver, str(drop),
                    column])
    shutil.rmtree(case.path, ignore_errors=True)
    return json.loads(out.read_text())


def run_bed(dem: int, fluid: int, folder: Path, nudge: int | None = None) -> dict:
    """cfd_fluidised_bed.py itself, quick, with ``dem`` processes and ``fluid`` fluid ranks (and
    its sphere ``nudge`` moved by one ulp before the coupling, if given): its records (by name)
    and, as its positions, every sphere's every 200 fluid steps and at the end."""
    out = folder / f"bed-{dem}-{fluid}-{nudge}"
    out.mkdir()
    talus_run(dem, [str(BED), "--quick", "--procs", str(fluid), "--results", str(out),
                    "--trajectory", str(out / "trajectory.npy"), "--pressure-tolerance", "1e-13",
                    *([] if nudge is None else ["--nudge", str(nudge)])])
    return {"records": {r["name"]: r for r in results.read_records(out)},
            "positions": np.load(out / "trajectory.npy")}


#: The fluidised bed's outputs compared, (record, field).
BED_OUTPUTS = (("cfd.fluidised_bed.plateau", "plateau"), ("cfd.fluidised_bed.plateau", "fluid_pressure_drop"),
               ("cfd.fluidised_bed.umf", "u_mf"), ("cfd.fluidised_bed.umf", "bed_expansion"))


def compare_bed(case: results.Case, runs: dict, nudged: dict):
    """Record and chart how far the fluidised bed's positions over the run and outputs in the
    2 + 2 run (and 1 + 2) lie from the 1 + 1 run's, against how far the 1 + 1 runs with one sphere
    moved by one ulp (``nudged``, by sphere) lie from it: the reach of one rounding in this bed."""
    import matplotlib.pyplot as plt
    serial = runs[1, 1]
    pairs = {"2+2 vs 1+1": (runs[2, 2], serial), "1+2 vs 1+1": (runs[1, 2], serial),
             "2+2 vs 1+2": (runs[2, 2], runs[1, 2])}
    one_ulp = {f"1+1, sphere {k} moved 1 ulp": (r, serial) for k, r in nudged.items()}
    pairs.update(one_ulp)
    curves = {label: difference(a, b) for label, (a, b) in pairs.items()}
    largest = {label: float(c.max()) for label, c in curves.items()}
    outputs = {label: {field: abs(a["records"][name][field] - b["records"][name][field])
                       / abs(b["records"][name][field]) for name, field in BED_OUTPUTS}
               for label, (a, b) in pairs.items()}
    rounding = max(largest[label] for label in one_ulp)
    spheres = serial["positions"].shape[1]
    print(f"fluidised bed (cfd_fluidised_bed.py --quick): {spheres} spheres; 1 + 1: plateau "
          f"{serial['records']['cfd.fluidised_bed.plateau']['plateau']:.6f} Pa, U_mf "
          f"{serial['records']['cfd.fluidised_bed.umf']['u_mf']:.6e} m/s")
    for label in pairs:
        print(f"{label}: largest position difference over the run / largest coordinate {largest[label]:.3e} (at the "
              f"end {curves[label][-1]:.3e}); outputs " + ", ".join(f"{k} {v:.3e}" for k, v in outputs[label].items()))

    fig, ax = plt.subplots(figsize=(5.5, 4))
    steps = np.arange(1, len(serial["positions"]) + 1) * 200     # the last sample is the run's end
    for label, c in curves.items():
        style = {"color": "grey", "lw": 0.8, "ls": "--"} if label in one_ulp else {"marker": "o", "ms": 3}
        ax.semilogy(steps, np.maximum(c, 1e-18), label=label, **style)
    ax.set_xlabel("fluid step")
    ax.set_ylabel("max |x - x_ref| / max |x| (0 drawn at 1e-18)")
    ax.set_title("cfd_fluidised_bed.py --quick: DEM processes + fluid ranks")
    ax.legend(fontsize=6)
    case.record("largest position difference over the quick run of the fluidised-bed case run as 2 DEM processes + "
                "2 fluid ranks from its 1 + 1 run, over the largest difference that one sphere moved by one ulp "
                "makes in the 1 + 1 run (the reach of one rounding in this bed)", largest["2+2 vs 1+1"] / rounding,
                "the 1 + 1 run and its one-ulp neighbours, same invocation", 1.0, suffix="fluidised-bed",
                differences=largest, differences_at_the_end={label: float(c[-1]) for label, c in curves.items()},
                one_ulp_reach=rounding, output_differences=outputs, spheres=spheres,
                outputs={label.split(" vs ")[0]: {field: a["records"][name][field] for name, field in BED_OUTPUTS}
                         for label, (a, _) in pairs.items()})
    # the DEM's split alone: the same fluid ranks with the DEM in one process or two
    case.record("largest position difference over the quick run of the fluidised-bed case run as 2 DEM processes + "
                "2 fluid ranks from its 1 DEM process + 2 fluid ranks run, over the largest coordinate",
                largest["2+2 vs 1+2"], "the 1 + 2 run (round-off)", 1e-9, suffix="fluidised-bed-dem-split",
                differences=largest, output_differences=outputs, spheres=spheres)
    case.save_chart(fig, "fluidised-bed")


def difference(a: dict, b: dict) -> np.ndarray:
    """Per sample, the largest position difference over the largest coordinate."""
    x, y = np.asarray(a["positions"]), np.asarray(b["positions"])
    return np.abs(x - y).reshape(len(x), -1).max(axis=1) / np.abs(x).max()


def compare(case: results.Case, runs: dict, steps: int, column: str, suffix: str | None):
    """Record and chart how far the runs ``runs`` (by DEM processes and fluid ranks) of one column
    lie from the 1 + 1 run and from the 1 + 2 run."""
    import matplotlib.pyplot as plt
    serial = runs[1, 1]
    pairs = {f"{d}+{f} vs 1+1": (r, serial) for (d, f), r in runs.items() if (d, f) != (1, 1)}
    pairs["2+2 vs 1+2"] = (runs[2, 2], runs[1, 2])
    curves = {label: difference(a, b) for label, (a, b) in pairs.items()}
    samples = np.arange(len(serial["positions"])) * 20
    samples[-1] = steps
    checked = {label: float(c[samples <= 100].max()) for label, c in curves.items()}
    worst = {label: float(c.max()) for label, c in curves.items()}
    lift = np.asarray(serial["lift"])
    spheres = len(serial["positions"][0]) - (5 if column == "walled" else 2)   # less the walls
    print(f"{column} column: {spheres} spheres, {steps} fluid steps x {serial['substeps']} DEM steps; "
          f"hydrodynamic lift {lift[0]:.3e} .. {lift[-1]:.3e} N")
    for label, value in worst.items():
        print(f"{label}: largest position difference / largest coordinate {checked[label]:.3e} over the first 100 "
              f"fluid steps, {value:.3e} over the run")
    for (d, f), r in runs.items():
        print(f"{d} + {f}: per DEM process, particles and messages of the last exchange {r['processes']}")

    fig, ax = plt.subplots(figsize=(5.5, 4))
    for label, c in curves.items():
        ax.semilogy(samples, np.maximum(c, 1e-18), "o-", ms=3, label=label)
    ax.axhline(1e-9, color="grey", lw=0.8, ls=":", label="checked bound (first 100 fluid steps)")
    ax.set_xlabel("fluid step")
    ax.set_ylabel("max |x - x_ref| / max |x| (0 drawn at 1e-18)")
    ax.set_title("Coupled fluidised column" + (" (periodic bed)" if column == "periodic" else "")
                 + ": DEM processes + fluid ranks")
    ax.legend(fontsize=7)
    case.record("largest position difference of the 2 DEM + 2 fluid ranks run from the 1 + 1 run over the first "
                "100 fluid steps, over the largest coordinate", checked["2+2 vs 1+1"], "the 1 + 1 run (round-off)", 1e-9,
                suffix=suffix, differences=checked, differences_over_the_run=worst, spheres=spheres,
                fluid_steps=steps, processes={f"{d}+{f}": r["processes"] for (d, f), r in runs.items()})
    case.save_chart(fig, suffix)


def main():
    args = results.case_arguments(__doc__).parse_args()
    import matplotlib
    matplotlib.use("Agg")
    case = results.Case("cfd.mpi.parity", quick=args.quick, folder=args.results)
    steps, layers = (100, 8) if args.quick else (400, 12)
    with tempfile.TemporaryDirectory() as tmp:
        walled = {(d, f): run(d, f, steps, layers, Path(tmp)) for d, f in [(1, 1), (1, 2), (2, 1), (2, 2)]}
        compare(case, walled, steps, "walled", None)
        periodic = {(d, f): run(d, f, steps, layers, Path(tmp), column="periodic") for d, f in [(1, 1), (1, 2), (2, 2)]}
        compare(case, periodic, steps, "periodic", "periodic-bed")
        bed = {(d, f): run_bed(d, f, Path(tmp)) for d, f in [(1, 1), (1, 2), (2, 2)]}
        spheres = bed[1, 1]["positions"].shape[1]
        compare_bed(case, bed, {k: run_bed(1, 1, Path(tmp), nudge=k) for k in (0, spheres // 2, spheres - 1)})


if __name__ == "__main__":
    main()
