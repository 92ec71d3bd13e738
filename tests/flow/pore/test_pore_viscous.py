"""Viscous forces between neighbouring spheres (talus.flow.FlowEngine's viscousShear,
shearLubrication, normalLubrication) against Yade's FlowEngine with the same options on the same
400-sphere packing and velocities (tests/flow/data/pore_yade_viscous.json, written by
pore_yade_viscous.py; rerun live when yade is installed), and against the closed forms on a
body-centred cubic lattice, whose power-diagram faces are known."""
import json
import math
import shutil
import subprocess
from pathlib import Path

import numpy as np
import pytest

from talus.flow import FlowEngine

HERE = Path(__file__).resolve().parent
DATA = HERE.parent / "data"
YADE = shutil.which("yade")
OPTIONS = {
    "viscousShear": dict(viscousShear=True),
    "shearLubrication": dict(shearLubrication=True),
    "normalLubrication": dict(normalLubrication=True),
    "normalLubricationNoSpring": dict(normalLubrication=True, stiffness=0),
}
QUANTITIES = ("shearLubForce", "shearLubTorque", "normalLubForce")


def packing():
    a = np.loadtxt(DATA / "pore_packing.txt")
    return a[:, :3], a[:, 3], np.arange(6, 6 + len(a))  # ids as in Yade: after the six walls


def differences(ref, order=True):
    """Largest difference to Yade of each quantity after each of the two steps, relative to the
    largest value Yade gives it (absolute where Yade gives zero everywhere); `order`:
    yadeInsertionOrder."""
    pos, rad, ids = packing()
    out = {}
    for name, options in OPTIONS.items():
        flow = FlowEngine(bndCondIsPressure=[0, 0, 1, 1, 0, 0], bndCondValue=[0, 0, 1, 0, 0, 0],
                          viscosity=ref["viscosity"], yadeInsertionOrder=order, **options)
        flow.triangulate(pos, rad, ids)
        flow.solve()
        for step, yade in enumerate(ref[name]):
            flow.computeViscousForces(ref["velocities"], ref["angularVelocities"], ref["dt"])
            for q in QUANTITIES:
                talus = np.array([getattr(flow, q)(int(i)) for i in ids])
                expected = np.array(yade[q])
                scale = np.abs(expected).max() or 1.0
                out[(name, step, q)] = np.abs(talus - expected).max() / scale
    return out


def test_same_viscous_forces_as_yade_stored():
    ref = json.load(open(DATA / "pore_yade_viscous.json"))
    # The same formulas on the same triangulation. With Yade's insertion order (the same pore
    # centres to the bit) measured: shear lubrication 7.5e-14, normal lubrication 1.4e-13 (with
    # and without the spring, both steps); viscous shear 7.5e-11, its face areas being fans from
    # another first pore around a polygon whose wall-pore corners carry round-off.
    d = differences(ref)
    assert max(d.values()) < 1e-9, {k: v for k, v in d.items() if v >= 1e-9}
    assert max(v for k, v in d.items() if k[0] != "viscousShear") < 1e-12
    # The sorted insertion (yadeInsertionOrder=False) computes the wall pores' centres in another vertex order
    # (their round-off is ~6e-5 of the box, see docs/flow.md): the faces of the pairs next to the
    # walls move, the lubrication forces do not (measured: viscous shear 5.1e-5, others 1.4e-13).
    d = differences(ref, order=False)
    assert max(d.values()) < 1e-4
    assert max(v for k, v in d.items() if k[0] != "viscousShear") < 1e-12


@pytest.mark.skipif(YADE is None, reason="yade not installed")
def test_same_viscous_forces_as_yade_live(tmp_path):
    out = tmp_path / "viscous.json"
    subprocess.run([YADE, "-n", "-x", "pore_yade_viscous.py", str(DATA / "pore_packing.txt"), str(out)],
                   cwd=HERE, check=True, capture_output=True, timeout=300)
    assert max(differences(json.load(open(out))).values()) < 1e-9


def bcc(cells=4, a=1.0, r=0.3):
    """Body-centred cubic lattice: corners and centres of cells^3 cubes of side a."""
    g = np.arange(cells + 1) * a
    corners = np.array([(x, y, z) for x in g for y in g for z in g])
    h = g[:-1] + a / 2
    centres = np.array([(x, y, z) for x in h for y in h for z in h])
    pos = np.vstack([corners, centres])
    return pos, np.full(len(pos), r)


def test_power_faces_of_a_bcc_lattice_are_its_truncated_octahedra_faces():
    # The Voronoi cell of a BCC lattice (equal spheres: power = Voronoi) is a truncated
    # octahedron of edge a / (2 sqrt 2): hexagons a^2 3 sqrt(3) / 16 towards the 8 nearest
    # neighbours (distance a sqrt(3) / 2), squares a^2 / 8 towards the 6 next (distance a).
    a = 1.0
    pos, rad = bcc(a=a)
    flow = FlowEngine(viscousShear=True, bndCondIsPressure=[0, 0, 1, 1, 0, 0])
    flow.triangulate(pos, rad)
    flow.computeViscousForces(np.zeros_like(pos), np.zeros_like(pos))
    pairs, areas = flow._flow.spherePairs()
    inner = np.all((pos > 0.9 * a) & (pos < 3.1 * a), axis=1)  # two layers of lattice inside
    found = {"hexagon": [], "square": []}
    for (i, j), area in zip(pairs, areas):
        if inner[i] and inner[j]:
            d = np.linalg.norm(pos[i] - pos[j])
            if abs(d - a * math.sqrt(3) / 2) < 1e-9:
                found["hexagon"].append(area)
            elif abs(d - a) < 1e-9:
                found["square"].append(area)
    assert len(found["hexagon"]) > 20 and len(found["square"]) > 10
    assert np.allclose(found["hexagon"], 3 * math.sqrt(3) / 16 * a * a, rtol=1e-9)
    assert np.allclose(found["square"], a * a / 8, rtol=1e-9)


