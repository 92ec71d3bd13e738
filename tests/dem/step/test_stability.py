"""A time step past the stability limit, an overlapping start, a non-finite force or a growing
total energy stop the run with an error that names the bodies and the stable step, instead of
going on silently."""
import math

import numpy as np
import pytest

from talus.dem import (FrictMat, ForceResetter, InsertionSortCollider, InteractionLoop,
                       Ip2_FrictMat_FrictMat_FrictPhys, Law2_ScGeom_FrictPhys_CundallStrack,
                       NewtonIntegrator, PWaveTimeStep, Scene, contactTimeStep, sphere, wall)


def column(dt_factor):
    S = Scene()
    S.materials.append(FrictMat(young=1e7, density=2600))
    S.bodies.append([wall(0, axis=2)] + [sphere((0, 0, 0.1 + 0.2 * k), 0.1) for k in range(5)])
    S.engines = [ForceResetter(), InsertionSortCollider(),
                 InteractionLoop([], [Ip2_FrictMat_FrictMat_FrictPhys()], [Law2_ScGeom_FrictPhys_CundallStrack()]),
                 NewtonIntegrator(gravity=(0, 0, -9.81), damping=0.0)]
    S.dt = dt_factor * PWaveTimeStep(S)
    return S


def test_a_stable_step_runs():
    S = column(0.3)
    S.run(3000)
    assert np.all(np.isfinite(S.positions()))
    assert contactTimeStep(S) > S.dt


def test_an_unstable_step_is_detected_and_named():
    S = column(8.0)
    with pytest.raises(RuntimeError, match=r"step \d+: bodies \d+ and \d+ overlap by .*% of the smaller radius"
                                           r".*time step .* is too large.*critical step is about .*P-wave"):
        S.run(3000)
    assert S.iter < 3000


def test_an_overlapping_start_is_detected_at_the_first_step():
    def overlapping():
        S = Scene()
        S.bodies.append([sphere((0, 0, 0), 0.1), sphere((0, 0, 0.05), 0.1)])
        S.engines = [ForceResetter(), InsertionSortCollider(),
                     InteractionLoop([], [Ip2_FrictMat_FrictMat_FrictPhys()], [Law2_ScGeom_FrictPhys_CundallStrack()]),
                     NewtonIntegrator()]
        S.dt = 1e-6
        return S
    with pytest.raises(RuntimeError, match="step 0: bodies 0 and 1 overlap by 0.15, 150% .*created overlapping"):
        overlapping().step()
    S = overlapping()
    S.maxOverlapRatio = 0            # the check can be switched off deliberately
    S.step()


def test_a_step_stopped_by_an_overlap_leaves_every_force_reset():
    """The step gathers a body's forces as soon as its contacts are computed (dem/step/GatherAhead);
    a step an overlap stops still leaves every body with its reset force, the persistent one, as
    the engines run one by one do: the touching pair (0, 1) comes before the overlapping one in
    the contact list, so its forces are summed before the overlap is found."""
    S = Scene()
    S.materials.append(FrictMat(young=1e7, density=2600))
    S.bodies.append([sphere((0, 0, 0), 0.1), sphere((0, 0, 0.199), 0.1),
                     sphere((1, 0, 0), 0.1), sphere((1, 0, 0.05), 0.1)])
    S.engines = [ForceResetter(), InsertionSortCollider(),
                 InteractionLoop([], [Ip2_FrictMat_FrictMat_FrictPhys()], [Law2_ScGeom_FrictPhys_CundallStrack()]),
                 NewtonIntegrator()]
    S.dt = 1e-6
    persistent = np.array([[0.0, 0.0, 1.5 + k] for k in range(4)])
    S.persistent_forces()[:] = persistent
    with pytest.raises(RuntimeError, match="bodies 2 and 3 overlap"):
        S.step()
    assert np.array_equal(np.array([S.forces.f(k) for k in range(4)]), persistent)


