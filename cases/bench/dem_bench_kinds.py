"""DEM speed by kind of scene: Talus against Yade and LIGGGHTS, one thread each, per core.

Run:      build/bin/talus run cases/bench/dem_bench_kinds.py [--quick] [--only NAME] [--results DIR]
          [--chart-from DIR] (the chart alone, from the records of kinds run one at a time)
Kinds:    each a scene script under cases/scenes/ run unchanged by `talus run` and `yade -n -j1 -x`
          on a packing this case writes (radius 5 mm, density 2600, young 1e7, poisson 0.3,
          friction 0.5 rad; dt half the P-wave step of the smallest sphere):
          dense-linear, dense-hertz, dense-viscoelastic, dense-cohesive  the dense bed of case 11
                 (scenes/dense_bed.py, a lattice bed in a five-wall box) with each contact law;
          silo   a square facet silo (16 triangles) discharging through a floor orifice six
                 diameters wide, Hertz-Mindlin, the fallen spheres erased by a PyRunner every
                 100 steps (scenes/silo.py); the fill first settled with the orifice plugged
                 (12 000 steps, quick 3 000, of Talus);
          drum   a closed cylinder of 96 facets turned by a RotationEngine at 1 rad/s, its lower
                 part filled with a bed first settled (12 000 steps, quick 3 000, of Talus with
                 the drum at rest), linear law (scenes/drum.py);
          peri-triax  a periodic cloud compacted to 100 kPa by PeriTriaxController (scenes/peri_triax.py);
          rve    400 spheres in a periodic cell (a jittered fcc packing, 5 x 5 x 4 unit cells), driven in calls of 100
                 steps with a velocity gradient and a getStress each, as FEM x DEM Gauss points
                 are (scenes/rve.py).
          LIGGGHTS 3.8 (Debian's liggghts) runs the kinds it has the model for, on the same
          packing and triangles (an STL file): the linear law and the visco-elastic one as
          hooke/stiffness with history (kn, kt of Yade's laws; it has no Cundall damping, so the
          linear bed has a viscous damping of 0.2 of the critical one instead), Hertz-Mindlin as
          hertz with history (restitution 0.5 in place of Cundall damping), the silo's fallen atoms
          lost through the box's floor, the drum's mesh turned by fix move/mesh. It has no
          cohesive-frictional law with moments, no PeriTriaxController, no call-by-call RVE.
Timing:   the machine is shared, so every figure is CPU time over the timed steps only: each
          scene script prints its process's process_time() around them; LIGGGHTS reads its own
          utime + stime from /proc around its timed run (a `shell` command, 10 ms ticks).
          OMP_NUM_THREADS=1, yade -j1, one MPI rank of LIGGGHTS. Rounds run Talus, Yade, LIGGGHTS
          in turn (3 rounds, quick 1); medians; ns per particle-step use the initial sphere count.
Produces: dem.bench.kind.<name>-yade (Talus over Yade, target >= 5; >= 10 for the rve) and
          dem.bench.kind.<name>-liggghts (target >= 1.5), each with the three ns per particle-step
          and Talus's fused-step count; the chart dem.bench.kind.png.
"""
import importlib
import json
import math
import os
import re
import shutil
import sys
import tempfile
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from talus import bench, results

HERE = Path(__file__).resolve().parent
SCENES = HERE.parent / "scenes"
RADIUS, DENSITY, YOUNG = 0.005, 2600.0, 1e7
YADE_TARGET, RVE_TARGET, LIGGGHTS_TARGET = 5.0, 10.0, 1.5
CPU = r"TIMED \d+ \S+ \S+ ([0-9.e+-]+)"
LIGGGHTS_CPU = r"CPUSECONDS ([0-9.e+-]+)"
# Prints the CPU seconds LIGGGHTS (the nearest ancestor process of that name) used since `start`.
CPU_PROBE = """p=$$
while [ "$p" -gt 1 ]; do
  if [ "$(cat /proc/$p/comm)" = liggghts ]; then break; fi
  p=$(awk '{print $4}' /proc/$p/stat)
done
ticks=$(awk '{print $14 + $15}' /proc/$p/stat)
if [ "$1" = start ]; then echo "$ticks" > "$(dirname "$0")/cpu.start"
else awk -v t="$ticks" -v s="$(cat "$(dirname "$0")/cpu.start")" -v hz="$(getconf CLK_TCK)" \
  'BEGIN {print "CPUSECONDS", (t - s) / hz}'; fi
"""


