"""Facet-sphere contacts go four at a time through the AVX2 geometry (where the processor has
it: dem/contact/FacetGeometryBatch.h), energy tracking runs every contact one by one: a turning
drum of facets holding a dense packing, with the linear law and with Hertz-Mindlin, gives the
same bits either way, at one thread and at two."""
import hashlib
import math
import subprocess
import sys

import numpy as np
import pytest

from talus import bench
from talus.dem import (FrictMat, ForceResetter, InsertionSortCollider, InteractionLoop, Ip2_FrictMat_FrictMat_FrictPhys,
                       Ip2_FrictMat_FrictMat_MindlinPhys, Law2_ScGeom_FrictPhys_CundallStrack,
                       Law2_ScGeom_MindlinPhys_Mindlin, NewtonIntegrator, RotationEngine, Scene, facet, sphere)

STEPS = 600


def drum(law, track):
    """A closed drum of 96 facets (axis z) turning at 3 rad/s, its lower part a lattice of
    spheres closer than their diameters, those at the rim overlapping the facets, falling onto
    the drum's faces, edges and the end caps' vertices."""
    rng = np.random.default_rng(3)
    S = Scene()
    material = S.materials.append(FrictMat(young=1e6, poisson=0.3, frictionAngle=0.5, density=2600))
    radius, length, segments, r = 0.1, 0.06, 24, 0.005
    rim = [(radius * math.cos(2 * math.pi * s / segments), radius * math.sin(2 * math.pi * s / segments))
           for s in range(segments + 1)]
    lo, hi = -length / 2, length / 2
    triangles = []
    for (x0, y0), (x1, y1) in zip(rim, rim[1:]):
        triangles += [((x0, y0, lo), (x1, y1, lo), (x1, y1, hi)), ((x0, y0, lo), (x1, y1, hi), (x0, y0, hi)),
                      ((0, 0, lo), (x1, y1, lo), (x0, y0, lo)), ((0, 0, hi), (x0, y0, hi), (x1, y1, hi))]
    walls = S.bodies.append([facet(t, material=material) for t in triangles])
    spacing = 1.95 * r
    axis = np.arange(-radius, radius, spacing)
    centres = [(x, y, z) for x in axis for y in axis for z in np.arange(lo + 0.8 * r, hi, spacing)
               if math.hypot(x, y) < radius * math.cos(math.pi / segments) - 0.6 * r and y < 0.3 * radius]
    S.bodies.append([sphere(np.array(c) + rng.uniform(-0.1, 0.1, 3) * r, r * rng.uniform(0.97, 1.0), material=material)
                     for c in centres])
    physics, contact_law = law
    S.engines = [ForceResetter(), InsertionSortCollider(), InteractionLoop([], [physics()], [contact_law()]),
                 RotationEngine(ids=walls, rotationAxis=(0, 0, 1), angularVelocity=3.0, rotateAroundZero=True,
                                zeroPoint=(0, 0, 0)),
                 NewtonIntegrator(damping=0.2, gravity=(0, -9.81, 0))]
    S.dt = 0.5 * 0.97 * r * math.sqrt(2600 / 1e6)
    S.trackEnergy = track
    S.run(STEPS, True)
    return S


LAWS = {"linear": (Ip2_FrictMat_FrictMat_FrictPhys, Law2_ScGeom_FrictPhys_CundallStrack),
        "hertz": (Ip2_FrictMat_FrictMat_MindlinPhys, Law2_ScGeom_MindlinPhys_Mindlin)}
STATES = ("positions", "velocities", "angular_velocities", "forces")


def digest(law, track):
    S = drum(LAWS[law], track)
    facets = sum(1 for c in S.contacts() if S.bodies[c["id1"]].shape.__class__.__name__ == "Facet")
    state = hashlib.sha256(b"".join(np.ascontiguousarray(getattr(S, values)()).tobytes() for values in STATES))
    return f"{S._cpp.contactCount()} {facets} {state.hexdigest()}"


@pytest.mark.parametrize("law", LAWS)
def test_facet_contacts_take_the_batched_geometry_with_the_same_bits(law):
    batched, one_by_one = drum(LAWS[law], False), drum(LAWS[law], True)
    contacts = batched.contacts()
    on_facets = [c for c in contacts if c["id1"] < 96]
    assert len(contacts) > 1000 and len(on_facets) > 150
    # Contacts on the faces, and on the edges or vertices (a normal off the face's).
    off_face = sum(1 for c in on_facets if abs(np.dot(c["normal"], (0, 0, 1))) < 0.999
                   and abs(math.hypot(*c["normal"][:2]) - 1) > 1e-9)
    assert off_face > 0
    for values in STATES:
        assert np.array_equal(getattr(batched, values)(), getattr(one_by_one, values)()), values


def test_one_and_two_threads_give_the_same_bits():
    def run(threads):
        env = {**bench.child_environment(), "OMP_NUM_THREADS": str(threads)}
        done = subprocess.run([sys.executable, __file__, "hertz"], capture_output=True, text=True, env=env, timeout=300)
        assert done.returncode == 0, done.stderr
        return done.stdout.split()
    one, two = run(1), run(2)
    assert int(one[0]) > 1024 and one == two   # over parallelLoopMinimum: the contacts split between the threads


if __name__ == "__main__":
    print(digest(sys.argv[1], False))