def test_a_non_finite_force_names_the_body():
    S = column(0.3)
    S.persistent_forces()[3] = (0, math.nan, 0)
    with pytest.raises(RuntimeError, match="step 0: body 3 has a non-finite force"):
        S.step()


def test_a_failed_step_is_not_silently_repeated():
    """A step that threw left contact histories and bodies half updated: the scene refuses to go
    on from there (instead of repeating the step on a corrupted state) until a checkpoint is
    loaded."""
    S = column(3.0)
    S.saveTmp("start")
    with pytest.raises(RuntimeError, match="overlap"):
        S.run(3000)
    failed_at = S.iter
    with pytest.raises(RuntimeError, match=rf"cannot continue: step {failed_at} failed .*overlap.*load a checkpoint"):
        S.step()
    assert S.iter == failed_at
    S.loadTmp("start")
    S.dt = 0.3 * PWaveTimeStep(S)
    S.run(100)
    assert S.iter == 100


def test_energy_growth_is_detected_and_named():
    # With the overlap check off, an unstable step shows as energy created from nothing.
    S = column(3.0)
    S.maxOverlapRatio = 0
    S.trackEnergy = True
    S.maxEnergyGrowth = 0.1
    with pytest.raises(RuntimeError, match=r"step \d+00: the total energy grew by .*% of the .* that flowed, limit 10%"
                                           r".*unstable; body \d+ moves fastest.*time step .* is too large: P-wave"):
        S.run(20000)
    stable = column(0.3)
    stable.trackEnergy = True
    stable.maxEnergyGrowth = 0.1
    stable.run(3000)                 # a stable column bouncing on the wall is not stopped
    with pytest.raises(ValueError, match="maxEnergyGrowth"):
        stable.maxEnergyGrowth = -1


def test_overlap_beyond_the_limit_goes_on_with_a_warning_when_asked_as_yade(tmp_path):
    # Yade has no overlap check: with overlapStops False (talus run's default, Yade's behaviour)
    # the same scene runs on, warned once, and the steps are counted; True stops with the error.
    from talus.dem import (Bo1_Sphere_Aabb, ForceResetter, Ig2_Sphere_Sphere_ScGeom, InsertionSortCollider,
                           InteractionLoop, Ip2_FrictMat_FrictMat_FrictPhys, Law2_ScGeom_FrictPhys_CundallStrack,
                           NewtonIntegrator, Scene, sphere)

    def overlapping():
        S = Scene()
        S.bodies.append([sphere((0, 0, 0), 1), sphere((0, 0, 0.5), 1)])
        S.engines = [ForceResetter(), InsertionSortCollider([Bo1_Sphere_Aabb()]),
                     InteractionLoop([Ig2_Sphere_Sphere_ScGeom()], [Ip2_FrictMat_FrictMat_FrictPhys()],
                                     [Law2_ScGeom_FrictPhys_CundallStrack()]), NewtonIntegrator()]
        S.dt = 1e-5
        return S

    strict = overlapping()
    assert strict.overlapStops
    with pytest.raises(RuntimeError, match="bodies 0 and 1 overlap by 1.5, 150% of the smaller radius"):
        strict.run(5, True)
    yade_like = overlapping()
    yade_like.overlapStops = False
    with pytest.warns(RuntimeWarning, match="150% of the smaller radius.*the run goes on, as in Yade") as said:
        yade_like.run(5, True)
        yade_like.run(5, True)
    assert len(said) == 1 and yade_like.iter == 10 and yade_like.overlapSteps == 10
    assert yade_like.bodies[1].state.vel[2] > 0          # it is being pushed out


