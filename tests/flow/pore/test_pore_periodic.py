"""Periodic pore-scale flow (talus.flow.PeriodicFlowEngine) against Yade's PeriodicFlowEngine on
the same 300-sphere periodic packing (tests/flow/data: the spheres and Yade's results, written by
pore_yade_periodic.py; rerun live when yade is installed), plus the balances that must hold
exactly in a periodic cell."""
import json
import shutil
import subprocess
from pathlib import Path

import numpy as np
import pytest

from talus.flow import FlowEngine, PeriodicFlowEngine

HERE = Path(__file__).resolve().parent
DATA = HERE.parent / "data"
YADE = shutil.which("yade")
CELL = np.array([1.0, 1.0, 1.0])
THRESHOLD = 0.25


def packing():
    a = np.loadtxt(DATA / "pore_periodic_packing.txt")
    return a[:, :3], a[:, 3]


def periodic_flow(g=(0, 1, 0), shift=(0, 0, 0), **kw):
    pos, rad = packing()
    flow = PeriodicFlowEngine(gradP=g, duplicateThreshold=THRESHOLD, **kw)
    flow.triangulate(pos + np.asarray(shift), rad, cellSize=CELL)
    flow.solve()
    return flow


def periodic_part(centres, pressures, g):
    """p - g.x with the mean removed (the level of a periodic field with nothing imposed is
    arbitrary; Yade's and Talus's differ by a constant)."""
    q = np.asarray(pressures) - np.asarray(centres) @ np.asarray(g, dtype=float)
    return q - q.mean()


def compare(ref, flow, g):
    g = np.asarray(g, dtype=float)
    assert flow.nCells() == ref["nCells"]
    k_yade = -np.dot(ref["averageVelocity"], g) / g.dot(g)
    dk = abs(flow.samplePermeability() - k_yade) / k_yade
    # pores in a different periodic frame have p - g.x unchanged: compare the sorted values
    dp = np.abs(np.sort(periodic_part(ref["centers"], ref["pressures"], g)) -
                np.sort(periodic_part(flow.cellCenters, flow.pressures, g))).max()
    f_ref = np.array(ref["fluidForce"])
    f = np.array([flow.fluidForce(i) for i in range(len(f_ref))])
    df = np.abs(f - f_ref).max() / np.abs(f_ref).max()
    return dk, dp, df


def test_against_yade_stored_reference():
    ref = json.loads((DATA / "pore_yade_periodic.json").read_text())
    dk, dp, df = compare(ref, periodic_flow(), (0, 1, 0))
    # the issue asks 1 % on K; the formulas are Yade's, so the numbers agree to round-off
    assert dk < 1e-8
    assert dp < 1e-8
    assert df < 1e-8


@pytest.mark.skipif(YADE is None, reason="yade is not installed")
def test_against_yade_live(tmp_path):
    out = tmp_path / "ref.json"
    g = (0.3, 0.0, -1.0)
    subprocess.run([YADE, "-n", "-x", "pore_yade_periodic.py", str(DATA / "pore_periodic_packing.txt"), str(out),
                    *map(str, CELL), *map(str, g), str(THRESHOLD)], cwd=HERE, check=True, capture_output=True, timeout=120)
    dk, dp, df = compare(json.loads(out.read_text()), periodic_flow(g), g)
    assert dk < 1e-8 and dp < 1e-8 and df < 1e-8


def test_balances():
    flow = periodic_flow()
    # every pore conserves the fluid: sum over its throats of k (p_i - p_j - g . shift) = 0
    pores, periods, k, p = flow.throatPores, flow.throatPeriods, flow.throatConductances, flow.pressures
    q = k * (p[pores[:, 0]] - p[pores[:, 1]] - periods @ (CELL * np.array([0, 1, 0])))
    net = np.zeros(flow.nCells())
    np.add.at(net, pores[:, 0], q)
    np.add.at(net, pores[:, 1], -q)
    # (round-off of the direct solve: 1.2e-12 of the largest throat flux with the nested-dissection
    # ordering, below 1e-12 with AMD's)
    assert np.abs(net).max() < 1e-11 * np.abs(q).max()
    # the solids carry the whole driving gradient: sum of the fluid forces = -gradP * volume
    total = np.sum([flow.fluidForce(i) for i in range(len(packing()[1]))], axis=0)
    assert total == pytest.approx([0, -1, 0], abs=1e-10)
    # the pores tile the cell
    assert flow.cellVolumes.sum() == pytest.approx(CELL.prod(), rel=1e-12)