def time_step(radii) -> float:
    return 0.5 * min(radii) * math.sqrt(DENSITY / YOUNG)


def lattice(shape, spacing, rng, jitter):
    """Centres of a simple cubic lattice (shape = counts along x, y, z) from spacing/2, jittered."""
    i, j, k = np.meshgrid(*(np.arange(n) for n in shape), indexing="ij")
    centres = (np.stack([i.ravel(), j.ravel(), k.ravel()], axis=1) + 0.5) * spacing
    return centres + rng.uniform(-jitter, jitter, centres.shape)


def rectangle(a, b, c, d):
    """Two triangles of the quadrilateral a b c d."""
    return [(a, b, c), (a, c, d)]


def write_facet_packing(path: Path, header, triangles, spheres) -> None:
    with open(path, "w") as out:
        out.write(" ".join(repr(float(v)) for v in header) + "\n")
        for t in triangles:
            out.write("F " + " ".join(repr(float(v)) for p in t for v in p) + "\n")
        for s in spheres:
            out.write("S " + " ".join(repr(float(v)) for v in s) + "\n")


def write_sphere_packing(path: Path, header, spheres) -> None:
    with open(path, "w") as out:
        out.write(" ".join(repr(float(v)) for v in header) + "\n")
        for s in spheres:
            out.write(" ".join(repr(float(v)) for v in s) + "\n")


def settled(path: Path, scene: str, header, triangles, spheres, steps: int):
    """The spheres after `steps` steps of Talus running the scene on them (its SAVE argument):
    a lattice collapses into a bed that takes longer than the timed steps to come to rest, and
    the benchmarks time a silo discharging and a drum turning a bed."""
    fill = path.with_suffix(".fill")
    write_facet_packing(fill, header, triangles, spheres)
    bench.run_once(bench.Side(f"talus settling {scene}", bench.talus_command(
        "run", "-j", "1", str(SCENES / scene), str(fill), str(steps), str(path)), CPU), 3600)
    return np.array([[float(v) for v in line.split()[1:]] for line in path.read_text().splitlines()])


def silo_packing(path: Path, n: int, settle: int):
    """A square silo about ten layers of n spheres deep (radii 0.9-1 r on a lattice of 2.1 r)
    settled by `settle` steps with its orifice plugged, the orifice six diameters wide; spheres
    erased 4 r below the floor."""
    rng = np.random.default_rng(7)
    spacing = 2.1 * RADIUS
    side = max(8, math.ceil(math.sqrt(n / 10)))
    layers = math.ceil(n / side**2)
    centres = lattice((side, side, layers), spacing, rng, 0.05 * RADIUS)[:n]
    radii = RADIUS * rng.uniform(0.9, 1.0, len(centres))
    width, height = side * spacing, 1.3 * layers * spacing
    a, b = (width - 12 * RADIUS) / 2, (width + 12 * RADIUS) / 2
    tri = []
    for x in (0.0, width):
        tri += rectangle((x, 0, 0), (x, width, 0), (x, width, height), (x, 0, height))
    for y in (0.0, width):
        tri += rectangle((0, y, 0), (width, y, 0), (width, y, height), (0, y, height))
    for x0, x1, y0, y1 in ((0, width, 0, a), (0, width, b, width), (0, a, a, b), (b, width, a, b)):
        tri += rectangle((x0, y0, 0), (x1, y0, 0), (x1, y1, 0), (x0, y1, 0))
    header = (time_step(radii), YOUNG, DENSITY, -4 * RADIUS)
    plug = rectangle((a, a, 0), (b, a, 0), (b, b, 0), (a, b, 0))
    spheres = settled(path, "silo.py", header, tri + plug, np.column_stack([centres, radii]), settle)
    write_facet_packing(path, header, tri, spheres)
    return len(spheres), tri, spheres, (0.0, width, 0.0, width, -4 * RADIUS, height)


OMEGA = 1.0