def test_viscous_shear_and_normal_lubrication_of_one_moving_sphere():
    # One sphere of the lattice moves; each neighbour across a face is dragged along the
    # tangential part of its velocity by mu v_t A / R_h, and pushed away (approach) or pulled
    # (separation) by 3 pi R^2 mu v_n / (2 h); nothing moves when all move together.
    a, r, mu, eps = 1.0, 0.3, 0.7, 1e-5
    pos, rad = bcc(a=a, r=r)
    mover = int(np.argmin(np.linalg.norm(pos - 2 * a, axis=1)))  # the corner at (2, 2, 2)
    v = np.array([0.3, -0.2, 0.5])
    vel = np.zeros_like(pos)
    vel[mover] = v
    flow = FlowEngine(viscousShear=True, normalLubrication=True, stiffness=0, viscosity=mu, eps=eps,
                      bndCondIsPressure=[0, 0, 1, 1, 0, 0])
    flow.triangulate(pos, rad)
    flow.computeViscousForces(vel, np.zeros_like(pos))
    hexagon = 3 * math.sqrt(3) / 16 * a * a
    neighbours = [j for j in range(len(pos)) if abs(np.linalg.norm(pos[j] - pos[mover]) - a * math.sqrt(3) / 2) < 1e-9]
    assert len(neighbours) == 8
    for j in neighbours:
        n = (pos[j] - pos[mover]) / np.linalg.norm(pos[j] - pos[mover])
        gap = a * math.sqrt(3) / 2 - 2 * r
        shear = mu * (v - n * n.dot(v)) * hexagon / (gap + 0.45 * r)
        assert np.allclose(flow.shearLubForce(j), shear, rtol=1e-9, atol=0)
        # approach (v . n > 0) pushes the neighbour away along n
        normal = 1.5 * math.pi * r * r * mu * v.dot(n) / (gap + 2 * eps * r) * n
        assert np.allclose(flow.normalLubForce(j), normal, rtol=1e-9, atol=0)
    flow.computeViscousForces(np.tile(v, (len(pos), 1)), np.zeros_like(pos))
    assert np.abs([flow.shearLubForce(j) for j in range(len(pos))]).max() == 0
    assert np.abs([flow.normalLubForce(j) for j in range(len(pos))]).max() == 0


def test_engine_adds_the_viscous_forces_and_torques_from_the_body_velocities():
    from talus.dem import ForceResetter, Scene, sphere
    pos, rad, _ = packing()
    ref = json.load(open(DATA / "pore_yade_viscous.json"))
    S = Scene()
    ids = S.bodies.append([sphere(p, r, fixed=True) for p, r in zip(pos, rad)])
    S.velocities()[ids] = ref["velocities"]
    S.angular_velocities()[ids] = ref["angularVelocities"]
    options = dict(bndCondIsPressure=[0, 0, 1, 1, 0, 0], bndCondValue=[0, 0, 1, 0, 0, 0], viscousShear=True,
                   normalLubrication=True)
    flow = FlowEngine(scene=S, **options)
    S.engines = [ForceResetter(), flow]  # no integrator: the spheres keep positions and velocities
    S.dt = ref["dt"]
    alone = FlowEngine(**options)
    alone.triangulate(pos, rad, ids)
    alone.solve()
    for _ in range(2):  # the second step starts from the springs' loads of the first
        S.step()
        alone.computeViscousForces(ref["velocities"], ref["angularVelocities"], ref["dt"])
        for i in ids[:50]:
            viscous = np.add(alone.shearLubForce(i), alone.normalLubForce(i))
            assert np.allclose(S.forces()[i], np.add(alone.fluidForce(i), viscous), rtol=1e-12, atol=1e-15)
            assert np.allclose(S.torques()[i], alone.shearLubTorque(i), rtol=1e-12, atol=1e-15)


def test_bad_input_of_the_viscous_forces():
    pos, rad, ids = packing()
    flow = FlowEngine(bndCondIsPressure=[0, 0, 1, 1, 0, 0])
    flow.triangulate(pos, rad, ids)
    zero = np.zeros_like(pos)
    with pytest.raises(ValueError, match="viscousShear, shearLubrication or normalLubrication"):
        flow.computeViscousForces(zero, zero)
    flow.normalLubrication = True
    with pytest.raises(ValueError, match="time step"):   # the spring (stiffness > 0) needs dt
        flow.computeViscousForces(zero, zero)
    with pytest.raises(ValueError, match="velocities"):
        flow.computeViscousForces(zero[:-1], zero, 1e-4)
    bad = zero.copy()
    bad[3, 1] = np.nan
    with pytest.raises(ValueError, match="body 9"):
        flow.computeViscousForces(bad, zero, 1e-4)
