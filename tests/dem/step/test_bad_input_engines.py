"""Bad engine and run settings Yade runs without a word: each gets an error (or, where it may be
meant, a warning) naming the parameter and its safe range."""
import math
import warnings

import pytest

from talus.dem import (CohFrictMat, FrictMat, ForceResetter, InsertionSortCollider, InteractionLoop,
                       Ip2_FrictMat_FrictMat_FrictPhys, Law2_ScGeom_FrictPhys_CundallStrack, Matrix3,
                       NewtonIntegrator, PWaveTimeStep, Scene, sphere, wall)

LINEAR = ([Ip2_FrictMat_FrictMat_FrictPhys()], [Law2_ScGeom_FrictPhys_CundallStrack()])


def falling_spheres(dt_factor: float, yade_mode: bool = False):
    """Two spheres falling on a floor, 0.2 m above it: a sparse scene without contacts."""
    S = Scene()
    S.overlapStops = not yade_mode
    S.materials.append(FrictMat(young=1e7, density=2600))
    S.bodies.append([sphere((0, 0, 0.2), 0.02), sphere((0.5, 0, 0.2), 0.02), wall(0, axis=2, sense=1)])
    S.engines = [ForceResetter(), InsertionSortCollider(), InteractionLoop([], *LINEAR),
                 NewtonIntegrator(gravity=(0, 0, -9.81), damping=0.2)]
    S.dt = dt_factor * PWaveTimeStep(S)
    return S


@pytest.mark.parametrize("damping", [-1, 2, 1.0001, math.nan, math.inf])
def test_newton_damping_outside_0_1_is_refused(damping):
    with pytest.raises(ValueError, match=r"NewtonIntegrator.damping must be in \[0, 1\]"):
        NewtonIntegrator(damping=damping)
    n = NewtonIntegrator(damping=0.3)
    with pytest.raises(ValueError, match=r"NewtonIntegrator.damping must be in \[0, 1\]"):
        n.damping = damping
    assert n.damping == 0.3
    for fine in (0, 0.4, 1):       # 1 is used by one of Yade's examples
        n.damping = fine
        assert n.damping == fine


@pytest.mark.parametrize("gravity", [(0, 0, math.nan), (math.inf, 0, 0), (0, 0)])
def test_newton_gravity_must_be_three_finite_numbers(gravity):
    with pytest.raises(ValueError, match="NewtonIntegrator.gravity must be 3 finite numbers"):
        NewtonIntegrator(gravity=gravity)


def test_two_newton_integrators_moving_the_same_bodies_are_refused():
    S = Scene()
    with pytest.raises(ValueError, match=r"two NewtonIntegrators \(engines 1 and 2\).*integrate them twice"):
        S.engines = [ForceResetter(), NewtonIntegrator(), NewtonIntegrator()]
    with pytest.raises(ValueError, match="two NewtonIntegrators"):
        S.engines = [ForceResetter(), NewtonIntegrator(mask=3), NewtonIntegrator(mask=2)]
    # Disjoint masks move different bodies: allowed.
    S.engines = [ForceResetter(), NewtonIntegrator(mask=1), NewtonIntegrator(mask=2)]
    assert len(S.engines) == 3


def test_an_interaction_loop_without_collider_warns():
    S = Scene()
    with pytest.warns(RuntimeWarning, match=r"InteractionLoop \(engine 1\) but no collider"):
        S.engines = [ForceResetter(), InteractionLoop([], *LINEAR), NewtonIntegrator()]
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        S.engines = [ForceResetter(), InsertionSortCollider(), InteractionLoop([], *LINEAR), NewtonIntegrator()]


def test_run_with_a_non_integer_step_count_is_refused():
    # Yade refuses O.run(10.5) too (a Boost.Python ArgumentError: nSteps is a long).
    S = falling_spheres(0.5)
    with pytest.raises(ValueError, match="nSteps must be a whole number of steps, got 10.5"):
        S.run(10.5)
    assert S.iter == 0
    S.run(10.0)
    assert S.iter == 10


