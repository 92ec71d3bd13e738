"""Replay of every registered contact law through a scripted history, against stored references.

Each scenario moves body 1 kinematically (imposed velocity and spin, body 0 fixed): approach,
normal loading, a slide past the Coulomb limit, rolling then twisting, a pause, unloading and
separation, with a checkpoint round trip (save, load into a new scene, continue) in the middle
of the slide. Every few steps it records both bodies' forces and torques, the contact's record
(geometry, stiffnesses, forces), the law's extra contact state and the energies (O.energy's
terms and the elastic potential), and compares them bit for bit with
``reference/<law>.json``: a refactoring of the laws must leave every number as it was.

A change of a law's physics changes its reference on purpose. Regenerate the references with

    TALUS_REGENERATE_REFERENCES=1 /usr/bin/python3 -m pytest -q tests/dem/laws/test_replay.py

and review the diff of ``reference/`` like code: only the scenarios of the law that changed may
move. The same history without the round trip must give the same numbers (a checkpoint that
forgets part of a contact's state fails here), and every Law2 name in the registry must have a
scenario (a new law gets one, and a reference, when it is added).
"""
import json
import math
import os
from pathlib import Path

import numpy as np
import pytest

from talus import _dem
from talus.dem import (CohFrictMat, ForceResetter, FrictMat, Ig2_PB_PB_ScGeom, Ig2_PP_PP_ScGeom,
                       InsertionSortCollider, InteractionLoop, Ip2_CohFrictMat_CohFrictMat_CohFrictPhys,
                       Ip2_FrictMat_FrictMat_FrictPhys, Ip2_FrictMat_FrictMat_KnKsPBPhys,
                       Ip2_FrictMat_FrictMat_KnKsPhys, Ip2_FrictMat_FrictMat_MindlinPhys,
                       Ip2_ViscElMat_ViscElMat_ViscElPhys, Law2_SCG_KnKsPBPhys_KnKsPBLaw,
                       Law2_SCG_KnKsPhys_KnKsLaw, Law2_ScGeom6D_CohFrictPhys_CohesionMoment,
                       Law2_ScGeom_FrictPhys_CundallStrack, Law2_ScGeom_MindlinPhys_Mindlin,
                       Law2_ScGeom_ViscElPhys_Basic, NewtonIntegrator, PotentialBlock, PotentialBlock2AABB,
                       PotentialParticle, PotentialParticle2AABB, Scene, ViscElMat, potentialBlock,
                       potentialParticle, sphere, wall)
from talus.dem.files import io

REFERENCES = Path(__file__).parent / "reference"
REGENERATE = os.environ.get("TALUS_REGENERATE_REFERENCES", "") not in ("", "0")
R = 0.1           # sphere radius; blocks and particles are cubes of half-size R
DT = 1e-5
V = 1.0           # imposed speed: 1e-5 m per step
SPIN = 10.0       # imposed spin: 1e-4 rad per step
GAP = 5e-5        # the bodies start 5 steps apart
RECORD_EVERY = 5
# (phase, steps, velocity, angular velocity) of body 1; the round trip is after "slide" step 15.
HISTORY = [("approach", 5, (0, 0, -V), (0, 0, 0)), ("load", 10, (0, 0, -V), (0, 0, 0)),
           ("slide", 30, (V, 0, 0), (0, 0, 0)), ("roll", 20, (0, 0, 0), (0, SPIN, 0)),
           ("twist", 20, (0, 0, 0), (0, 0, SPIN)), ("hold", 5, (0, 0, 0), (0, 0, 0)),
           ("unload", 40, (0, 0, V), (0, 0, 0))]
ROUND_TRIP = ("slide", 15)


# --- scenes: two bodies touching along z, body 0 fixed (a sphere, a wall, a block, a particle) ---

def spheres(S: Scene, material: int, against_wall: bool) -> None:
    first = wall(0, axis=2, sense=1, material=material) if against_wall else sphere((0, 0, 0), R, material=material,
                                                                                     fixed=True)
    top = R if against_wall else 2 * R
    S.bodies.append([first, sphere((0, 0, top + GAP), R, material=material)])


def sphere_scene(material, ip2, law, against_wall=False) -> Scene:
    S = Scene()
    m = S.materials.append(material)
    spheres(S, m, against_wall)
    S.engines = [ForceResetter(), InsertionSortCollider(), InteractionLoop([], [ip2], [law]), NewtonIntegrator()]
    return S


def block_scene(ip2, law, bonded) -> Scene:
    S = Scene()
    m = S.materials.append(FrictMat(density=2000, frictionAngle=math.radians(25)))
    faces = dict(cohesion=[5e3] * 6, tension=[1e4] * 6, intactRock=[True] * 6) if bonded else {}
    shape = PotentialBlock.cuboid((R, R, R), r=0.005, **faces)
    S.bodies.append([potentialBlock(shape, pos=(0, 0, 0), material=m, fixed=True),
                     potentialBlock(shape, pos=(0, 0, 2 * R + GAP), material=m)])
    S.engines = [ForceResetter(), InsertionSortCollider([PotentialBlock2AABB()], verletDist=0.01),
                 InteractionLoop([Ig2_PB_PB_ScGeom()], [ip2], [law]), NewtonIntegrator()]
    return S


