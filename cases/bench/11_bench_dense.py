"""Case 11: a dense, contact-dominated bed against Yade and LIGGGHTS; cost per particle-step from
1 000 to 200 000 spheres.

Run:      build/bin/talus run cases/bench/11_bench_dense.py [--quick] [--results DIR]
Scene:    N spheres (radius 5 mm, density 2600, FrictMat young 1e7, poisson 0.3, friction 0.5 rad)
          on a simple cubic lattice of spacing 2r(1 - 1e-4), with a deterministic jitter of
          1e-5 r, resting on the floor of a five-wall box under gravity: about three contacts per
          sphere (coordination near six), the contacts loaded by the weight of the columns.
          Linear Cundall-Strack with Coulomb friction, Cundall damping 0.2, dt = 0.5 P-wave step,
          Verlet skin half a radius. One step to build the contacts, then timed steps.
          The scene is cases/scenes/dense_bed.py, one file run by Talus and by Yade; LIGGGHTS
          (Debian's liggghts 3.8) runs the same packing with Hooke-with-history in its stiffness
          form (the same linear normal and tangential springs kn = E r, kt = 0.3 kn, Coulomb friction; its viscous damping replaces Cundall's,
          which it lacks) and skin 0.5 r.
Compared: 20 000 spheres (quick: 8 000), 200 timed steps (quick: 100), alternately with the peer
          in one invocation, 3 runs each (quick: 1); medians of the seconds per timed run.
Produces: dem.bench.dense-yade (Talus over Yade, target >= 5), dem.bench.dense-liggghts (Talus
          over LIGGGHTS, target >= 1: the real bar of ANCHORS.md), dem.bench.cost-per-particle
          (largest over smallest ns per particle-step from 1k to 200k spheres, quick 1k to 32k,
          medians of 3 runs per size, 1 in quick mode, CPU time of the timed steps; target <= 1.5:
          no super-linear growth) and
          the chart dem.bench.cost-per-particle.png.
"""
import math
import os
import shutil
import statistics
import tempfile
from pathlib import Path

import numpy as np

from talus import bench, results

import dem_bench_kinds   # the LIGGGHTS input of the dense bed, shared with its kinds

HERE = Path(__file__).resolve().parent
SCENE = HERE.parent / "scenes" / "dense_bed.py"
RADIUS, DENSITY, YOUNG = 0.005, 2600.0, 1e7


def bed_shape(n: int) -> tuple[int, int, int]:
    """A box of about n spheres, twice as wide as high (nx = ny = 2 nz)."""
    nz = max(2, round((n / 4) ** (1 / 3)))
    nx = max(2, round(math.sqrt(n / nz)))
    return nx, nx, nz


def bed_lattice(n: int) -> tuple[np.ndarray, float, float, float]:
    """The lattice of about n spheres: (centres, time step, box_x, box_y)."""
    nx, ny, nz = bed_shape(n)
    spacing = 2 * RADIUS * (1 - 1e-4)
    rng = np.random.default_rng(12345)
    i, j, k = np.meshgrid(np.arange(nx), np.arange(ny), np.arange(nz), indexing="ij")
    centres = np.stack([i.ravel(), j.ravel(), k.ravel()], axis=1) * spacing + RADIUS
    centres += rng.uniform(-1e-5, 1e-5, centres.shape) * RADIUS
    dt = 0.5 * RADIUS * math.sqrt(DENSITY / YOUNG)
    return centres, dt, nx * spacing + 2 * RADIUS * 1e-4, ny * spacing + 2 * RADIUS * 1e-4


def write_packing(path: Path, n: int) -> int:
    """Write the lattice of about n spheres in dense_bed.py's format; return the sphere count."""
    centres, dt, box_x, box_y = bed_lattice(n)
    with open(path, "w") as out:
        out.write(f"{dt!r} {YOUNG!r} {DENSITY!r} {box_x!r} {box_y!r}\n")
        for x, y, z in centres:
            out.write(f"{x!r} {y!r} {z!r} {RADIUS!r}\n")
    return len(centres)


