"""A build configured with TALUS_WITH_MPI_DEM=OFF has no talus._distributed (nor
_distributed_checkpoint): `talus run` of a one-process script still imports talus.dem and runs
it. Checked by hiding the two modules from a fresh interpreter (a sitecustomize that puts None in
their place in sys.modules, as an import of a module that was never built fails)."""
import os
import subprocess
import sys
from pathlib import Path

import talus

SCRIPT = """
O.materials.append(FrictMat(young=1e7, poisson=0.3, frictionAngle=0.5, density=2600))
O.bodies.append(utils.wall(0, axis=2, sense=1))
O.bodies.append([utils.sphere((0, 0, 0.05 + 0.1 * k), 0.04) for k in range(5)])
O.engines = [ForceResetter(), InsertionSortCollider([Bo1_Sphere_Aabb(), Bo1_Wall_Aabb()]),
             InteractionLoop([Ig2_Sphere_Sphere_ScGeom(), Ig2_Wall_Sphere_ScGeom()],
                             [Ip2_FrictMat_FrictMat_FrictPhys()], [Law2_ScGeom_FrictPhys_CundallStrack()]),
             NewtonIntegrator(gravity=(0, 0, -9.81)), PyRunner(command="print(O.bodies[1].state.pos[2])", iterPeriod=50)]
O.dt = 1e-5
O.run(100, True)
import talus
assert "_distributed" not in dir(talus)
print("ran", O.iter, len(O.bodies))
"""


def test_a_script_runs_without_the_dem_over_mpi(tmp_path):
    (tmp_path / "sitecustomize.py").write_text(
        "import sys\nsys.modules['talus._distributed'] = None\nsys.modules['talus._distributed_checkpoint'] = None\n")
    script = tmp_path / "falls.py"
    script.write_text(SCRIPT)
    package_root = str(Path(talus.__file__).resolve().parents[1])
    env = dict(os.environ, PYTHONPATH=os.pathsep.join([str(tmp_path), package_root]))
    done = subprocess.run([sys.executable, "-m", "talus", "run", "-j", "1", str(script)], capture_output=True,
                          text=True, env=env, timeout=120)
    assert done.returncode == 0, done.stderr
    assert "ran 100 6" in done.stdout
