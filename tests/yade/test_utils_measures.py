"""yade.utils measurements and O helpers scripts use, against numbers Yade 2023.02a printed for
the same scene (tf2 below run by `yade -n -x`)."""
import os

import pytest

SCENE = """
O.bodies.append([sphere((0, 0, 0), 1), sphere((1.9, 0.3, 0.1), 1), sphere((0, 1.95, 0), 1)])
O.engines = [ForceResetter(), InsertionSortCollider([Bo1_Sphere_Aabb()]),
             InteractionLoop([Ig2_Sphere_Sphere_ScGeom()], [Ip2_FrictMat_FrictMat_FrictPhys()],
                             [Law2_ScGeom_FrictPhys_CundallStrack()]), NewtonIntegrator()]
O.dt = 1e-5
O.bodies[1].state.vel = (0, 0.3, 0.2)
O.run(3, True)
F, stiffness = totalForceInVolume()
print('F %.10g %.10g %.10g k %.10g' % (F[0], F[1], F[2], stiffness))
name = O.tmpFilename()
open(name, 'w').write('x')
print('tmp', name, os.path.isfile(name), name != O.tmpFilename())
"""


def test_total_force_in_volume_and_tmp_filename(talus_cmd, tmp_path):
    script = tmp_path / "measures.py"
    script.write_text(SCENE)
    out = talus_cmd("run", script).stdout
    # Yade: (Vector3(728609.8191607212648,615017.1854291777126,38330.72887373413687), 5333333.333333333)
    assert "F 728609.8192 615017.1854 38330.72887 k 5333333.333" in out
    name, exists, fresh = out.split("tmp ")[1].split()
    assert exists == "True" and fresh == "True"
    assert not os.path.exists(name)          # the folder went when the run's Python exited


def test_calm_and_text_export_select_bodies_by_mask(talus_cmd, tmp_path):
    script = tmp_path / "masks.py"
    script.write_text(
        "O.bodies.append([sphere((0, 0, 0), 1, mask=1), sphere((3, 0, 0), 1, mask=2), sphere((6, 0, 0), 1, mask=3)])\n"
        "for b in O.bodies: b.state.vel = (1, 2, 3)\n"
        "calm(2)\n"
        "print('V', [tuple(b.state.vel) for b in O.bodies])\n"
        "from yade import export\n"
        "print('N', export.textExt('a.txt', mask=1), export.textExt('b.txt'), export.textExt('c.txt', mask=0))\n")
    out = talus_cmd("run", script, cwd=tmp_path).stdout
    # What Yade 2023.02a prints for the same script.
    assert "V [(1.0, 2.0, 3.0), (0.0, 0.0, 0.0), (0.0, 0.0, 0.0)]" in out
    assert "N 2 3 0" in out


def test_first_iter_run_hp1_helpers_and_launcher_options(talus_cmd, tmp_path):
    script = tmp_path / "first.py"
    script.write_text(
        "O.engines = [PyRunner(command='calls.append(O.iter)', iterPeriod=3, firstIterRun=5)]\n"
        "calls = []\n"
        "O.dt = 1\n"
        "O.run(15, True)\n"
        "import yade.math\n"
        "print('CALLS', calls, yade.math.radiansHP1(180) == math.pi, yade.math.degreesHP1(math.pi), opts.nogui)\n")
    # Yade 2023.02a (yade -n -x): CALLS [5, 8, 11, 14] True 180.0 True
    assert "CALLS [5, 8, 11, 14] True 180.0 True" in talus_cmd("run", script).stdout