def drum_packing(path: Path, n: int, settle: int):
    """A closed drum (axis z, 24 segments) whose lower 45 % holds n spheres in eight layers
    along its axis (radii 0.9-1 r on a lattice of 2.1 r), settled by `settle` steps with the drum
    at rest."""
    rng = np.random.default_rng(11)
    spacing, layers, segments = 2.1 * RADIUS, 8, 24
    radius = spacing * math.sqrt(n / (layers * 0.45 * math.pi)) + 2 * spacing
    length = layers * spacing
    side = math.ceil(2 * radius / spacing)
    centres = lattice((side, side, layers), spacing, rng, 0.05 * RADIUS) - (radius, radius, length / 2)
    # Clear of the facets, which are chords of the circle.
    rim_gap = radius * math.cos(math.pi / segments) - 1.2 * RADIUS
    inside = (np.hypot(centres[:, 0], centres[:, 1]) < rim_gap) & (centres[:, 1] < 0.3 * radius)
    centres = centres[inside][np.argsort(centres[inside][:, 1], kind="stable")][:n]
    radii = RADIUS * rng.uniform(0.9, 1.0, len(centres))
    rim = [(radius * math.cos(2 * math.pi * s / segments), radius * math.sin(2 * math.pi * s / segments))
           for s in range(segments + 1)]
    lo, hi = -length / 2, length / 2
    tri = []
    for (x0, y0), (x1, y1) in zip(rim, rim[1:]):
        tri += rectangle((x0, y0, lo), (x1, y1, lo), (x1, y1, hi), (x0, y0, hi))
        tri += [((0, 0, lo), (x1, y1, lo), (x0, y0, lo)), ((0, 0, hi), (x0, y0, hi), (x1, y1, hi))]
    spheres = settled(path, "drum.py", (time_step(radii), YOUNG, DENSITY, 0.0), tri,
                      np.column_stack([centres, radii]), settle)
    write_facet_packing(path, (time_step(radii), YOUNG, DENSITY, OMEGA), tri, spheres)
    m = 1.01 * radius
    return len(spheres), tri, spheres, (-m, m, -m, m, lo - 0.01 * length, hi + 0.01 * length)


def cloud_packing(path: Path, n: int):
    """A periodic cloud: radii 0.7-1.3 r (Yade's rRelFuzz 0.3) on a lattice of 2.4 r."""
    rng = np.random.default_rng(3)
    side = round(n ** (1 / 3))
    spacing = 2.4 * RADIUS
    centres = lattice((side,) * 3, spacing, rng, 0.1 * RADIUS)
    radii = RADIUS * rng.uniform(0.7, 1.3, len(centres))
    write_sphere_packing(path, (time_step(radii), YOUNG, DENSITY, side * spacing), np.column_stack([centres, radii]))
    return len(centres)


def rve_packing(path: Path):
    """400 spheres on an fcc lattice of 5 x 5 x 4 unit cells in a periodic cell, centres jittered
    by 1 % of r and radii from 0.998 to 1.004 of the touching radius: most of the 12 contacts per
    sphere are closed and loaded."""
    rng = np.random.default_rng(5)
    cells = (5, 5, 4)
    a = 2 * math.sqrt(2) * RADIUS
    basis = np.array([[0, 0, 0], [0.5, 0.5, 0], [0.5, 0, 0.5], [0, 0.5, 0.5]]) * a
    corners = lattice(cells, a, rng, 0.0) - a / 2
    centres = (corners[:, None, :] + basis[None, :, :]).reshape(-1, 3) + 0.25 * a
    centres += rng.uniform(-0.01, 0.01, centres.shape) * RADIUS
    radii = RADIUS * rng.uniform(0.998, 1.004, len(centres))
    write_sphere_packing(path, (time_step(radii), YOUNG, DENSITY, *(c * a for c in cells)),
                         np.column_stack([centres, radii]))
    return len(centres)


# LIGGGHTS: the data file, the models and the walls.

def liggghts_data(path: Path, spheres, box) -> None:
    with open(path, "w") as out:
        out.write(f"LIGGGHTS data file\n\n{len(spheres)} atoms\n1 atom types\n\n")
        out.write(f"{box[0]!r} {box[1]!r} xlo xhi\n{box[2]!r} {box[3]!r} ylo yhi\n{box[4]!r} {box[5]!r} zlo zhi\n\nAtoms\n\n")
        for n, (x, y, z, r) in enumerate(spheres, start=1):
            out.write(f"{n} 1 {2 * r!r} {DENSITY!r} {x!r} {y!r} {z!r}\n")


