"""A packing read in slabs under mpirun (talus.dem.files.slabs): ymport.text gives each process only
its part of the file, no process holds all the spheres before the split, and the run gives the
serial positions bit for bit at 2 and 3 processes."""
import json
import math
import shutil
from pathlib import Path

import numpy as np
import pytest

from test_mpi_run import assert_refused_by_name_once, talus_run

pytestmark = pytest.mark.skipif(shutil.which("mpirun") is None, reason="needs mpirun")
try:
    from talus import _distributed  # noqa: F401
except ImportError:
    pytestmark = pytest.mark.skip(reason="built without the mpi_dem feature")

SCENE = Path(__file__).resolve().parents[3] / "cases" / "scenes" / "file_bed.py"
WALLS = 5


def write_packing(path: Path, nx: int = 7, nz: int = 8, comments: bool = True) -> int:
    """A loose lattice of spheres of varied radii with random offsets, which falls and packs on
    the floor (contacts made and bodies moving between processes); returns the sphere count."""
    rng = np.random.default_rng(7)
    r, spacing = 0.01, 0.026
    i, j, k = np.meshgrid(np.arange(nx), np.arange(nx), np.arange(nz), indexing="ij")
    centres = (np.stack([i.ravel(), j.ravel(), k.ravel()], axis=1) + 0.5) * spacing
    centres += rng.uniform(-0.002, 0.002, centres.shape)
    radii = r * rng.uniform(0.8, 1.0, len(centres))
    dt = 0.3 * r * math.sqrt(2600 / 1e7)
    with open(path, "w") as out:
        out.write(f"# {dt!r} 10000000.0 2600.0 {nx * spacing!r} {nx * spacing!r}\n")
        for n, ((x, y, z), radius) in enumerate(zip(centres, radii)):
            if comments and n % 50 == 0:
                out.write("# a comment between spheres\n\n")
            out.write(f"{x!r} {y!r} {z!r} {radius!r}\n")
    return len(centres)