def particle_scene() -> Scene:
    S = Scene()
    m = S.materials.append(FrictMat(density=2000, frictionAngle=math.radians(25)))
    shape = PotentialParticle.cuboid((R, R, R), r=0.02, k=0.1)
    bulge = 1.4e-3  # the faces' spherical term reaches this far beyond the half-size
    S.bodies.append([potentialParticle(shape, pos=(0, 0, 0), material=m, fixed=True),
                     potentialParticle(shape, pos=(0, 0, 2 * R + bulge + GAP), material=m)])
    S.engines = [ForceResetter(), InsertionSortCollider([PotentialParticle2AABB()], verletDist=0.01),
                 InteractionLoop([Ig2_PP_PP_ScGeom()], [Ip2_FrictMat_FrictMat_KnKsPhys(Knormal=1e8, Kshear=5e7,
                                                                                        viscousDamping=0.1)],
                                 [Law2_SCG_KnKsPhys_KnKsLaw()]), NewtonIntegrator()]
    return S


def frict():
    return FrictMat(young=1e7, poisson=0.3, frictionAngle=0.5, density=2600)


def cohfrict(**kw):
    params = dict(young=1e7, poisson=0.3, frictionAngle=0.5, density=2600, normalCohesion=5e3, shearCohesion=1e3,
                  momentRotationLaw=True, alphaKr=2.0, alphaKtw=1.5, etaRoll=0.02, etaTwist=0.01)
    params.update(kw)
    return CohFrictMat(**params)


def bonding():
    return Ip2_FrictMat_FrictMat_KnKsPBPhys(Knormal=1e8, Kshear=5e7, useFaceProperties=True, cohesionBroken=False,
                                            tensionBroken=False)


def cohesive(material, against_wall=False, **law):
    return sphere_scene(material, Ip2_CohFrictMat_CohFrictMat_CohFrictPhys(setCohesionOnNewContacts=True),
                        Law2_ScGeom6D_CohFrictPhys_CohesionMoment(**law), against_wall)


# law (its Law2 name) -> scenario name -> a function making the scene
SCENARIOS = {
    "Law2_ScGeom_FrictPhys_CundallStrack": {
        "spheres": lambda: sphere_scene(frict(), Ip2_FrictMat_FrictMat_FrictPhys(),
                                        Law2_ScGeom_FrictPhys_CundallStrack()),
        "wall": lambda: sphere_scene(frict(), Ip2_FrictMat_FrictMat_FrictPhys(),
                                     Law2_ScGeom_FrictPhys_CundallStrack(), against_wall=True),
    },
    "Law2_ScGeom_MindlinPhys_Mindlin": {
        "spheres_restitution": lambda: sphere_scene(frict(), Ip2_FrictMat_FrictMat_MindlinPhys(en=0.5, es=0.7),
                                                    Law2_ScGeom_MindlinPhys_Mindlin()),
        "wall_betas": lambda: sphere_scene(frict(), Ip2_FrictMat_FrictMat_MindlinPhys(betan=0.2, betas=0.1),
                                           Law2_ScGeom_MindlinPhys_Mindlin(), against_wall=True),
    },
    "Law2_ScGeom_ViscElPhys_Basic": {
        "spheres_tc": lambda: sphere_scene(ViscElMat(tc=1e-3, en=0.5, et=0.6, frictionAngle=0.5, density=2600),
                                           Ip2_ViscElMat_ViscElMat_ViscElPhys(), Law2_ScGeom_ViscElPhys_Basic()),
        "wall_young_rolling": lambda: sphere_scene(
            ViscElMat(young=1e7, poisson=0.3, en=0.5, frictionAngle=0.5, density=2600, mR=0.05, mRtype=1),
            Ip2_ViscElMat_ViscElMat_ViscElPhys(), Law2_ScGeom_ViscElPhys_Basic(), against_wall=True),
        "spheres_rolling_type2": lambda: sphere_scene(
            ViscElMat(tc=1e-3, en=0.5, et=0.6, frictionAngle=0.5, density=2600, mR=0.05, mRtype=2),
            Ip2_ViscElMat_ViscElMat_ViscElPhys(), Law2_ScGeom_ViscElPhys_Basic()),
    },
    "Law2_ScGeom6D_CohFrictPhys_CohesionMoment": {
        # a fragile bond broken by the slide; moments from the total rotation, kept after it broke
        "spheres_fragile": lambda: cohesive(cohfrict(), always_use_moment_law=True),
        # a ductile bond (yields in shear, then in tension: it never lets go), incremental
        # moments with plastic limits
        "spheres_ductile_incremental": lambda: cohesive(cohfrict(fragile=False), useIncrementalForm=True),
        "wall_frictional": lambda: cohesive(cohfrict(isCohesive=False), against_wall=True),
    },
    "Law2_SCG_KnKsPBPhys_KnKsPBLaw": {
        "blocks_damped": lambda: block_scene(Ip2_FrictMat_FrictMat_KnKsPBPhys(Knormal=1e8, Kshear=5e7,
                                                                              viscousDamping=0.1),
                                             Law2_SCG_KnKsPBPhys_KnKsPBLaw(), bonded=False),
        # a rock bridge broken by the slide
        "blocks_bond_breaks": lambda: block_scene(bonding(), Law2_SCG_KnKsPBPhys_KnKsPBLaw(allowBreakage=True),
                                                  bonded=True),
        # a rock bridge yielding in shear, then broken by the pull
        "blocks_bond_yields": lambda: block_scene(bonding(), Law2_SCG_KnKsPBPhys_KnKsPBLaw(), bonded=True),
    },
    "Law2_SCG_KnKsPhys_KnKsLaw": {
        "particles_damped": particle_scene,
    },
}