def write_stl(path: Path, triangles) -> None:
    with open(path, "w") as out:
        out.write("solid mesh\n")
        for t in triangles:
            out.write("facet normal 0 0 0\nouter loop\n")
            for p in t:
                out.write(f"vertex {p[0]!r} {p[1]!r} {p[2]!r}\n")
            out.write("endloop\nendfacet\n")
        out.write("endsolid mesh\n")


def hooke_model(kn: float, kt: float, gamman: float, gammat: float) -> tuple[str, str]:
    """hooke/stiffness with history: spring stiffnesses and damping per unit effective mass."""
    return "hooke/stiffness", f"""fix m1 all property/global kn peratomtypepair 1 {kn!r}
fix m2 all property/global kt peratomtypepair 1 {kt!r}
fix m3 all property/global gamman peratomtypepair 1 {gamman!r}
fix m4 all property/global gammat peratomtypepair 1 {gammat!r}
fix m5 all property/global coefficientFriction peratomtypepair 1 {math.tan(0.5)!r}
"""


def linear_model():
    """Yade's linear law for equal spheres (kn = E r, ks = 0.3 kn) with a viscous damping of 0.2
    of the critical one per contact in place of Cundall's (as case 11)."""
    kn = YOUNG * RADIUS
    mass = DENSITY * 4 / 3 * math.pi * RADIUS**3
    gamma = 2 * 0.2 * math.sqrt(kn / (mass / 2))
    return hooke_model(kn, 0.3 * kn, gamma, gamma)


def viscoelastic_model():
    """Yade's ViscElPhys for the dense bed's contact time and en = et = 0.3, per unit mass."""
    mass = DENSITY * 4 / 3 * math.pi * RADIUS**3
    tc = math.pi / math.sqrt(YOUNG * RADIUS / (mass / 2))
    log_e = math.log(0.3)
    kn = (math.pi**2 + log_e**2) / tc**2 * mass / 2
    return hooke_model(kn, 2 / 7 * kn, -2 * log_e / tc, -2 / 7 * 2 * log_e / tc)


def hertz_model():
    return "hertz", f"""fix m1 all property/global youngsModulus peratomtype {YOUNG!r}
fix m2 all property/global poissonsRatio peratomtype 0.3
fix m3 all property/global coefficientRestitution peratomtypepair 1 0.5
fix m4 all property/global coefficientFriction peratomtypepair 1 {math.tan(0.5)!r}
"""


def liggghts_script(folder: Path, name: str, spheres, box, dt: float, model, walls: str, gravity: str,
                    steps: int) -> Path:
    """The input script of one kind: the atoms, the model, the walls and the timed run between
    two CPU probes."""
    data = folder / f"{name}.data"
    liggghts_data(data, spheres, box)
    probe = folder / "cpu_probe.sh"
    probe.write_text(CPU_PROBE)
    style, properties = model
    walls = walls.replace("MODEL", f"model {style} tangential history")
    script = folder / f"in.{name}"
    script.write_text(f"""atom_style granular
atom_modify map array
boundary f f f
newton off
communicate single vel yes
units si
read_data {data}
neighbor {0.5 * RADIUS} bin
neigh_modify delay 0
{properties}pair_style gran model {style} tangential history
pair_coeff * *
timestep {dt!r}
fix gravity all gravity 9.81 vector {gravity}
{walls}fix integrate all nve/sphere
thermo_style custom step atoms
thermo 100000
thermo_modify lost ignore norm no
run 1
shell sh {probe} start
run {steps}
shell sh {probe} stop
""")
    return script


def dense_walls(box_x: float, box_y: float) -> str:
    return "".join(f"fix {name} all wall/gran MODEL primitive type 1 {plane} {at!r}\n" for name, plane, at in
                   (("floor", "zplane", 0.0), ("xlo", "xplane", 0.0), ("xhi", "xplane", box_x),
                    ("ylo", "yplane", 0.0), ("yhi", "yplane", box_y)))


def dense_liggghts_script(folder: Path, name: str, packing: Path, model, steps: int) -> Path:
    """The dense bed of a packing file of case 11 (scenes/dense_bed.py's format) for LIGGGHTS:
    its five walls, gravity along -z and `model`."""
    lines = packing.read_text().splitlines()
    dt, _, _, box_x, box_y = (float(v) for v in lines[0].split())
    spheres = np.array([[float(v) for v in line.split()] for line in lines[1:]])
    box = (0.0, box_x, 0.0, box_y, 0.0, spheres[:, 2].max() + 4 * RADIUS)
    return liggghts_script(folder, name, spheres, box, dt, model, dense_walls(box_x, box_y), "0.0 0.0 -1.0", steps)


