"""The step with other engines: the DEM part of a step with a PyRunner, a VANS coupling or a pore
flow against the plain step of the same bed.

Run:      OMP_NUM_THREADS=2 build/bin/talus run -j 2 cases/bench/dem_bench_pipeline.py [--quick] [--results DIR]
Scene:    case 11's dense bed (cases/bench/11_bench_dense.py: a lattice of spheres of radius 5 mm, linear
          Cundall-Strack, Cundall damping 0.2) closed by a sixth wall on top, at two threads.
          Variants, each a scene of its own built from the same packing:
          - plain: ForceResetter, InsertionSortCollider, InteractionLoop, NewtonIntegrator;
          - pyrunner: the same and a PyRunner every 100 steps after the integrator;
          - vans: a HydroForceEngine (buoyancy and drag of a sheared water profile on every
            sphere) between the loop and the integrator;
          - poreflow: a FlowEngine (pressure 1 Pa at the bottom, 0 at the top, no remeshing while
            timed) between the loop and the integrator.
          The DEM part of a step is its wall time less the time its other engines took
          (Scene.fusedOtherEnginesSeconds, measured around each of them in the same steps).
          The pore flow's solve (seconds at 32 000 spheres) evicts the bed from the caches, so
          the DEM part of its step is also compared with the same scene's engines one by one
          (Yade's sub-steps, each engine's own run(), timed: the sum of ForceResetter's, the
          collider's, the loop's and the integrator's times), which start as cold.
Compared: 32 000 spheres (quick: 8 000), 100 timed steps per run (quick: 50; poreflow: a tenth,
          its solve dominates), the variants in turn after an untimed run each, 3 rounds (quick:
          1); medians.
Produces: dem.bench.pipeline: the larger ratio of the pyrunner and vans variants' DEM part to
          the plain step (target <= 1.05: they do not leave the fused step), with every
          variant's times in the record; dem.bench.pipeline-poreflow: the pore-flow step's DEM
          part fused over one by one (target <= 1.05), its ratio to the warm plain step an
          extra.
"""
import importlib.util
import os
import statistics
import tempfile
import time
from pathlib import Path

from talus import results
from talus.dem import (ForceResetter, FrictMat, InsertionSortCollider, InteractionLoop, Ip2_FrictMat_FrictMat_FrictPhys,
                       Law2_ScGeom_FrictPhys_CundallStrack, NewtonIntegrator, PyRunner, Scene, sphere, wall)
from talus.flow import FlowEngine, HydroForceEngine

HERE = Path(__file__).resolve().parent
_spec = importlib.util.spec_from_file_location("bench_dense", HERE / "11_bench_dense.py")
bench_dense = importlib.util.module_from_spec(_spec)
_spec.loader.exec_module(bench_dense)
VARIANTS = ("plain", "pyrunner", "vans", "poreflow")


def bed(packing: Path, variant: str) -> tuple[Scene, object]:
    """The bed of `packing` with the variant's engines; returns the scene and its extra engine."""
    S = Scene()
    with open(packing) as source:
        dt, young, density, box_x, box_y = (float(v) for v in source.readline().split())
        spheres = [tuple(float(v) for v in line.split()) for line in source if line.strip()]
    mat = S.materials.append(FrictMat(young=young, poisson=0.3, frictionAngle=0.5, density=density))
    ids = S.bodies.append([sphere((x, y, z), r, material=mat) for x, y, z, r in spheres])
    radius = spheres[0][3]
    top = max(z for _, _, z, _ in spheres) + radius
    walls = S.bodies.append([wall(0, axis=0, sense=1), wall(box_x, axis=0, sense=-1), wall(0, axis=1, sense=1),
                             wall(box_y, axis=1, sense=-1), wall(0, axis=2, sense=1), wall(top, axis=2, sense=-1)])
    engines = [ForceResetter(), InsertionSortCollider(),
               InteractionLoop([], [Ip2_FrictMat_FrictMat_FrictPhys()], [Law2_ScGeom_FrictPhys_CundallStrack()])]
    extra = None
    if variant == "vans":
        dz = 2 * radius
        cells = int(top / dz) + 2
        extra = HydroForceEngine(densFluid=1000, viscoDyn=1e-3, zRef=0, gravity=(0, 0, -9.81), deltaZ=dz, expoRZ=3.1,
                                 lift=False, nCell=cells, vCell=box_x * box_y * dz, radiusPart=radius, phiMax=0.61,
                                 ids=ids, scene=S)
        extra.vxFluid = [0.01 * k for k in range(cells + 1)]
        extra.averageProfile()
    elif variant == "poreflow":
        extra = FlowEngine(bndCondIsPressure=[0, 0, 0, 0, 1, 1], bndCondValue=[0, 0, 0, 0, 1, 0], wallIds=walls,
                           meshUpdateInterval=10 ** 9, viscosity=1e-3, scene=S)
    engines += [extra] if extra is not None else []
    engines.append(NewtonIntegrator(damping=0.2, gravity=(0, 0, -9.81)))
    if variant == "pyrunner":
        engines.append(PyRunner(command="pass", iterPeriod=100))
    S.engines = engines
    S.dt = dt
    S.run(1, wait=True)       # contacts (and the pore mesh) built before any timing
    return S, extra