def test_invariance_and_linearity():
    k = periodic_flow().samplePermeability()
    assert k > 0
    # the same packing translated (other spheres wrapped, other pores chosen as the real ones)
    assert periodic_flow(shift=(0.37, -1.21, 2.5)).samplePermeability() == pytest.approx(k, rel=1e-9)
    assert periodic_flow(g=(0, -3, 0)).samplePermeability() == pytest.approx(k, rel=1e-10)
    assert periodic_flow(viscosity=2.0).samplePermeability() == pytest.approx(k, rel=1e-10)
    # the pressure field is periodic plus gradP . x: a pore's image one cell up is at +1
    flow = periodic_flow()
    x = np.array(flow.cellCenters[7])
    assert flow.getPorePressure(x + [0, 1, 0]) == pytest.approx(flow.getPorePressure(x) + 1.0, abs=1e-12)


def test_against_the_box_engine():
    # the same packing between walls on the cell faces (walls cut the spheres crossing them):
    # the walls add a looser layer along the lateral faces, a fast path for the flow; on this
    # small loose packing (300 spheres, porosity 0.55, the wall layers a seventh of the width)
    # the box K is 1.50 times the periodic one (measured)
    pos, rad = packing()
    box = FlowEngine(bndCondIsPressure=[0, 0, 1, 1, 0, 0], bndCondValue=[0, 0, 1, 0, 0, 0],
                     boundaryUseMaxMin=[0] * 6, wallPosition=[0, 1, 0, 1, 0, 1])
    box.triangulate(pos, rad)
    box.solve()
    ratio = box.samplePermeability(2, 3) / periodic_flow().samplePermeability()
    assert 1.3 < ratio < 1.7


def test_bad_input():
    pos, rad = packing()
    flow = PeriodicFlowEngine(gradP=(0, 1, 0), duplicateThreshold=0.0)
    with pytest.raises(RuntimeError, match="duplicateThreshold"):
        flow.triangulate(pos, rad, cellSize=CELL)
    with pytest.raises(ValueError, match="positive"):
        flow.cellSize = (1, 0, 1)
    with pytest.raises(ValueError, match="gradP is zero"):
        periodic_flow(g=(0, 0, 0)).samplePermeability()


def test_engine_in_a_periodic_scene():
    from talus.dem import ForceResetter, NewtonIntegrator, Scene, sphere
    S = Scene()
    S.periodic = True
    S.cell.hSize = np.diag(CELL)
    pos, rad = packing()
    S.bodies.append([sphere(p, r, fixed=True) for p, r in zip(pos, rad)])
    flow = PeriodicFlowEngine(scene=S, gradP=(0, 0, 2), duplicateThreshold=THRESHOLD)
    S.engines = [ForceResetter(), flow, NewtonIntegrator()]
    S.dt = 1e-6
    S.step()
    f = np.asarray(S.forces())
    assert f.sum(axis=0) == pytest.approx([0, 0, -2.0], abs=1e-9)
    ref = periodic_flow(g=(0, 0, 2))
    assert flow.samplePermeability() == pytest.approx(ref.samplePermeability(), rel=1e-9)
    with pytest.raises(ValueError, match="not periodic"):
        S2 = Scene()
        S2.bodies.append([sphere(p, r, fixed=True) for p, r in zip(pos, rad)])
        S2.engines = [ForceResetter(), PeriodicFlowEngine(scene=S2), NewtonIntegrator()]
        S2.dt = 1e-6
        S2.step()
