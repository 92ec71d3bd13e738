"""A script written for one process, run unchanged under `mpirun -np N talus run` (2 and 3
processes against one): `for b in O.bodies` (sums, extremes, colours, reference positions and
velocities set, bodies erased in the loop, utils.calm) visits every body of the scene on every process; O.interactions
(iteration, counts, a wall's contacts) gives every contact once; plot.saveDataTxt and the VTK
output (VTKRecorder, export.VTKExporter, export.text) are written by process 0 alone and hold
what one process writes, every body once; a snapshot of a body owned elsewhere names the rule
for what it does not hold. The scene: spheres thrown onto a floor of two facets, against a wall
and a fixed box."""
import json
import os
import sys
from pathlib import Path

import numpy as np
import pytest

from test_mpi_run import pytestmark, talus_run  # noqa: F401  (the same skip: mpi_dem feature and mpirun)

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "python"))
from test_export import read_pvd, read_vtu  # noqa: E402  (the .vtu reader of the export tests)


SCRIPT = """
import json, sys
import numpy as np
import talus.plot, talus.dem.files.export
from yade import pack, export, plot
from talus.dem import distributed
out = sys.argv[1]
if distributed.rank() != 0:     # a file written by another process than 0 is reported
    def written(path, *args, **kwargs):
        sys.stderr.write("WROTE %s ON %d\\n" % (path, distributed.rank()))
    talus.plot.write_atomically = talus.dem.files.export.write_atomically = written
O.materials.append(FrictMat(young=1e7, poisson=0.3, frictionAngle=0.5, density=2600))
cloud = pack.SpherePack()
cloud.makeCloud((0.05, 0.05, 0.05), (0.95, 0.95, 1.0), rMean=0.04, rRelFuzz=0.3, num=250, seed=2)
cloud.toSimulation()
wall = O.bodies.append(utils.wall(0, axis=0, sense=1))
O.bodies.append(utils.facet([(-0.1, -0.1, 0), (1.1, -0.1, 0), (1.1, 1.1, 0)]))
O.bodies.append(utils.facet([(-0.1, -0.1, 0), (1.1, 1.1, 0), (-0.1, 1.1, 0)]))
O.bodies.append(utils.box((0.5, 1.05, 0.5), (0.6, 0.05, 0.6), fixed=True))
O.engines = [ForceResetter(), InsertionSortCollider([Bo1_Sphere_Aabb(), Bo1_Wall_Aabb(), Bo1_Facet_Aabb(), Bo1_Box_Aabb()]),
             InteractionLoop([Ig2_Sphere_Sphere_ScGeom(), Ig2_Wall_Sphere_ScGeom(), Ig2_Facet_Sphere_ScGeom(),
                              Ig2_Box_Sphere_ScGeom()],
                             [Ip2_FrictMat_FrictMat_FrictPhys()], [Law2_ScGeom_FrictPhys_CundallStrack()]),
             NewtonIntegrator(gravity=(0, 0, -9.81), damping=0.4),
             VTKRecorder(fileName=out + "/rec-", recorders=["spheres", "facets", "walls", "boxes", "intr"], iterPeriod=200),
             PyRunner(command="plot.addData(i=O.iter, unbalanced=unbalancedForce(), contacts=O.interactions.countReal(), "
                              "kinetic=kineticEnergy(), onWall=sumForces([wall], (1, 0, 0)))", iterPeriod=100)]
O.dt = 0.7 * PWaveTimeStep()
result = {}
O.run(10, True)     # (split: the loops below visit every body of the scene)
for b in O.bodies:
    if isinstance(b.shape, Sphere):
        b.state.vel = (-0.6, 0.5, -2)
        if b.state.pos[2] > 0.5:
            b.shape.color = (0, 0, 1)
    b.state.refPos = b.state.pos
O.forces.setPermF(7, (0.3, 0, 0))     # a sphere, whichever process owns it, and the wall every process holds
O.forces.setPermF(wall, (0, 0, 2))
O.forces.addT(7, (0, 0, 1e-3), permanent=True)
O.run(591, True)
result["forces"] = [*O.forces.permF(7), *O.forces.permT(7), *O.forces.permF(wall), *O.forces.f(wall)]
result["moved"] = sum((b.state.pos - b.state.refPos).norm() for b in O.bodies)
result["mass"] = sum(b.state.mass for b in O.bodies if isinstance(b.shape, Sphere))
result["ids"] = [b.id for b in O.bodies]
result["top"] = max(b.state.pos[2] + b.shape.radius for b in O.bodies if isinstance(b.shape, Sphere))
result["kinetic"] = sum(0.5 * b.state.mass * b.state.vel.squaredNorm() for b in O.bodies if b.dynamic)
result["blue"] = [b.id for b in O.bodies if tuple(b.shape.color) == (0, 0, 1)]
result["erased"] = []
for b in O.bodies:
    if isinstance(b.shape, Sphere) and b.state.pos[2] > result["top"] - 0.2:
        O.bodies.erase(b.id)
        result["erased"].append(b.id)
result["pairs"] = [[i.id1, i.id2, *i.phys.normalForce, *i.phys.shearForce] for i in O.interactions]
result["counts"] = [len(O.interactions), O.interactions.countReal(), len(O.interactions.all(onlyReal=True))]
result["onFloor"] = sorted([i.id1, i.id2] for i in O.interactions.withBody(wall + 1))
vtk = export.VTKExporter(out + "/exp")
vtk.exportSpheres(what={"speed": "b.state.vel.norm()"})
vtk.exportInteractions()
vtk.exportFacets()
result["text"] = export.textExt(out + "/spheres.txt", "x_y_z_r_attrs", attrs=["b.state.vel"])
utils.calm()
O.run(100, True)
result["after"] = [[b.id, *b.state.pos, *b.state.vel] for b in O.bodies]
result["measures"] = [unbalancedForce(), kineticEnergy(), *np.asarray(getStress(1.0)).ravel(), porosity(1.0),
                      avgNumInteractions()]
plot.saveDataTxt(out + "/plot.txt")
errors = []
for b in O.bodies:
    if type(b).__name__ == "RemoteBody":
        for read in (lambda: b.bound, lambda: b.state.angMom):
            try:
                read()
            except AttributeError as e:
                errors.append(str(e))
        break
result["errors"] = errors
if distributed.rank() == 0:
    open(out + "/result.json", "w").write(json.dumps(result))
"""