@pytest.mark.parametrize("processes", [2, 3])
def test_a_packing_read_in_slabs_gives_the_serial_positions(tmp_path, processes):
    packing = tmp_path / "bed.txt"
    spheres = write_packing(packing)
    serial, split = tmp_path / "serial.json", tmp_path / "split.json"
    done = talus_run(SCENE, packing, 1000, serial, "positions", timeout=120)
    assert done.returncode == 0, done.stderr
    done = talus_run(SCENE, packing, 1000, split, "positions", processes=processes, timeout=120)
    assert done.returncode == 0, done.stderr
    a, b = json.loads(serial.read_text()), json.loads(split.read_text())
    assert a["spheres"] == b["spheres"] == spheres
    assert np.array_equal(np.asarray(a["positions"]), np.asarray(b["positions"]))
    # The spheres fell: the run compares something.
    start = np.loadtxt(packing)[:, :3]
    assert (start[:, 2] - np.asarray(a["positions"])[:spheres, 2]).max() > 0.005
    # Before the split each process held its slab of the file and the walls, no more.
    held = [p["rows_before_split"] for p in b["processes"]]
    assert sum(held) == spheres + WALLS * processes
    assert all(h - WALLS in (spheres // processes, spheres // processes + 1) for h in held)
    assert sum(p["owned"] for p in b["processes"]) == spheres


FALLING = """\
from talus.dem import distributed
ids = O.bodies.append(ymport.text({packing!r}))
print("ids", ids[0], ids[-1], len(O.bodies))
b = O.bodies[next(i for i in ids if distributed.row_of(O, i, missing=None) is not None)]
print("reference as made", (b.state.refPos - b.state.pos).norm() == 0, b.state.refOri == b.state.ori)
wall = O.bodies.append(utils.wall(0, axis=2, sense=1))
print("wall", wall, O.bodies[wall].id)
{then}
"""


def run_script(tmp_path, then, processes=2):
    packing = tmp_path / "bed.txt"
    spheres = write_packing(packing, nx=4, nz=4)
    script = tmp_path / "script.py"
    script.write_text(FALLING.format(packing=str(packing), then=then))
    return spheres, talus_run(script, processes=processes, timeout=60)


def test_ids_are_the_serial_ones_and_whole_scene_reads_wait_for_the_split(tmp_path):
    spheres, done = run_script(tmp_path, "print(kineticEnergy())")
    # ids as in one process: the file's spheres first, the wall after them
    assert f"ids 0 {spheres - 1} {spheres}" in done.stdout
    assert f"wall {spheres} {spheres}" in done.stdout
    assert "reference as made True True" in done.stdout
    assert done.returncode != 0
    assert "read in slabs" in done.stderr and "first step" in done.stderr
    assert done.stderr.count("not distributed") == 1      # reported once, by process 0


def test_the_p_wave_step_before_the_split_is_the_whole_scenes(tmp_path):
    # a minimum over the bodies each process holds, taken over the processes: the serial value
    steps = [run_script(tmp_path, "print('dt %r' % PWaveTimeStep())", processes=p)[1] for p in (None, 2, 3)]
    assert all(done.returncode == 0 for done in steps), [done.stderr for done in steps]
    values = [[line for line in done.stdout.splitlines() if line.startswith("dt ")] for done in steps]
    assert values[0] == values[1] == values[2] and len(values[0]) == 1


def test_the_box_of_the_spheres_before_the_split_is_the_whole_scenes(tmp_path):
    # extrema over the bodies each process holds, taken over the processes: the serial values
    # (aabbWalls around a packing read from a file, as Yade's triaxial tutorial builds its box)
    script = "print('box %r %r' % tuple(aabbExtrema())); print('walls', len(aabbWalls()))"
    runs = [run_script(tmp_path, script, processes=p)[1] for p in (None, 2, 3)]
    assert all(done.returncode == 0 for done in runs), [done.stderr for done in runs]
    boxes = [[line for line in done.stdout.splitlines() if line.startswith(("box ", "walls "))] for done in runs]
    assert boxes[0] == boxes[1] == boxes[2] and len(boxes[0]) == 2, boxes


def test_a_scene_read_in_slabs_is_saved_after_its_first_step_only(tmp_path):
    _, done = run_script(tmp_path, "O.save({!r})".format(str(tmp_path / "early.h5")))
    assert done.returncode != 0 and "O.save of a scene holding a packing read in slabs" in done.stderr, done.stderr
    assert not (tmp_path / "early.h5").exists()


def test_a_slab_cannot_be_iterated(tmp_path):
    _, done = run_script(tmp_path, "print([b for b in ymport.text({!r})])".format(str(tmp_path / "bed.txt")))
    assert done.returncode != 0 and "read in slabs" in done.stderr and "O.bodies.append" in done.stderr
    # every process refuses alike: reported once
    assert done.stderr.count(f"{tmp_path / 'bed.txt'} were read in slabs") == 1, done.stderr


def test_a_bad_line_in_one_slab_names_the_file_and_line_and_ends_every_process(tmp_path):
    packing = tmp_path / "bed.txt"
    write_packing(packing, nx=4, nz=4, comments=False)
    lines = packing.read_text().splitlines()
    lines[-3] = "0.1 0.2 oops 0.01"       # in the last process's slab
    packing.write_text("\n".join(lines) + "\n")
    done = talus_run(SCENE, packing, 10, tmp_path / "out.json", processes=2, timeout=60)
    assert done.returncode != 0
    assert f"{packing}, line {len(lines) - 2}" in done.stderr


def test_reference_states_after_the_split_are_refused_not_another_bodys(tmp_path):
    # refPos is kept by body id once a scene is split, but a process built only its own slab's:
    # reading it after would give another body's (body 10 read body 0's on process 1); refused by
    # name instead.
    _, done = run_script(tmp_path, "O.dt = 1e-6\nO.engines = [InsertionSortCollider([Bo1_Sphere_Aabb(), Bo1_Wall_Aabb()])]\n"
                                   "O.run(1, True)\n"
                                   "b = O.bodies[wall]\nprint(b.state.refPos)")
    assert done.returncode != 0 and "State.refPos and refOri in a scene holding a packing read in slabs" in done.stderr, done.stderr


CLUMPED = """\
import json, sys
from talus.dem import distributed
O.materials.append(FrictMat(young=1e7, poisson=0.3, frictionAngle=0.5, density=2600))
ids = O.bodies.append(ymport.text({packing!r}))
for k in range(12):     # clumps of two spheres above the bed, every process making them whole
    x, y = 0.015 + 0.026 * (k % 4), 0.015 + 0.03 * (k // 4)
    O.bodies.appendClumped([utils.sphere((x, y, 0.14), 0.01), utils.sphere((x + 0.012, y, 0.145), 0.007)])
O.bodies.append(utils.wall(0, axis=2, sense=1))
O.engines = [ForceResetter(), InsertionSortCollider([Bo1_Sphere_Aabb(), Bo1_Wall_Aabb()]),
             InteractionLoop([Ig2_Sphere_Sphere_ScGeom(), Ig2_Wall_Sphere_ScGeom()],
                             [Ip2_FrictMat_FrictMat_FrictPhys()], [Law2_ScGeom_FrictPhys_CundallStrack()]),
             NewtonIntegrator(gravity=(0, 0, -9.81), damping=0.3)]
O.dt = 0.5 * PWaveTimeStep()
O.run(3000, True)
p = distributed.positions().tolist()
if distributed.rank() == 0:
    json.dump(p, open(sys.argv[1], "w"))
"""


@pytest.mark.parametrize("processes", [2, 3])
def test_clumps_appended_to_a_packing_read_in_slabs_give_the_serial_positions(tmp_path, processes):
    packing = tmp_path / "bed.txt"
    spheres = write_packing(packing, nx=4, nz=4)
    script = tmp_path / "script.py"
    script.write_text(CLUMPED.format(packing=str(packing)))
    out = {}
    for n in (None, processes):
        done = talus_run(script, tmp_path / f"{n}.json", processes=n, timeout=120)
        assert done.returncode == 0, done.stderr
        out[n] = np.asarray(json.loads((tmp_path / f"{n}.json").read_text()))
    assert len(out[None]) == spheres + 3 * 12 + 1
    assert np.array_equal(out[None], out[processes])
    # the clumps fell onto the bed (their members' ids after the file's spheres)
    assert (0.14 - out[None][spheres:spheres + 36, 2]).min() > 0.03


def test_a_clump_of_a_slabs_spheres_is_refused_by_name(tmp_path):
    _, done = run_script(tmp_path, "O.bodies.clump([ids[0], ids[1]])")
    assert_refused_by_name_once(done, "a clump of body 0, a sphere of a packing read in slabs")
