"""Pore-scale flow case: fluid injection below a granular layer (the seed's tutorial 2.6.7),
periodic along x and z, DEM and PeriodicFlowEngine coupled through the particle exchange interface.

Run:      build/bin/talus run cases/pore/flow_injection.py [--quick] [--results DIR]
Set-up:   as the tutorial: periodic cell width x 3 height x depth (0.8 x 3 x 0.4), a seeded
          periodic cloud (porosity 0.8, rRelFuzz 0.002, seed 2) above a fixed bottom wall at
          y = height (a top wall at 2 height + 4 r closes the cell as the tutorial's), deposited under gravity (FrictMat E 4e5, friction 10 deg, density
          1600; damping 0.4 for the deposition, 0 afterwards as the tutorial). Then the fluid:
          talus.flow.PeriodicFlowEngine (viscosity 0.01, boundaries ymin and ymax at the layer's
          extremes with pressure 0 at ymax, x and z periodic, remeshing every 40 steps), the
          injected flux shared among the pores touching the bottom boundary whose centre lies in
          the central slot |x - width/2| < aperture/2 (aperture 0.05 width; re-imposed after each
          remesh by blockHook, as the tutorial), ramped linearly from 0 to q_max. q_max is set
          from the fixed layer's resistance R (inlet pressure per unit flux, static solve) so that
          R q_max is 3 times the layer's weight per unit area: the pressure lifts the grains above
          the slot long before the end of the ramp.
Checked:  flow.injection.linear: slope of the inlet pressure against the flux over the first 15 %
          of the ramp (least squares through 0) against R of the fixed layer: |slope / R - 1| <=
          0.05 (at small flux the grains do not move: the coupled response must be the rigid one);
          flow.injection.sublinear: inlet pressure at the end over R q_max (<= 0.7: the layer
          yields, the response bends below the linear one);
          flow.injection.yade: R of the same fixed layer in Yade 2023.02a's PeriodicFlowEngine (same
          sphere file, cell, boundaries and injection points), relative difference <= 1 %
          (skipped, no record, without yade).
Produces: the records and chart flow.injection.png (inlet pressure against injected flux, with the
          rigid-layer line R q).
"""
import math
import tempfile
import time
from pathlib import Path

import numpy as np

from talus import results
from talus.dem import (FrictMat, GlobalStiffnessTimeStepper, InsertionSortCollider, InteractionLoop, Matrix3,
                       NewtonIntegrator, O, sphere, unbalancedForce, wall)
from talus import twin
from talus.dem.step.engines import (Bo1_Sphere_Aabb, Bo1_Wall_Aabb, ForceResetter, Ig2_Sphere_Sphere_ScGeom,
                               Ig2_Wall_Sphere_ScGeom, Ip2_FrictMat_FrictMat_FrictPhys,
                               Law2_ScGeom_FrictPhys_CundallStrack)
from talus.dem.packing.pack import SpherePack
from talus.flow import PeriodicFlowEngine

WIDTH, HEIGHT, DEPTH = 0.8, 1.0, 0.4
APERTURE = 0.05 * WIDTH
MU = 0.01
YADE_SCRIPT = Path(__file__).resolve().parents[1] / "yade" / "pore_injection.py"


def deposit(num: int, seed: int):
    """The tutorial's layer: a loose periodic cloud falling on the bottom wall (body 0; body 1 the
    top wall)."""
    O.periodic = True
    O.cell.hSize = Matrix3(WIDTH, 0, 0, 0, 3 * HEIGHT, 0, 0, 0, DEPTH)
    O.materials.append(FrictMat(young=4e5, poisson=0.5, frictionAngle=math.radians(10), density=1600, label="spheres"))
    O.materials.append(FrictMat(young=4e5, poisson=0.5, frictionAngle=math.radians(15), density=1000, label="walls"))
    mean_rad = (WIDTH * HEIGHT * DEPTH * 0.2 / (math.pi * 4 / 3 * num)) ** (1 / 3)
    O.bodies.append(wall(HEIGHT, axis=1, material="walls"))
    O.bodies.append(wall(2 * HEIGHT + 4 * mean_rad, axis=1, material="walls"))
    sp = SpherePack()
    sp.makeCloud((0, HEIGHT + 2 * mean_rad, 0), (WIDTH, 2 * HEIGHT + 2 * mean_rad, DEPTH), -1, 0.002, num,
                 periodic=True, porosity=0.8, seed=seed)
    # appended one by one: toSimulation would make the cell the cloud's box
    O.bodies.append([sphere(c, r, material="spheres") for c, r in sp])
    newton = NewtonIntegrator(damping=0.4, gravity=(0, -9.81, 0))
    O.engines = [ForceResetter(), InsertionSortCollider([Bo1_Sphere_Aabb(), Bo1_Wall_Aabb()]),
                 InteractionLoop([Ig2_Sphere_Sphere_ScGeom(), Ig2_Wall_Sphere_ScGeom()],
                                 [Ip2_FrictMat_FrictMat_FrictPhys()], [Law2_ScGeom_FrictPhys_CundallStrack()]),
                 GlobalStiffnessTimeStepper(timeStepUpdateInterval=100, timestepSafetyCoefficient=0.3),
                 newton]
    O.run(1000, True)
    while unbalancedForce() > 0.01:
        O.run(200, True)
        if O.iter > 200000:
            raise RuntimeError("the deposition did not settle")
    newton.damping = 0.0
    return newton


def spheres():
    ids = [i for i in range(2, len(O.bodies))]
    return ids, np.asarray(O.positions())[ids], np.asarray(O.radii())[ids]