def run_script(folder: Path, text: str) -> dict:
    """The script ``text`` (its output folder its argument) run in one process and under mpirun
    at 2 and 3 processes: per process count (None: one), its folder and the result.json process
    0 wrote there; no other process wrote a file (the script reports one as WROTE)."""
    script = folder / "script.py"
    script.write_text(text)
    out = {}
    for processes in (None, 2, 3):
        where = folder / f"run-{processes}"
        where.mkdir()
        done = talus_run(script, where, processes=processes, timeout=300)
        assert done.returncode == 0, done.stderr
        assert "WROTE" not in done.stderr, done.stderr
        out[processes] = (where, json.loads((where / "result.json").read_text()))
    return out


@pytest.fixture(scope="module")
def runs(tmp_path_factory):
    return run_script(tmp_path_factory.mktemp("scripts"), SCRIPT)


@pytest.mark.parametrize("processes", [2, 3])
def test_loops_over_the_bodies_give_the_serial_answers(runs, processes):
    (_, serial), (_, split) = runs[None], runs[processes]
    for key in ("mass", "ids", "top", "kinetic", "blue", "erased", "after", "moved"):    # in id order: the same bits
        assert serial[key] == split[key], key
    assert serial["moved"] > 10 and len(serial["ids"]) == 254 and 0 < len(serial["blue"]) < 250 and 0 < len(serial["erased"]) < 250
    # calm() stopped every body, wherever it was owned, and the erased bodies are gone everywhere
    assert len(serial["after"]) == 254 - len(serial["erased"])
    # a permanent force or torque set by every process acts once, on the body's owner (a wall's on process 0)
    assert serial["forces"][:9] == split["forces"][:9] == [0.3, 0, 0, 0, 0, 1e-3, 0, 0, 2]
    assert split["forces"][9:] == pytest.approx(serial["forces"][9:], rel=1e-12, abs=1e-12)
    assert np.allclose(serial["measures"], split["measures"], rtol=1e-12, atol=1e-12 * np.abs(serial["measures"]).max())


@pytest.mark.parametrize("processes", [2, 3])
def test_interactions_give_every_contact_once(runs, processes):
    (_, serial), (_, split) = runs[None], runs[processes]
    assert split["counts"] == serial["counts"] and serial["counts"][1] == len(serial["pairs"]) > 10
    assert sorted(serial["pairs"]) == split["pairs"]    # every contact once, ordered by (id1, id2)
    assert split["onFloor"] == serial["onFloor"] and len(serial["onFloor"]) >= 2


@pytest.mark.parametrize("processes", [2, 3])
def test_plots_and_text_are_the_serial_files(runs, processes):
    (serial_dir, _), (split_dir, _) = runs[None], runs[processes]
    # per sphere: the same text; the plot's sums over bodies and contacts within round-off
    assert (split_dir / "spheres.txt").read_text() == (serial_dir / "spheres.txt").read_text()
    assert len((serial_dir / "spheres.txt").read_text().splitlines()) == 1 + 250 - len(runs[None][1]["erased"])
    a, b = ((folder / "plot.txt").read_text().splitlines() for folder in (serial_dir, split_dir))
    assert a[0] == b[0] == "# contacts\t\ti\t\tkinetic\t\tonWall\t\tunbalanced" and len(a) == len(b) == 8
    a, b = (np.array([line.split() for line in lines[1:]], dtype=float) for lines in (a, b))
    assert np.allclose(a, b, rtol=1e-12, atol=0) and np.abs(a[:, 3]).max() > 0    # the wall was pushed


