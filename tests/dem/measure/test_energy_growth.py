"""The energy tracker under particle growth (growParticles, TriaxialStressController's internal
compaction): the radii change at fixed positions, the contacts' compressions and stiffnesses and
the masses at their velocities jump; growthWork (not a Yade key: Yade books nothing) is that
jump, so that O.energy.total() stays constant."""
import numpy as np
import pytest

from talus.dem import (FrictMat, ForceResetter, InsertionSortCollider, InteractionLoop, Ip2_FrictMat_FrictMat_FrictPhys,
                       Law2_ScGeom_FrictPhys_CundallStrack, NewtonIntegrator, Scene, growParticles, sphere, wall)

from control.test_controllers import run_until, walled_cloud
from test_energy import restart_continues


def pressed_pair():
    """Two spheres overlapping on a wall, at rest, no gravity, no damping: a closed system."""
    S = Scene()
    S.materials.append(FrictMat(young=1e7, poisson=0.3, frictionAngle=0.5, density=2600))
    S.bodies.append([wall(0, axis=2, sense=1), sphere((0, 0, 0.099), 0.1), sphere((0.195, 0, 0.1), 0.1)])
    S.bodies[2].state.vel = (0.01, 0, 0.02)
    S.engines = [ForceResetter(), InsertionSortCollider(),
                 InteractionLoop([], [Ip2_FrictMat_FrictMat_FrictPhys()], [Law2_ScGeom_FrictPhys_CundallStrack()]),
                 NewtonIntegrator(damping=0.0)]
    S.dt = 1e-5
    S.trackEnergy = True
    return S


def test_one_growth_step_books_the_jump_of_the_state():
    S = pressed_pair()
    S.run(1)
    before = S.energy.total()
    elastic, kinetic = S.energy["elastPotential"], S.energy["kinetic"]
    growParticles(1.01, scene=S)
    e = S.energy
    # stiffer (kn x 1.01) and more compressed springs (each overlap + 1 mm per grown sphere),
    # heavier bodies at the same velocities
    assert e["elastPotential"] > 1.5 * elastic and e["kinetic"] == pytest.approx(kinetic * 1.01 ** 3, rel=1e-12)
    assert e["growthWork"] == pytest.approx(-(e["elastPotential"] - elastic) - (e["kinetic"] - kinetic), rel=1e-12)
    assert e.total() == pytest.approx(before, abs=1e-15 * abs(e["growthWork"]))
    # the next force pass finds the same compressions: the elastic energy does not jump again
    # (without the penetrations following the radii it would, by half of growthWork)
    S.run(1)
    assert abs(S.energy.total() - before) < 1e-4 * abs(e["growthWork"])


def test_growth_steps_in_a_closed_system_close_the_balance():
    # Undamped: the springs push the spheres apart after each growth. What is left (0.18 %) is
    # the step of each growth: the integrator applies the forces computed before it (as in Yade),
    # not those of the grown state, over that one step.
    S = pressed_pair()
    S.run(1)                          # the contacts exist from the first pass on
    before = S.energy.total()
    for _ in range(20):
        S.run(50)
        growParticles(1.002, scene=S)
    S.run(500)
    e = S.energy
    assert e["growthWork"] < 0
    assert abs(S.energy.total() - before) < 0.01 * abs(e["growthWork"])


def test_internal_compaction_closes_the_balance():
    # TriaxialStressController grows the spheres between fixed walls up to 10 kPa: growth is the
    # only energy input, dissipated by friction and damping (adaptive time step). Closes to 1.9 %
    # (3.9 % without the energy of the contacts the growth makes, 100 % without growthWork): the
    # controller grows after the contact pass, so each growth's step moves the bodies with the
    # forces of the ungrown state, a first-order error (Yade's engine order: the same in Yade, which books no growth at all).
    S, triax = walled_cloud(internalCompaction=True, maxMultiplier=1.004, finalMaxMultiplier=1.0004)
    S.trackEnergy = True
    before = S.energy.total()
    run_until(S, lambda: abs(triax.meanStress + 1e4) < 1e-3 * 1e4)
    S.run(2000)
    e = dict(S.energy.items())
    assert e["growthWork"] < 0 and e["kinematicWork"] == 0 and e["gravWork"] == 0
    assert e["plastDissip"] > 0 and e["nonviscDamp"] > 0
    assert abs(S.energy.total() - before) < 0.025 * abs(e["growthWork"])


def test_restart_between_a_growth_and_the_next_contact_pass_continues_bit_identically(tmp_path):
    # The growth not yet seen by the contacts (EnergyTracker::grownBy) is in the checkpoint.
    S, _ = walled_cloud(n=80, internalCompaction=True, maxMultiplier=1.004)
    S.trackEnergy = True
    S.run(300)
    growParticles(1.01, scene=S)
    assert restart_continues(S, tmp_path / "grown.h5")["growthWork"] < 0


def test_growing_a_clump_books_the_jump_and_its_members_move_apart():
    # A clump of two spheres lying on a wall, a free sphere pressed against one member, a spin:
    # the growth moves the members away from the centroid as well as growing them, so the
    # compressions change by both (the wall's exactly, the pair's through the line of centres).
    S = Scene()
    S.materials.append(FrictMat(young=1e7, poisson=0.3, frictionAngle=0.5, density=2600))
    S.bodies.append(wall(0, axis=2, sense=1))
    cid, ids = S.bodies.appendClumped([sphere((0, 0, 0.099), 0.1), sphere((0.19, 0, 0.0995), 0.1)])
    S.bodies.append(sphere((0.38, 0.05, 0.105), 0.1))
    S.bodies[cid].state.angVel = (0, 0, 0.3)
    S.engines = [ForceResetter(), InsertionSortCollider(),
                 InteractionLoop([], [Ip2_FrictMat_FrictMat_FrictPhys()], [Law2_ScGeom_FrictPhys_CundallStrack()]),
                 NewtonIntegrator(damping=0.0)]
    S.dt = 1e-5
    S.trackEnergy = True
    S.run(1)
    before = S.energy.total()
    elastic, kinetic = S.energy["elastPotential"], S.energy["kinetic"]
    growParticles(1.01, scene=S)
    e = S.energy
    # masses x s^3 and moments x s^5 at fixed velocities (the clump translates and spins)
    assert kinetic * 1.01 ** 3 < e["kinetic"] < kinetic * 1.01 ** 5
    assert e["growthWork"] == pytest.approx(-(e["elastPotential"] - elastic) - (e["kinetic"] - kinetic), rel=1e-12)
    # the next force pass finds the compressions the growth booked (without the members'
    # displacement the elastic energy would jump again, by 47 % of growthWork)
    S.run(1)
    assert abs(S.energy.total() - before) < 1e-4 * abs(e["growthWork"])
