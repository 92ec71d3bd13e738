"""A Yade script's first contact with Talus: the namespace of `talus run`, `import yade`, and
Yade's habits that Talus keeps (density-0 walls, a plot opened before the run)."""
import os
import subprocess
import sys

import pytest


def test_talus_run_gives_the_namespace_of_yade_x(talus_cmd, tmp_path):
    script = tmp_path / "drop.py"
    # No import at all, as in Yade's examples: O, the engines, utils' functions, math, os, time.
    script.write_text(
        "O.bodies.append([sphere((0, 0, 1), 0.1), wall(0, axis=2)])\n"
        "O.engines = [ForceResetter(), InsertionSortCollider([Bo1_Sphere_Aabb(), Bo1_Wall_Aabb()]),\n"
        "             InteractionLoop([Ig2_Sphere_Sphere_ScGeom(), Ig2_Wall_Sphere_ScGeom()],\n"
        "                             [Ip2_FrictMat_FrictMat_FrictPhys()], [Law2_ScGeom_FrictPhys_CundallStrack()]),\n"
        "             NewtonIntegrator(gravity=(0, 0, -9.81))]\n"
        "O.dt = 0.5 * PWaveTimeStep()\n"
        "O.run(100, True)\n"
        "assert Omega() is O and sqrt(4) == 2 and os.path and time.time() and sys.argv\n"
        "from yade import pack, plot, utils, ymport, export, timing, qt\n"
        "from yade.utils import *\n"
        "qt.View()\n"
        "print('iter', O.iter, 'z below start', O.bodies[0].state.pos[2] < 1)\n")
    done = talus_cmd("run", script)
    assert "iter 100 z below start True" in done.stdout
    assert "yade.qt" in done.stderr          # the GUI call is accepted and said to do nothing


def test_import_yade_from_python_puts_O_in_builtins(build_dir):
    code = ("import yade, builtins\n"
            "from yade import utils, pack, plot\n"
            "assert builtins.O is yade.O and yade.Omega() is yade.O\n"
            "assert plot.addData and utils.sphere and pack.SpherePack\n"
            "print('ok')\n")
    done = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                          env={"PYTHONPATH": str(build_dir / "python")}, timeout=60)
    assert done.stdout.strip() == "ok", done.stderr


def test_real_yade_is_not_shadowed(build_dir, tmp_path):
    """Yade's launcher puts its own modules ahead of PYTHONPATH: with Talus's package on the path,
    `yade -x` still runs Yade (the side-by-side cases rely on it)."""
    import shutil
    if not shutil.which("yade"):
        pytest.skip("yade is not installed")
    script = tmp_path / "which.py"
    script.write_text("import yade\nprint('module', yade.__file__)\n")
    done = subprocess.run(["yade", "-n", "-x", str(script)], capture_output=True, text=True, timeout=120,
                          env=dict(os.environ, PYTHONPATH=str(build_dir / "python")))
    assert "module /usr/lib" in done.stdout, done.stdout + done.stderr


def test_density_zero_walls_and_a_clear_error_for_a_massless_dynamic_body():
    from talus.dem import FrictMat, Scene, sphere, wall, ForceResetter, NewtonIntegrator
    scene = Scene()
    walls = scene.materials.append(FrictMat(density=0, label="walls"))
    scene.bodies.append(wall(0, axis=2, material=walls))          # fixed: fine, as in Yade
    ball = scene.bodies.append(sphere((0, 0, 1), 0.1, material=walls))
    scene.engines = [ForceResetter(), NewtonIntegrator(gravity=(0, 0, -9.81))]
    scene.dt = 1e-4
    with pytest.raises(ValueError, match=rf"body {ball} is dynamic but its mass is 0.*'walls'.*positive density"):
        scene.step()


def test_plot_opened_before_any_data_is_empty_not_an_error():
    from talus import plot
    plot.reset()
    plot.plots = {"i": ("unbalanced", None, "z")}
    figure = plot.plot(noShow=True)                    # Yade's scripts open the live plot first
    assert len(figure.axes) == 2 and not figure.axes[0].lines
    plot.addData(i=0, unbalanced=1.0, z=0.5)
    assert len(plot.plot(noShow=True).axes[0].lines) == 1
    plot.reset()


def test_save_gnuplot_writes_data_and_script(tmp_path):
    from talus import plot
    plot.reset()
    plot.plots = {"i": ("a", None, "b")}
    for k in range(3):
        plot.addData(i=k, a=k * k, b=-k)
    script = plot.saveGnuplot(str(tmp_path / "run"))
    text = open(script).read()
    assert "axes x1y2" in text and "run.data.bz2" in text
    assert plot.loadDataTxt(tmp_path / "run.data.bz2")["a"] == [0.0, 1.0, 4.0]
    plot.reset()


@pytest.mark.parametrize("line, says", [
    ("O.engines = [MicroMacroAnalyser()]", "MicroMacroAnalyser is a name of Yade 2023.02a that Talus does not "
                                          "implement yet; it is within Talus's scope"),
    ("b = Bo1_Polyhedra_Aabb()", "it belongs to polyhedra, which is outside Talus's scope"),
    ("from yade import polyhedra_utils", "polyhedra_utils is a name of Yade 2023.02a"),
    ("from yade import bisectionDecomposition", "bisectionDecomposition is a name of Yade 2023.02a that Talus does not "
                                                "implement: it belongs to MPI subdomains"),
    ("from yade import pack\npack.inTorus", None),                     # not Yade's: Python's own error
    ("O.engines = [MicroMacroAnalyzer()]", None),                       # a typo stays a plain NameError
])
def test_a_yade_name_talus_lacks_is_named_with_its_scope(talus_cmd, tmp_path, line, says):
    script = tmp_path / "missing.py"
    script.write_text(line + "\n")
    done = talus_cmd("run", script, check=False)
    assert done.returncode == 1
    if says:
        assert says in done.stderr
    else:
        assert "a name of Yade" not in done.stderr and ("Error" in done.stderr)


def test_a_script_starts_with_yades_default_engines(talus_cmd, tmp_path):
    # Yade's examples/simple-scene/simple-scene-default-engines.py: no O.engines of its own.
    script = tmp_path / "defaults.py"
    script.write_text(
        "print([type(e).__name__ for e in O.engines])\n"
        "newton.gravity = (0, 0, -9.81)\n"
        "O.bodies.append([box(center=[0, 0, 0], extents=[.5, .5, .5], fixed=True), sphere([0, 0, 2], 1)])\n"
        "O.run(2000, True)\n"
        "print('z %.15f dt %.15g' % (O.bodies[1].state.pos[2], O.dt))\n"
        "O.reset()\n"
        "print('after reset', len(O.engines))\n")
    out = talus_cmd("run", script).stdout
    assert ("['ForceResetter', 'InsertionSortCollider', 'InteractionLoop', 'GlobalStiffnessTimeStepper', "
            "'NewtonIntegrator']") in out
    # Yade 2023.02a on the same script (damping 0.2, time step from the global stiffness).
    assert "z 1.49589079680910" in out and "dt 0.0230934547512967" in out
    assert "after reset 0" in out