def _sorted(vtu: dict, keys) -> tuple[dict, np.ndarray]:
    data = vtu["point"] if vtu["point"] else vtu["cell"]
    return data, np.lexsort([data[k] for k in reversed(keys)])


@pytest.mark.parametrize("processes", [2, 3])
def test_vtk_files_hold_every_body_once_as_in_one_process(runs, processes):
    (serial_dir, _), (split_dir, _) = runs[None], runs[processes]
    names = sorted(os.listdir(serial_dir))
    assert sorted(os.listdir(split_dir)) == names
    vtus = [n for n in names if n.endswith(".vtu")]
    assert len(vtus) == 3 * 5 + 3 and "exp-spheres-0.vtu" in vtus
    for name in (n for n in names if n.endswith(".pvd")):
        assert read_pvd(split_dir / name) == read_pvd(serial_dir / name)
    for name in vtus:
        a, b = read_vtu(serial_dir / name), read_vtu(split_dir / name)
        assert (a["points_count"], a["cells_count"]) == (b["points_count"], b["cells_count"]), name
        keys = ("id1", "id2") if "intrs" in name else ("id",)
        (da, oa), (db, ob) = _sorted(a, keys), _sorted(b, keys)
        assert da.keys() == db.keys(), name
        if "spheres" in name:     # every sphere once (no ghost), in id order
            assert np.array_equal(db["id"], np.sort(db["id"])) and len(set(db["id"])) == len(db["id"]) > 150
            assert np.array_equal(a["points"], b["points"]), name
        for key in da:
            x, y = da[key][oa].astype(float), db[key][ob].astype(float)
            scale = max(np.abs(x).max(), 1e-300) if len(x) else 1
            assert np.allclose(x, y, rtol=0, atol=1e-12 * scale), (name, key)
    last = read_vtu(split_dir / "rec-intrs.600.vtu")["cell"]
    assert len(last["id1"]) > 10 and set(last["kind"]) >= {0, 2}     # sphere pairs and the floor's facets
    assert np.abs(read_vtu(split_dir / "rec-walls.600.vtu")["cell"]["force"]).max() > 0


def test_a_snapshot_names_the_rule_for_what_it_does_not_hold(runs):
    errors = runs[2][1]["errors"]
    assert len(errors) == 2 and all("owned by another process" in e and "snapshot" in e for e in errors), errors
    assert "bound" in errors[0] and "angMom" in errors[1]


# A PyRunner in a scene of its own (not O) writes into the spheres its process owns: the other
# processes' ghost copies of them must take the write before the next contacts are computed.
OWN_SCENE = """
import json, sys
import numpy as np
from talus.dem import distributed
from talus.dem.core.scene import Scene
s = Scene()
s.materials.append(FrictMat(young=1e7, poisson=0.3, frictionAngle=0.5, density=2600))
rng = np.random.default_rng(3)
for k in range(160):
    s.bodies.append(utils.sphere((0.1 * (k % 8) + rng.uniform(0, 0.01), 0.1 * (k // 8 % 4), 0.1 * (k // 32)), 0.052))
s.bodies.append(utils.wall(-0.1, axis=2, sense=1))


def kick():
    split = distributed.domain(s)
    rows = np.arange(160) if split is None else split.ownedBodies(s._cpp)[0]
    rows = rows[rows < len(s.radii())]
    s.velocities()[rows, 0] += 0.05 * np.sign(s.positions()[rows, 1] - 0.15)


s.engines = [ForceResetter(), InsertionSortCollider([Bo1_Sphere_Aabb(), Bo1_Wall_Aabb()]),
             InteractionLoop([Ig2_Sphere_Sphere_ScGeom(), Ig2_Wall_Sphere_ScGeom()],
                             [Ip2_FrictMat_FrictMat_FrictPhys()], [Law2_ScGeom_FrictPhys_CundallStrack()]),
             NewtonIntegrator(gravity=(0, 0, -9.81)), PyRunner(command=kick, iterPeriod=25)]
s.dt = 2e-5
s.run(600, True)
result = distributed.positions(s).tolist()
if distributed.rank() == 0:
    json.dump(result, open(sys.argv[1], "w"))
"""


def test_a_pyrunner_of_another_scene_sends_its_writes_to_the_ghosts(tmp_path):
    script = tmp_path / "own_scene.py"
    script.write_text(OWN_SCENE)
    out = {}
    for processes in (None, 2):
        path = tmp_path / f"positions-{processes}.json"
        done = talus_run(script, path, processes=processes, timeout=300)
        assert done.returncode == 0, done.stderr
        out[processes] = np.asarray(json.loads(path.read_text()))
    assert np.array_equal(out[None], out[2])