def mesh_walls(stl: Path, motion: str = "") -> str:
    return (f"fix mesh all mesh/surface file {stl} type 1\n{motion}"
            "fix walls all wall/gran MODEL mesh n_meshes 1 meshes mesh\n")


@dataclass
class Kind:
    name: str
    scene: str
    target: float
    what: str


KINDS = [Kind("dense-linear", "dense_bed.py", YADE_TARGET, "dense bed, linear Cundall-Strack"),
         Kind("dense-hertz", "dense_bed.py", YADE_TARGET, "dense bed, Hertz-Mindlin"),
         Kind("dense-viscoelastic", "dense_bed.py", YADE_TARGET, "dense bed, visco-elastic"),
         Kind("dense-cohesive", "dense_bed.py", YADE_TARGET, "dense bed, cohesive-frictional with moments"),
         Kind("silo", "silo.py", YADE_TARGET, "facet silo discharging, Hertz-Mindlin, spheres erased"),
         Kind("drum", "drum.py", YADE_TARGET, "rotating facet drum, linear law"),
         Kind("peri-triax", "peri_triax.py", YADE_TARGET, "periodic compaction, PeriTriaxController"),
         Kind("rve", "rve.py", RVE_TARGET, "periodic RVE of 400 spheres, 100-step calls")]


def prepare(kind: Kind, folder: Path, quick: bool):
    """Write the kind's packing (and LIGGGHTS input where it has the model); return the scene's
    arguments, the sphere count, the particle-steps timed and the LIGGGHTS script or None."""
    packing = folder / f"{kind.name}.txt"
    if kind.name.startswith("dense-"):
        dense = importlib.import_module("11_bench_dense")
        law, steps = kind.name.split("-")[1], 100 if quick else 300
        n = dense.write_packing(packing, 2000 if quick else 20000)
        args, ligg = [str(packing), str(steps), law], None
        model = {"linear": linear_model, "hertz": hertz_model, "viscoelastic": viscoelastic_model}.get(law)
        if model:
            ligg = dense_liggghts_script(folder, kind.name, packing, model(), steps)
        return args, n, n * steps, ligg
    if kind.name in ("silo", "drum"):
        steps = 500 if quick else 4000
        n, settle = (1500, 3000) if quick else (4000, 12000)
        n, tri, spheres, box = (silo_packing if kind.name == "silo" else drum_packing)(packing, n, settle)
        stl = folder / f"{kind.name}.stl"
        write_stl(stl, tri)
        if kind.name == "silo":
            model, walls, gravity = hertz_model(), mesh_walls(stl), "0.0 0.0 -1.0"
        else:
            motion = (f"fix turn all move/mesh mesh mesh rotate origin 0. 0. 0. axis 0. 0. 1. "
                      f"period {2 * math.pi / OMEGA!r}\n")
            model, walls, gravity = linear_model(), mesh_walls(stl, motion), "0.0 -1.0 0.0"
        dt = time_step(spheres[:, 3])
        ligg = liggghts_script(folder, kind.name, spheres, box, dt, model, walls, gravity, steps)
        return [str(packing), str(steps)], n, n * steps, ligg
    if kind.name == "peri-triax":
        steps = 500 if quick else 4000
        n = cloud_packing(packing, 1000 if quick else 4000)
        return [str(packing), str(steps)], n, n * steps, None
    calls = 10 if quick else 100
    n = rve_packing(packing)
    return [str(packing), str(calls), "100"], n, n * calls * 100, None