def test_time_step_far_above_the_critical_step_in_a_sparse_scene():
    # Without the check the spheres fall through the floor (no contact ever sees the overlap).
    S = falling_spheres(100)
    with pytest.raises(ValueError, match=r"O.dt = \S+ is 100 times the P-wave critical step .* of sphere 0 "
                                         r"\(radius 0.02, young 1e\+07.*safe range is O.dt <= PWaveTimeStep\(\)"):
        S.run(10)
    with pytest.raises(ValueError, match="100 times the P-wave critical step"):
        S.step()
    assert S.iter == 0
    S.dt = 0.5 * PWaveTimeStep(S)
    S.run(10)
    assert S.iter == 10
    # Under Yade's names (a `yade -x` script: O.overlapStops off) Yade runs it: a warning, once.
    Y = falling_spheres(100, yade_mode=True)
    with pytest.warns(RuntimeWarning, match="100 times the P-wave critical step"):
        Y.run(2)
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        Y.run(2)                   # same step, same bodies: not said again


def test_time_step_check_needs_contacts_that_can_form():
    # A sphere settling in a fluid (a coupling's scene: no contact law) takes the fluid's step.
    S = Scene()
    S.bodies.append([sphere((0, 0, 0), 1e-3), sphere((1, 0, 0), 1e-3)])
    S.engines = [ForceResetter(), NewtonIntegrator(gravity=(0, 0, -9.81))]
    S.dt = 1e3 * PWaveTimeStep(S)
    S.run(2)
    # The same scene with a contact law is refused, the lone sphere with one is not.
    S.engines = [ForceResetter(), InsertionSortCollider(), InteractionLoop([], *LINEAR), NewtonIntegrator()]
    with pytest.raises(ValueError, match="1e\\+03 times the P-wave critical step"):
        S.run(2)
    T = Scene()
    T.bodies.append(sphere((0, 0, 0), 1e-3))
    T.engines = [ForceResetter(), InsertionSortCollider(), InteractionLoop([], *LINEAR), NewtonIntegrator()]
    T.dt = 1e3 * PWaveTimeStep(T)
    T.run(2)
    assert T.iter == 2


def test_time_step_check_skips_bodies_that_do_not_move():
    S = falling_spheres(0.5)
    S.dt = 1e3 * PWaveTimeStep(S)
    for b in list(S.bodies)[:2]:
        b.dynamic = False          # nothing moves: any step is fine
    S.run(2)
    assert S.iter == 2


def test_a_velocity_gradient_that_inverts_the_cell_is_refused():
    S = Scene()
    S.periodic = True
    S.cell.setBox(1, 1, 1)
    S.bodies.append(sphere((0.5, 0.5, 0.5), 0.1))
    S.engines = [ForceResetter(), InsertionSortCollider(), InteractionLoop([], *LINEAR), NewtonIntegrator()]
    S.dt = 1e-4
    S.cell.velGrad = Matrix3(-2e4, 0, 0, 0, 0, 0, 0, 0, 0)    # |L dt| = 2: the cell flips
    with pytest.raises(RuntimeError, match=r"velGrad inverts the cell in one step: det\(I \+ velGrad\*O.dt\) = -1"):
        S.step()
    T = Scene()
    T.periodic = True
    T.cell.setBox(1, 1, 1)
    T.bodies.append(sphere((0.5, 0.5, 0.5), 0.1))
    T.engines = [ForceResetter(), NewtonIntegrator()]
    T.dt = 1e-4
    T.cell.velGrad = Matrix3(-1e2, 0, 0, 0, 0, 0, 0, 0, 0)    # 1 % per step: fine
    T.run(5)
    assert T.cell.hSize.determinant() == pytest.approx(0.99 ** 5)


def test_a_sphere_larger_than_the_periodic_cell_is_refused():
    S = Scene()
    S.periodic = True
    S.cell.setBox(1, 1, 1)
    S.bodies.append([sphere((0.5, 0.5, 0.5), 0.8), sphere((0.1, 0.1, 0.1), 0.05)])
    S.engines = [ForceResetter(), InsertionSortCollider(), InteractionLoop([], *LINEAR), NewtonIntegrator()]
    S.dt = 1e-5
    with pytest.raises(RuntimeError, match=r"sphere 0 \(radius 0.8.*\) is larger than the periodic cell"):
        S.step()


@pytest.mark.parametrize("name", ["normalCohesion", "shearCohesion"])
def test_a_negative_cohesion_warns(name):
    with pytest.warns(UserWarning, match=rf"CohFrictMat.{name} = -5 < 0: .*range is >= 0"):
        CohFrictMat(**{name: -5.0})
    m = CohFrictMat()
    with pytest.warns(UserWarning, match=rf"CohFrictMat.{name} = -2 < 0"):
        setattr(m, name, -2.0)
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        CohFrictMat(**{name: -1.0})      # Yade's default: no cohesion
        CohFrictMat(**{name: 1e5})