def test_talus_run_reports_overlaps_as_yade_would_run_on(talus_cmd, tmp_path):
    script = tmp_path / "grow.py"
    script.write_text(
        "O.bodies.append([sphere((0, 0, 0), 1), sphere((0, 0, 0.5), 1)])\n"
        "O.engines = [ForceResetter(), InsertionSortCollider([Bo1_Sphere_Aabb()]),\n"
        "             InteractionLoop([Ig2_Sphere_Sphere_ScGeom()], [Ip2_FrictMat_FrictMat_FrictPhys()],\n"
        "                             [Law2_ScGeom_FrictPhys_CundallStrack()]), NewtonIntegrator()]\n"
        "O.dt = 1e-5\n"
        "O.run(3, True)\n")
    done = talus_cmd("run", script)
    assert "talus run: 3 steps had a contact overlapping beyond O.maxOverlapRatio" in done.stderr


def test_overlapping_fixed_bodies_are_not_an_overlap_error():
    # Two fixed spheres (a rough bed) overlapping by far more than the limit move under no force:
    # they cannot blow up, so the check passes them over; a free sphere in such overlap does not.
    from talus.dem import (Bo1_Sphere_Aabb, ForceResetter, Ig2_Sphere_Sphere_ScGeom, InsertionSortCollider,
                           InteractionLoop, Ip2_FrictMat_FrictMat_FrictPhys, Law2_ScGeom_FrictPhys_CundallStrack,
                           NewtonIntegrator, Scene, sphere)
    S = Scene()
    S.bodies.append([sphere((0, 0, 0), 1, fixed=True), sphere((0, 0, 0.5), 1, fixed=True), sphere((5, 0, 0), 1)])
    S.engines = [ForceResetter(), InsertionSortCollider([Bo1_Sphere_Aabb()]),
                 InteractionLoop([Ig2_Sphere_Sphere_ScGeom()], [Ip2_FrictMat_FrictMat_FrictPhys()],
                                 [Law2_ScGeom_FrictPhys_CundallStrack()]), NewtonIntegrator()]
    S.dt = 1e-5
    S.run(3, True)
    assert S.interactions.countReal() == 1 and S.overlapSteps == 0
    S.bodies[1].dynamic = True
    with pytest.raises(RuntimeError, match="bodies 0 and 1 overlap"):
        S.run(1, True)


@pytest.mark.parametrize("law", ["linear", "hertz"])
@pytest.mark.parametrize("track", [False, True])
def test_an_overlap_in_the_lanes_is_found_as_one_by_one(law, track):
    """Sphere contacts real at the last step go four at a time through the laws' AVX2 lanes (where
    the processor has them), which test the overlap against maxOverlapRatio in the lanes and leave
    only the deep ones to the full check; energy tracking takes every contact one by one. Nine
    spheres in a row (contacts (4, 5) to (7, 8) in one group of four), sphere 6 pushed 60 % of a
    radius into sphere 5 after the first step: either way the step stops on bodies 5 and 6."""
    from talus.dem import Ip2_FrictMat_FrictMat_MindlinPhys, Law2_ScGeom_MindlinPhys_Mindlin
    S = Scene()
    S.materials.append(FrictMat(young=1e7, density=2600))
    r = 0.1
    S.bodies.append([sphere((2 * r * 0.999 * k, 0, 0), r) for k in range(9)])
    physics, contact_law = ((Ip2_FrictMat_FrictMat_FrictPhys(), Law2_ScGeom_FrictPhys_CundallStrack()) if law == "linear"
                            else (Ip2_FrictMat_FrictMat_MindlinPhys(), Law2_ScGeom_MindlinPhys_Mindlin()))
    S.engines = [ForceResetter(), InsertionSortCollider(), InteractionLoop([], [physics], [contact_law]), NewtonIntegrator()]
    S.dt = 1e-6
    S.trackEnergy = track
    S.step()
    assert S.interactions.countReal() == 8
    S.bodies[6].state.pos = (2 * r * 0.999 * 6 - 0.6 * r, 0, 0)
    with pytest.raises(RuntimeError, match=r"step 1: bodies 5 and 6 overlap by .*, 6\d(\.\d+)?% of the smaller radius"):
        S.step()