def injection_points(flow):
    """A point inside each pore touching the bottom boundary (2) under the slot (its barycentre,
    as the tutorial's getCellBarycenter)."""
    points = []
    for cell in range(flow.nCells()):
        if 2 in flow.getVertices(cell):
            c = flow.getCellBarycenter(cell)
            if abs(c[0] - WIDTH / 2) < APERTURE / 2:
                points.append(c)
    return points


def make_engine(**kw):
    return PeriodicFlowEngine(viscosity=MU, duplicateThreshold=DEPTH, wallIds=[-1, -1, 0, 1, -1, -1],
                              bndCondIsPressure=[0, 0, 0, 1, 0, 0], **kw)


def rigid_resistance(flux: float = 1.0):
    """Inlet pressure per unit flux of the fixed layer (standalone solve) and the points used."""
    flow = make_engine()
    ids, pos, rad = spheres()
    flow.triangulate(pos, rad, ids, cellSize=(WIDTH, 3 * HEIGHT, DEPTH))
    points = injection_points(flow)
    for p in points:
        flow.imposeFlux(p, -flux / len(points))
    flow.solve()
    return float(np.mean([flow.getPorePressure(p) for p in points])) / flux, points, flow


def main():
    args = results.case_arguments(__doc__).parse_args()
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    case = results.Case("flow.injection", quick=args.quick, folder=args.results)
    num = 400 if args.quick else 2000
    start = time.perf_counter()
    deposit(num, seed=2)
    print(f"deposited {num} spheres in {time.perf_counter() - start:.1f} s ({O.iter} steps, dt {O.dt:.3g} s)")
    r, points, static = rigid_resistance()
    _, pos, rad = spheres()
    weight = 1600 * 9.81 * float(np.sum(4 / 3 * np.pi * rad ** 3)) / (WIDTH * DEPTH)
    q_max = 3 * weight / r
    print(f"rigid layer: R = {r:.4g} Pa s/m3 over {len(points)} injection pores, layer weight {weight:.4g} Pa, "
          f"q_max = {q_max:.4g} m3/s")

    yade = None
    if twin.yade_available():
        with tempfile.TemporaryDirectory() as tmp:
            path = Path(tmp) / "layer.txt"
            np.savetxt(path, np.c_[pos, rad], fmt="%.17g")
            yade = twin.run(YADE_SCRIPT, {"packing": str(path), "cell": [WIDTH, 3 * HEIGHT, DEPTH], "points": points,
                                          "flux": 1.0, "viscosity": MU, "threshold": DEPTH}, "yade")

    flow = make_engine(meshUpdateInterval=40)
    state = {"q": 0.0, "points": []}

    def impose():
        state["points"] = injection_points(flow)
        flow.clearImposedFlux()
        for p in state["points"]:
            flow.imposeFlux(p, -state["q"] / len(state["points"]))

    flow.blockHook = impose
    engines = list(O.engines)
    engines.insert(4, flow)  # after the time stepper, before the integrator (as the tutorial)
    O.engines = engines
    ramp_steps = 1500 if args.quick else 6000
    chunk = 20
    series = {"q": [], "p": [], "t": []}
    t0 = O.time
    for k in range(ramp_steps // chunk):
        state["q"] = q_max * (k + 0.5) / (ramp_steps // chunk)
        if state["points"]:
            flow.clearImposedFlux()
            for p in state["points"]:
                flow.imposeFlux(p, -state["q"] / len(state["points"]))
        O.run(chunk, True)
        series["q"].append(state["q"])
        series["p"].append(float(np.mean([flow.getPorePressure(p) for p in state["points"]])))
        series["t"].append(O.time - t0)
    q, p = np.array(series["q"]), np.array(series["p"])
    early = q <= 0.15 * q_max
    slope = float(np.dot(q[early], p[early]) / np.dot(q[early], q[early]))
    case.record("|slope of inlet pressure vs flux over the first 15 % of the ramp / R_rigid - 1|", abs(slope / r - 1),
                "R of the same fixed layer (static solve): at small flux the grains do not move", 0.05,
                suffix="linear", slope=slope, R=r, q_max=q_max, weight=weight, spheres=num,
                steps=ramp_steps, remeshes=list(flow.remeshCount()))
    end = float(np.mean(p[-3:]) / (r * q[-3:].mean()))
    case.record("inlet pressure at the end of the ramp / R_rigid q", end,
                "the rigid layer's linear response (the layer yields: sublinear)", 0.7, suffix="sublinear",
                q=series["q"], p=series["p"], t=series["t"])
    print(f"slope {slope:.4g} against R {r:.4g} ({slope / r - 1:+.2%}); end of ramp p / (R q) = {end:.3f}")
    if yade is not None:
        r_yade = float(np.mean(yade["pressures"]))
        case.record("relative difference of the fixed layer's R from Yade's", abs(r / r_yade - 1),
                    "Yade 2023.02a PeriodicFlowEngine, same layer, boundaries and injection points", 0.01,
                    suffix="yade", R=r, R_yade=r_yade, nCells=static.nCells(), nCells_yade=yade["nCells"])
        print(f"Yade: R {r_yade:.6g} ({r / r_yade - 1:+.2e}), {yade['nCells']} pores against {static.nCells()}")

    fig, ax = plt.subplots(figsize=(6, 4.5))
    ax.plot(q, p, "o-", ms=3, label="Talus, coupled DEM + PeriodicFlowEngine")
    ax.plot([0, q_max], [0, r * q_max], "k--", label="rigid layer, R q")
    ax.axhline(weight, color="grey", lw=0.8, label="layer weight per unit area")
    ax.set_xlabel("injected flux q (m$^3$/s)")
    ax.set_ylabel("inlet pressure (Pa)")
    ax.set_title(f"Fluid injection below a granular layer ({num} spheres, periodic x, z)")
    ax.legend(fontsize=8)
    case.save_chart(fig)


if __name__ == "__main__":
    main()