def talus_seconds_per_step(n: int, steps: int, folder: Path) -> float:
    packing = folder / f"bed-{n}.txt"
    count = write_packing(packing, n)
    # CPU seconds (the scene's fourth figure): the machine is shared, and only Talus's own
    # sizes are compared.
    side = bench.Side(f"talus N={count}", bench.talus_command("run", str(SCENE), str(packing), str(steps)),
                      r"TIMED \d+ \S+ \S+ ([0-9.e+-]+)")
    return bench.run_once(side, 3600) / steps, count


def main():
    args = results.case_arguments(__doc__).parse_args()
    quick = args.quick
    n_compare, steps, repeat = (8000, 100, 1) if quick else (20000, 200, 3)
    os.environ["OMP_NUM_THREADS"] = "1"
    with tempfile.TemporaryDirectory(prefix="talus-dense-") as scratch:
        folder = Path(scratch)
        packing = folder / "bed.txt"
        count = write_packing(packing, n_compare)
        figure = r"TIMED \d+ ([0-9.e+-]+)"
        ours = bench.Side("talus -j1", bench.talus_command("run", str(SCENE), str(packing), str(steps)), figure)
        peers = []
        if shutil.which("yade"):
            peers.append(("yade", bench.Side("yade -j1", ["yade", "-n", "-j1", "-x", str(SCENE), str(packing), str(steps)],
                                              figure, cwd=scratch), 5.0))
        if shutil.which("liggghts"):
            script = dem_bench_kinds.dense_liggghts_script(folder, "bed", packing, dem_bench_kinds.linear_model(), steps)
            peers.append(("liggghts", bench.Side("liggghts", ["liggghts", "-in", str(script), "-log", "none"],
                                                  r"Loop time of ([0-9.e+-]+) on", cwd=scratch), 1.0))
        if not peers:
            print("neither yade nor liggghts is installed: no comparison recorded")
        case = results.Case("dem.bench", quick=quick, folder=args.results)
        for name, peer, target in peers:
            ours.samples.clear()
            c = bench.compare(ours, peer, repeat=repeat, unit="s")
            per_step = 1e9 / (count * steps)
            case.record(f"{count} spheres, {steps} steps: Talus speed over {name}, 1 thread", c.ratio,
                        f"{peer.label} on the same packing, same invocation", target, comparison=">=",
                        suffix=f"dense-{name}", peer=peer.label, ours=c.ours * per_step,
                        theirs=c.theirs * per_step, ratio=c.ratio, unit="ns per particle-step")
            print(f"{name}: Talus {c.ours * per_step:.0f} ns, {name} {c.theirs * per_step:.0f} ns per "
                  f"particle-step: {c.ratio:.2f}x")

        sizes = [1000, 4000, 16000, 32000] if quick else [1000, 4000, 16000, 64000, 200000]
        # Each size `repeat` times, the sizes in turn, and the median per size: one run of the
        # smallest bed lasts about a second, and a single one can come out much slower than its
        # neighbours when the host takes the vCPU for a moment (docs/dem.md, "Measurements behind
        # the code").
        samples: dict[int, list[float]] = {}
        for _ in range(repeat):
            for n in sizes:
                seconds, count_n = talus_seconds_per_step(n, max(20, int(4e6 / n)) if not quick else max(10, int(1e6 / n)), folder)
                samples.setdefault(count_n, []).append(1e9 * seconds / count_n)
        costs = [(count_n, statistics.median(values)) for count_n, values in samples.items()]
        for count_n, cost in costs:
            print(f"N={count_n}: {cost:.1f} ns per particle-step (median of {len(samples[count_n])})")
    spread = max(c for _, c in costs) / min(c for _, c in costs)
    case.record("largest over smallest cost per particle-step", spread,
                f"Talus, {costs[0][0]} to {costs[-1][0]} spheres", 1.5, comparison="<=",
                suffix="cost-per-particle", sizes=[n for n, _ in costs], ns_per_particle_step=[c for _, c in costs])
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, ax = plt.subplots(figsize=(6, 4))
    ax.semilogx([n for n, _ in costs], [c for _, c in costs], "o-", label="Talus, 1 thread")
    ax.set_xlabel("spheres")
    ax.set_ylabel("ns per particle-step")
    ax.set_ylim(bottom=0)
    ax.grid(True, which="both", alpha=0.3)
    ax.set_title("Dense bed: cost per particle-step")
    ax.legend()
    case.save_chart(fig, "cost-per-particle")


if __name__ == "__main__":
    main()