def main():
    parser = results.case_arguments(__doc__)
    parser.add_argument("--only", choices=[k.name for k in KINDS], help="run this kind alone")
    parser.add_argument("--chart-from", metavar="DIR", type=Path,
                        help="run nothing: draw the chart from the records dem.bench.kind.*.json in DIR (kinds run "
                             "one at a time with --only, each ratio from its own invocation)")
    args = parser.parse_args()
    if args.chart_from:
        chart(results.Case("dem.bench.kind", quick=args.quick, folder=args.results), table_of_records(args.chart_from))
        return
    os.environ["OMP_NUM_THREADS"] = "1"
    sys.path.insert(0, str(HERE))
    repeat = 1 if args.quick else 3
    case = results.Case("dem.bench.kind", quick=args.quick, folder=args.results)
    kinds = [k for k in KINDS if args.only in (None, k.name)]
    have_yade, have_liggghts = shutil.which("yade") is not None, shutil.which("liggghts") is not None
    if not have_yade:
        print("yade is not installed (apt-get install yade): no comparison with Yade recorded")
    if not have_liggghts:
        print("liggghts is not installed (apt-get install liggghts): no comparison with LIGGGHTS recorded")
    table = []
    with tempfile.TemporaryDirectory(prefix="talus-kinds-") as scratch:
        folder = Path(scratch)
        for kind in kinds:
            scene_args, n, particle_steps, ligg = prepare(kind, folder, args.quick)
            scene = str(SCENES / kind.scene)
            one = {"OMP_NUM_THREADS": "1"}
            ours = bench.Side("talus -j1", bench.talus_command("run", "-j", "1", scene, *scene_args), CPU, env=one)
            sides = [ours]
            if have_yade:
                sides.append(bench.Side("yade -j1", ["yade", "-n", "-j1", "-x", scene, *scene_args], CPU,
                                        cwd=scratch, env=one))
            if have_liggghts and ligg is not None:
                sides.append(bench.Side("liggghts 3.8", ["liggghts", "-in", str(ligg), "-log", "none"], LIGGGHTS_CPU,
                                        cwd=scratch, env=one))
            bench.run_rounds(sides, repeat=repeat, unit="cpu s")
            fused = int(re.search(r"fused (\d+)", ours.last_output).group(1))
            ns = {side.label: 1e9 * side.median / particle_steps for side in sides}
            row = {"kind": kind.name, "spheres": n, "talus": ns[ours.label], "fused": fused}
            for peer in sides[1:]:
                label = peer.label.split()[0]
                target = kind.target if label == "yade" else LIGGGHTS_TARGET
                ratio = peer.median / ours.median
                row[label], row[f"{label}_ratio"] = ns[peer.label], ratio
                case.record(f"{kind.what}, {n} spheres: Talus speed over {label}, 1 thread, CPU time",
                            ratio, f"{peer.label} on the same scene, same invocation", target, comparison=">=",
                            suffix=f"{kind.name}-{label}", peer=peer.label, ours=ns[ours.label],
                            theirs=ns[peer.label], ratio=ratio, unit="ns per particle-step", spheres=n,
                            fused_steps=fused, ours_samples=ours.samples, theirs_samples=peer.samples)
            table.append(row)
            print(f"{kind.name}: " + ", ".join(f"{label} {v:.0f} ns" for label, v in ns.items()) +
                  f" per particle-step; fused steps {fused}")
    for row in table:
        print(" | ".join(f"{k} {v:.3g}" if isinstance(v, float) else f"{k} {v}" for k, v in row.items()))
    chart(case, table)


def table_of_records(folder: Path) -> list[dict]:
    """The chart's rows from the records in `folder`, in the order of KINDS: per kind Talus's ns
    per particle-step and each peer's, as the records of its runs with the peers wrote them."""
    rows = {}
    for kind in KINDS:
        for peer in ("yade", "liggghts"):
            path = folder / f"dem.bench.kind.{kind.name}-{peer}.json"
            if path.exists():
                record = json.loads(path.read_text())
                row = rows.setdefault(kind.name, {"kind": kind.name, "talus": record["ours"]})
                row[peer] = record["theirs"]
    return list(rows.values())


def chart(case, table) -> None:
    if not table:
        return
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, ax = plt.subplots(figsize=(8, 4))
    x = np.arange(len(table))
    for offset, (key, label) in zip((-0.27, 0.0, 0.27), (("talus", "Talus"), ("liggghts", "LIGGGHTS 3.8"),
                                                         ("yade", "Yade 2023.02a"))):
        values = [row.get(key, np.nan) for row in table]
        ax.bar(x + offset, values, width=0.27, label=label)
    ax.set_xticks(x, [row["kind"] for row in table], rotation=30, ha="right")
    ax.set_ylabel("ns per particle-step (CPU time, 1 thread)")
    ax.set_yscale("log")
    ax.grid(True, axis="y", which="both", alpha=0.3)
    ax.legend(loc="lower center", bbox_to_anchor=(0.5, 1.08), ncol=3, frameon=False)
    case.save_chart(fig)


if __name__ == "__main__":
    main()