def engines_one_by_one(S: Scene, extra, steps: int) -> float:
    """Seconds per step of the DEM's own engines (all but `extra`) run one by one (Yade's
    sub-steps: each engine's own run(), a step being the engines' count plus two), timed."""
    S.timingEnabled = True
    S.subStepping = True
    for engine in S.engines:
        engine.execTime = 0
    for _ in range(steps * (len(S.engines) + 2)):
        S.step()
    S.subStepping = False
    S.timingEnabled = False
    return sum(engine.execTime for engine in S.engines if engine is not extra) / 1e9 / steps


def main():
    args = results.case_arguments(__doc__).parse_args()
    n, steps, rounds = (8000, 50, 1) if args.quick else (32000, 100, 3)
    threads = int(os.environ.get("OMP_NUM_THREADS", "2"))
    case = results.Case("dem.bench", quick=args.quick, folder=args.results)
    with tempfile.TemporaryDirectory() as folder:
        packing = Path(folder) / "bed.txt"
        count = bench_dense.write_packing(packing, n)
        scenes = {v: bed(packing, v) for v in VARIANTS}
    runs = {v: max(2, steps // 10) if v == "poreflow" else steps for v in VARIANTS}
    samples = {v: [] for v in VARIANTS}
    own_samples = {v: [] for v in VARIANTS}
    for v, (S, _) in scenes.items():    # an untimed run each: the first timed one came out slower
        S.run(runs[v], wait=True)
    one_by_one = []   # the pore-flow step's DEM part with the engines one by one
    for _ in range(rounds):
        for v, (S, extra) in scenes.items():
            start, other = time.perf_counter(), S.fusedOtherEnginesSeconds
            S.run(runs[v], wait=True)
            seconds = time.perf_counter() - start
            own_samples[v].append((S.fusedOtherEnginesSeconds - other) / runs[v])
            samples[v].append((seconds - (S.fusedOtherEnginesSeconds - other)) / runs[v])
            if v == "poreflow":
                one_by_one.append(engines_one_by_one(S, extra, runs[v]))
    dem = {v: statistics.median(samples[v]) for v in VARIANTS}
    own = {v: statistics.median(own_samples[v]) for v in VARIANTS}
    step = {v: dem[v] + own[v] for v in VARIANTS}
    ratios = {v: dem[v] / dem["plain"] for v in VARIANTS}
    for v in VARIANTS:
        print(f"{v:9s} step {step[v] * 1e3:9.3f} ms   other engines {own[v] * 1e3:9.3f} ms   DEM part "
              f"{dem[v] * 1e3:8.3f} ms = {ratios[v]:.3f} x plain   fused steps {scenes[v][0].fusedSteps}")
    cold = statistics.median(one_by_one)
    print(f"poreflow DEM part with the engines one by one {cold * 1e3:.3f} ms: fused / one by one = "
          f"{dem['poreflow'] / cold:.3f}")
    worst = max(ratios["pyrunner"], ratios["vans"])
    case.record(f"{count} spheres, {threads} threads: larger DEM part of a step with a PyRunner or a VANS coupling "
                "over the plain step", worst, "the plain step of the same bed, same invocation", 1.05,
                suffix="pipeline", spheres=count, threads=threads, steps=runs, step_seconds=step,
                other_engines_seconds=own, ratios=ratios, fused_steps={v: scenes[v][0].fusedSteps for v in VARIANTS})
    case.record(f"{count} spheres, {threads} threads: DEM part of a pore-flow step, fused over the engines one by one",
                dem["poreflow"] / cold, "the same scene's engines one by one (sub-steps, timed), same invocation", 1.05,
                suffix="pipeline-poreflow", spheres=count, threads=threads, fused_seconds=dem["poreflow"],
                one_by_one_seconds=cold, over_warm_plain_step=ratios["poreflow"])


if __name__ == "__main__":
    main()