STAYS_BONDED = {"spheres_ductile_incremental"}


# --- the replay ---

def plain(value):
    """JSON-ready copy: arrays to lists, numpy scalars to Python numbers."""
    if isinstance(value, dict):
        return {k: plain(v) for k, v in value.items()}
    if isinstance(value, (list, tuple, np.ndarray)):
        return [plain(v) for v in value]
    if isinstance(value, (np.floating, float)):
        return float(value)
    if isinstance(value, (np.integer, np.bool_, bool, int)):
        return value.item() if hasattr(value, "item") else value
    return value


def record(S: Scene, phase: str, step: int) -> dict:
    contacts = [c for c in S.contacts() if c["isReal"]]
    return plain({"phase": phase, "step": step, "iter": S.iter,
                  "force": S.forces()[:2], "torque": S.torques()[:2],
                  "contacts": contacts, "state": _dem.contact_extra(S._cpp), "energy": _dem.energy(S._cpp)})


def replay(make, tmp_path: Path | None) -> list[dict]:
    """Run the history; with `tmp_path`, through a checkpoint round trip at ROUND_TRIP."""
    S = make()
    S.dt = DT
    S.trackEnergy = True
    S.bodies[1].state.blockedDOFs = "xyzXYZ"   # moves as imposed, with its mass in the dashpots
    out = []
    for phase, steps, vel, angVel in HISTORY:
        S.bodies[1].state.vel = vel
        S.bodies[1].state.angVel = angVel
        for k in range(1, steps + 1):
            S.run(1, True)
            if k % RECORD_EVERY == 0 or k == steps:
                out.append(record(S, phase, k))
            if tmp_path is not None and (phase, k) == ROUND_TRIP:
                path = tmp_path / "round_trip.h5"
                S.save(path)
                S = Scene()
                S.load(path, engines="saved")
    return out


def first_difference(got, want, where=""):
    """Path and values of the first number that differs (None: identical)."""
    if isinstance(want, dict):
        if not isinstance(got, dict) or got.keys() != want.keys():
            return where, sorted(got) if isinstance(got, dict) else got, sorted(want)
        for k in want:
            d = first_difference(got[k], want[k], f"{where}.{k}")
            if d:
                return d
        return None
    if isinstance(want, list):
        if not isinstance(got, list) or len(got) != len(want):
            return where, got, want
        for i, (g, w) in enumerate(zip(got, want)):
            d = first_difference(g, w, f"{where}[{i}]")
            if d:
                return d
        return None
    return None if got == want else (where, got, want)


def cases():
    return [(law, name) for law, scenarios in SCENARIOS.items() for name in scenarios]


def test_every_registered_law_has_a_scenario():
    registered = {n for n in _dem.contact_law_names() if n.startswith("Law2_")}
    assert registered == set(SCENARIOS), "a registered law without a replay scenario (or a scenario of no law)"


@pytest.mark.skipif(not io.available(), reason="built without HDF5: no checkpoint round trip")
@pytest.mark.parametrize("law, scenario", cases())
def test_replay_matches_the_reference(law, scenario, tmp_path):
    history = replay(SCENARIOS[law][scenario], tmp_path)
    assert any(r["contacts"] for r in history), "the bodies must touch"
    assert (scenario in STAYS_BONDED) == bool(history[-1]["contacts"]), "the bodies must part unless bonded"
    assert first_difference(replay(SCENARIOS[law][scenario], None), history) is None, \
        "the checkpoint round trip changed the continuation"
    path = REFERENCES / f"{law}.json"
    stored = json.loads(path.read_text()) if path.exists() else {}
    if REGENERATE:
        stored[scenario] = history
        path.parent.mkdir(exist_ok=True)
        # one record per line: a change shows as the lines of the records it touched
        lines = ",\n".join(f"  {json.dumps(name)}: [\n" + ",\n".join("    " + json.dumps(r) for r in records) + "\n  ]"
                           for name, records in sorted(stored.items()))
        path.write_text("{\n" + lines + "\n}\n")
        return
    assert scenario in stored, f"no reference for {law}/{scenario}: run with TALUS_REGENERATE_REFERENCES=1"
    diff = first_difference(history, stored[scenario])
    assert diff is None, f"{law}/{scenario}: {diff[0]} is {diff[1]!r}, the reference has {diff[2]!r}"
